// SPDX-License-Identifier: MIT
/* bvh_fixtures_reference.c: the brute-force reference the BVH tests compare the device's traversal
 * with (bvh_fixtures.h): the watertight test of cl/geometry/intersect_triangle.cl, operation for
 * operation, over every triangle in file order (C runs this loop some 30 times faster than PoCL).
 * ISO C compiles without fma contraction, so the explicit fmaf calls round exactly as the
 * kernel's. One step is written the other way round on purpose: the kernel permutes (vertex -
 * origin), this subtracts the permuted origin from the permuted vertex; the two are exactly equal,
 * and the bit-for-bit comparisons hold the kernel to that. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh_fixtures.h"

/* Two closest hits agree: the same triangle, or ties at the same distance (1e-6 relative). */
static bool same_closest(float4 a, float4 b)
{
    if (hit_prim(a) == hit_prim(b))
        return hit_prim(a) == HIT_NONE || fabsf(a.s[0] - b.s[0]) <= 1e-6f * fabsf(b.s[0]);
    return hit_prim(a) != HIT_NONE && hit_prim(b) != HIT_NONE &&
           fabsf(a.s[0] - b.s[0]) <= 1e-6f * fmaxf(fabsf(a.s[0]), fabsf(b.s[0]));
}

typedef struct {
    int axis_z;
    float origin[3], shear[3];
} RefRay;

static void ref_permute(const float v[3], int axis_z, float out[3])
{
    out[0] = v[(axis_z + 1) % 3];
    out[1] = v[(axis_z + 2) % 3];
    out[2] = v[axis_z];
}

static RefRay ref_ray(const float origin[3], const float dir[3])
{
    RefRay ray;
    float a[3] = {fabsf(dir[0]), fabsf(dir[1]), fabsf(dir[2])}, d[3];
    ray.axis_z = a[0] >= a[1] ? (a[0] >= a[2] ? 0 : 2) : (a[1] >= a[2] ? 1 : 2);
    ref_permute(dir, ray.axis_z, d);
    ref_permute(origin, ray.axis_z, ray.origin);
    ray.shear[0] = d[0] / d[2];
    ray.shear[1] = d[1] / d[2];
    ray.shear[2] = 1.0f / d[2];
    return ray;
}

static float ref_difference_of_products(float a, float b, float c, float d)
{
    float cd = c * d;
    float cd_error = fmaf(-c, d, cd);
    return fmaf(a, b, -cd) + cd_error;
}

static void ref_shear_vertex(const RefRay *ray, const float4 *vertex, float out[3])
{
    float p[3];
    ref_permute(vertex->s, ray->axis_z, p);
    for (int k = 0; k < 3; k++)
        p[k] -= ray->origin[k];
    out[0] = fmaf(-ray->shear[0], p[2], p[0]);
    out[1] = fmaf(-ray->shear[1], p[2], p[1]);
    out[2] = ray->shear[2] * p[2];
}

static bool ref_intersect(const RefRay *ray, const float4 *v0, const float4 *v1, const float4 *v2,
                          float tmin, float tmax, float *t_out, float *u_out, float *v_out)
{
    float a[3], b[3], c[3];
    ref_shear_vertex(ray, v0, a);
    ref_shear_vertex(ray, v1, b);
    ref_shear_vertex(ray, v2, c);
    float w0 = ref_difference_of_products(c[0], b[1], c[1], b[0]);
    float w1 = ref_difference_of_products(a[0], c[1], a[1], c[0]);
    float w2 = ref_difference_of_products(b[0], a[1], b[1], a[0]);
    if ((w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) && (w0 > 0.0f || w1 > 0.0f || w2 > 0.0f))
        return false;
    float det = w0 + w1 + w2;
    if (det == 0.0f)
        return false;
    float inv_det = 1.0f / det;
    float t = fmaf(w0, a[2], fmaf(w1, b[2], w2 * c[2])) * inv_det;
    if (!(t >= tmin && t < tmax))
        return false;
    *t_out = t;
    *u_out = w1 * inv_det;
    *v_out = w2 * inv_det;
    return true;
}

/* (Comparisons, not fmaxf: that is a libm call in the hottest loop of the test.) */
static inline float max_abs3(float x, float y, float z)
{
    float ax = fabsf(x), ay = fabsf(y), az = fabsf(z);
    float m = ax > ay ? ax : ay;
    return m > az ? m : az;
}

/* Closest hit over every triangle. A bounding-sphere test skips triangles whose sphere the ray's
 * line passes far from; it is conservative (distance >= |w x d|_inf / (sqrt(3) |d|_inf), and a
 * margin of 1e-5 of the distance dwarfs either test's rounding). */
float4 brute_force_closest(const TraceScene *scene, const Ray *r)
{
    const float *o = r->origin.s, *d = r->dir.s;
    RefRay ray = ref_ray(o, d);
    float line_scale = 1.7320509f * max_abs3(d[0], d[1], d[2]);
    float best_t = r->dir.s[3], best_u = 0.0f, best_v = 0.0f;
    uint32_t best = HIT_NONE;
    const TestMesh *mesh = &scene->mesh;
    for (uint32_t k = 0; k < mesh->num_triangles; k++) {
        const float *sphere = scene->spheres[k].s;
        float w[3] = {sphere[0] - o[0], sphere[1] - o[1], sphere[2] - o[2]};
        float reach = (sphere[3] + 1e-5f * max_abs3(w[0], w[1], w[2])) * line_scale;
        if (max_abs3(w[1] * d[2] - w[2] * d[1], w[2] * d[0] - w[0] * d[2],
                     w[0] * d[1] - w[1] * d[0]) > reach)
            continue;
        const uint4 v = mesh->triangles[k].v;
        float t, u, bv;
        if (ref_intersect(&ray, &mesh->positions[v.s[0]], &mesh->positions[v.s[1]],
                          &mesh->positions[v.s[2]], r->origin.s[3], best_t, &t, &u, &bv)) {
            best_t = t;
            best_u = u;
            best_v = bv;
            best = k;
        }
    }
    float4 hit = vec(best_t, best_u, best_v, 0.0f);
    memcpy(&hit.s[3], &best, sizeof best);
    return hit;
}

static void log_mismatch(uint32_t *count, const char *name, const char *what, uint32_t i,
                         const Ray *ray, float4 got, float4 want)
{
    if ((*count)++ < 5)
        cr_log_error("%s: %s, ray %u o=(%g %g %g) d=(%g %g %g) t=[%g %g): BVH prim %d t %.9g, "
                     "reference prim %d t %.9g",
                     name, what, i, ray->origin.s[0], ray->origin.s[1], ray->origin.s[2],
                     ray->dir.s[0], ray->dir.s[1], ray->dir.s[2], ray->origin.s[3], ray->dir.s[3],
                     (int)hit_prim(got), got.s[0], (int)hit_prim(want), want.s[0]);
}

uint32_t check_against_brute_force(TraceScene *scene, const Ray *rays, uint32_t n, const char *name)
{
    float4 *hits = malloc(n * sizeof *hits), *reference = malloc(n * sizeof *reference);
    cl_uint *any = malloc(n * sizeof *any);
    trace(scene, "bvh_test_trace_closest", rays, n, hits);
    for (uint32_t i = 0; i < n; i++)
        reference[i] = brute_force_closest(scene, &rays[i]);
    trace(scene, "bvh_test_trace_any", rays, n, any);
    uint32_t closest_bad = 0, any_bad = 0, num_hits = 0;
    Ray *cut = malloc(2 * n * sizeof *cut);
    for (uint32_t i = 0; i < n; i++) {
        if (!same_closest(hits[i], reference[i]))
            log_mismatch(&closest_bad, name, "closest hit differs", i, &rays[i], hits[i], reference[i]);
        bool hit = hit_prim(hits[i]) != HIT_NONE;
        if (any[i] != (cl_uint)hit)
            log_mismatch(&any_bad, name, "any hit differs", i, &rays[i], hits[i], reference[i]);
        if (hit) {
            cut[2 * num_hits] = cut[2 * num_hits + 1] = rays[i];
            cut[2 * num_hits].dir.s[3] = hits[i].s[0];
            cut[2 * num_hits + 1].dir.s[3] = nextafterf(hits[i].s[0], INFINITY);
            num_hits++;
        }
    }
    uint32_t cut_bad = 0;
    if (num_hits > 0) {
        cl_uint *cut_any = malloc(2 * num_hits * sizeof *cut_any);
        trace(scene, "bvh_test_trace_any", cut, 2 * num_hits, cut_any);
        for (uint32_t i = 0; i < num_hits; i++)
            if (cut_any[2 * i] != 0 || cut_any[2 * i + 1] != 1) {
                float4 none = vec(cut[2 * i].dir.s[3], 0, 0, 0);
                log_mismatch(&cut_bad, name, "any hit with tmax at the closest hit", i, &cut[2 * i],
                             vec((float)cut_any[2 * i], 0, 0, 0), none);
            }
        free(cut_any);
    }
    cr_expect_eq(closest_bad, 0, "%s: %u of %u closest hits differ from brute force", name,
                 closest_bad, n);
    cr_expect_eq(any_bad, 0, "%s: %u of %u any hits differ", name, any_bad, n);
    cr_expect_eq(cut_bad, 0, "%s: %u of %u any hits wrong at tmax = closest t", name, cut_bad,
                 num_hits);
    free(hits);
    free(reference);
    free(any);
    free(cut);
    return num_hits;
}
