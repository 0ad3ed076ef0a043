// SPDX-License-Identifier: MIT
/* Two-level traversal (host/accel/tlas.c, trace_scene_bvh in cl/geometry/bvh_traverse*.cl) on the
 * test device, in the layout PT_BVH_WIDTH / PT_BVH_QUANTIZED choose: closest and any hits through
 * TLAS + BLAS equal the brute-force loop over every instance's triangles, bit for bit, for random
 * rays into overlapping, mirrored, composed ("nested") and moving instances at random times; the
 * hits are the world-space truth (a double-precision host reference over transformed triangles);
 * and two identical instances in one place always report the lower index.
 * (test_accel_instances_bvh_tlas.c: the TLAS's boxes in every layout.) */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/scene_bvh.h"
#include "base/transform.h"
#include "bvh_fixtures_instances.h"
#include "support.h"

/* The SceneBvh with the given levels (BVH_FLAT: static instances only) and the device's
 * Instance / InstanceMotion records. */
static void build_scene_bvh(InstancedScene *s, SceneBvh *bvh, int width, bool quantized,
                            BvhLevels levels, Instance *instances, InstanceMotion *motions)
{
    BvhInstance boxes[MAX_INSTANCES];
    for (int k = 0; k < 3; k++)
        s->lo[k] = INFINITY, s->hi[k] = -INFINITY;
    uint32_t moving = 0;
    for (uint32_t i = 0; i < s->num_instances; i++) {
        const TestInstance *in = &s->inst[i];
        boxes[i].mesh = in->mesh;
        boxes[i].to_world = in->to_world;
        world_box(s, in, boxes[i].lo, boxes[i].hi);
        for (int k = 0; k < 3; k++)
            s->lo[k] = fminf(s->lo[k], boxes[i].lo[k]), s->hi[k] = fmaxf(s->hi[k], boxes[i].hi[k]);
        Affine inverse;
        cr_assert(affine_invert(&in->to_world, &inverse));
        affine_to_rows(&in->to_world, instances[i].to_world);
        affine_to_rows(&inverse, instances[i].to_object);
        instances[i].motion = INSTANCE_STATIC;
        if (in->moving) {
            InstanceMotion *m = &motions[moving];
            memset(m, 0, sizeof *m);
            for (int key = 0; key < 2; key++) {
                for (int k = 0; k < 3; k++) {
                    m->translation[key].s[k] = (float)in->motion[key].t[k];
                    for (int j = 0; j < 3; j++)
                        m->scale[3 * key + k].s[j] = (float)in->motion[key].s[k][j];
                }
                for (int k = 0; k < 4; k++)
                    m->rotation[key].s[k] = (float)in->motion[key].q[k];
            }
            instances[i].motion = moving++;
        }
    }
    scene_bvh_build(bvh, s->all.positions, s->all.triangles, s->meshes, s->num_meshes, boxes,
                    s->num_instances, width, quantized, levels);
    for (uint32_t i = 0; i < s->num_instances; i++) {
        instances[i].blas_root = bvh->blas_root[s->inst[i].mesh];
        instances[i].first_prim = bvh->first_prim[s->inst[i].mesh];
        instances[i].num_prims = bvh->num_mesh_prims[s->inst[i].mesh];
    }
}

typedef struct {
    float4 *hits;       /* per mode and ray: t, u, v, prim */
    uint32_t *instance; /* per mode and ray */
} Traces;

/* Every ray in the four modes of bvh_test_scene_trace, or bvh_test_flat_trace for a flat BVH
 * (closest, any, brute closest, brute any). */
static Traces trace_all(InstancedScene *s, const float4 *rays, const float *times, uint32_t n,
                        BvhLevels levels)
{
    Device *dev = test_device();
    SceneBvh bvh;
    Instance instances[MAX_INSTANCES + 1];
    InstanceMotion motions[MAX_INSTANCES];
    memset(instances, 0, sizeof instances);
    build_scene_bvh(s, &bvh, dev->bvh_width, dev->bvh_quantized, levels, instances, motions);
    bool flat = levels == BVH_FLAT;
    cr_assert(!flat || bvh.num_flat_prims > 0, "a flat BVH without its (instance, triangle) pairs");
    Error err = {0};
    cl_mem nodes = device_buffer(dev, "nodes", CL_MEM_READ_ONLY, bvh.num_nodes * bvh.node_size, bvh.nodes, &err);
    cl_mem prims = device_buffer(dev, "prims", CL_MEM_READ_ONLY, bvh.num_prims * bvh.prim_size, bvh.prims, &err);
    cl_mem inst = flat ? device_buffer(dev, "flat prims", CL_MEM_READ_ONLY,
                                       bvh.num_flat_prims * 2 * sizeof(cl_uint), bvh.flat_prims, &err)
                       : device_buffer(dev, "instances", CL_MEM_READ_ONLY,
                                       (s->num_instances + 1) * sizeof(Instance), instances, &err);
    cl_mem mot = device_buffer(dev, "motions", CL_MEM_READ_ONLY, sizeof motions, motions, &err);
    cl_mem ray_buf = device_buffer(dev, "rays", CL_MEM_READ_ONLY, 2 * n * sizeof(float4), rays, &err);
    cl_mem time_buf = device_buffer(dev, "times", CL_MEM_READ_ONLY, n * sizeof(float), times, &err);
    cl_mem hit_buf = device_buffer(dev, "hits", CL_MEM_WRITE_ONLY, n * sizeof(float4), NULL, &err);
    cl_mem inst_buf = device_buffer(dev, "hit instances", CL_MEM_WRITE_ONLY, n * sizeof(cl_uint), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    Traces out = {malloc(4 * n * sizeof(float4)), malloc(4 * n * sizeof(uint32_t))};
    cl_kernel kernel = device_kernel(dev, flat ? "bvh_test_flat_trace" : "bvh_test_scene_trace");
    for (cl_uint mode = 0; mode < 4; mode++) {
        cl_uint arg = 0, num_instances = s->num_instances, num_rays = n, num_prims = bvh.num_prims;
        KERNEL_ARG(kernel, arg++, nodes);
        KERNEL_ARG(kernel, arg++, prims);
        KERNEL_ARG(kernel, arg++, inst);
        if (flat) {
            KERNEL_ARG(kernel, arg++, num_prims);
        } else {
            KERNEL_ARG(kernel, arg++, mot);
            KERNEL_ARG(kernel, arg++, num_instances);
        }
        KERNEL_ARG(kernel, arg++, ray_buf);
        if (!flat)
            KERNEL_ARG(kernel, arg++, time_buf);
        KERNEL_ARG(kernel, arg++, num_rays);
        KERNEL_ARG(kernel, arg++, mode);
        KERNEL_ARG(kernel, arg++, hit_buf);
        KERNEL_ARG(kernel, arg++, inst_buf);
        device_run(dev, kernel, n, 0, NULL);
        device_read(dev, hit_buf, 0, n * sizeof(float4), out.hits + mode * n);
        device_read(dev, inst_buf, 0, n * sizeof(cl_uint), out.instance + mode * n);
    }
    clReleaseKernel(kernel);
    cl_mem bufs[] = {nodes, prims, inst, mot, ray_buf, time_buf, hit_buf, inst_buf};
    for (size_t i = 0; i < sizeof bufs / sizeof *bufs; i++)
        clReleaseMemObject(bufs[i]);
    scene_bvh_free(&bvh);
    test_device_release(dev);
    return out;
}

static uint32_t prim_of(float4 hit)
{
    uint32_t prim;
    memcpy(&prim, &hit.s[3], sizeof prim);
    return prim;
}

/* Rays from a sphere around the instances toward points among them, and from points among them
 * in random directions; a few with a finite [tmin, tmax). */
static float4 *random_rays(const InstancedScene *s, uint32_t n, uint64_t seed, float *times)
{
    float4 *rays = malloc(2 * n * sizeof *rays);
    uint64_t rng = seed;
    double center[3], radius = 0.0;
    for (int k = 0; k < 3; k++) {
        center[k] = 0.5 * (s->lo[k] + s->hi[k]);
        radius += 0.25 * (s->hi[k] - s->lo[k]) * (s->hi[k] - s->lo[k]);
    }
    radius = sqrt(radius);
    for (uint32_t i = 0; i < n; i++) {
        double target[3], origin[3], dir[3], len = 0.0;
        for (int k = 0; k < 3; k++)
            target[k] = s->lo[k] + (s->hi[k] - s->lo[k]) * mesh_rng_float(&rng);
        bool outside = mesh_rng_float(&rng) < 0.6f;
        for (int k = 0; k < 3; k++) {
            double u = 2.0 * mesh_rng_float(&rng) - 1.0;
            origin[k] = outside ? center[k] + 1.5 * radius * u : target[k];
            dir[k] = outside ? target[k] - origin[k] : 2.0 * mesh_rng_float(&rng) - 1.0;
            len += dir[k] * dir[k];
        }
        len = sqrt(len);
        float tmin = mesh_rng_float(&rng) < 0.1f ? (float)(radius * mesh_rng_float(&rng)) : 0.0f;
        float tmax = mesh_rng_float(&rng) < 0.1f ? tmin + (float)(radius * mesh_rng_float(&rng)) : INFINITY;
        rays[2 * i] = (float4){{(float)origin[0], (float)origin[1], (float)origin[2], tmin}};
        rays[2 * i + 1] = (float4){{(float)(dir[0] / len), (float)(dir[1] / len), (float)(dir[2] / len), tmax}};
        times[i] = mesh_rng_float(&rng);
    }
    return rays;
}

/* Where a ray meets a world triangle, in double: 1 inside by a margin (*t set), 0 clearly outside
 * (or parallel), -1 too close to an edge to tell at float precision. */
static int world_hit(const double o[3], const double d[3], double p[3][3], double *t)
{
    double e1[3], e2[3], s[3], q[3], h[3];
    for (int k = 0; k < 3; k++)
        e1[k] = p[1][k] - p[0][k], e2[k] = p[2][k] - p[0][k], s[k] = o[k] - p[0][k];
    h[0] = d[1] * e2[2] - d[2] * e2[1], h[1] = d[2] * e2[0] - d[0] * e2[2], h[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    double scale = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]) *
                   sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    if (fabs(det) <= 1e-6 * scale)
        return fabs(det) == 0.0 ? 0 : -1;
    double u = (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]) / det;
    q[0] = s[1] * e1[2] - s[2] * e1[1], q[1] = s[2] * e1[0] - s[0] * e1[2], q[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]) / det;
    *t = (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]) / det;
    const double eps = 1e-4;
    if (u < -eps || v < -eps || u + v > 1.0 + eps)
        return 0;
    return (u > eps && v > eps && u + v < 1.0 - eps) ? 1 : -1;
}

static void world_triangle(const InstancedScene *s, uint32_t instance, uint32_t prim, double time,
                           double p[3][3])
{
    Affine m = instance_at_time(&s->inst[instance], time);
    for (int c = 0; c < 3; c++) {
        const float4 v = s->all.positions[s->all.triangles[prim].v.s[c]];
        double x[3] = {v.s[0], v.s[1], v.s[2]};
        affine_point(&m, x, p[c]);
    }
}

/* The closest hit agrees with the world: its triangle is met near its t, and no triangle of any
 * instance is met clearly in front of it (or, for a miss, anywhere in [tmin, tmax)). */
static bool matches_world(const InstancedScene *s, const float4 ray[2], float time, float4 hit,
                          uint32_t instance)
{
    double o[3] = {ray[0].s[0], ray[0].s[1], ray[0].s[2]}, d[3] = {ray[1].s[0], ray[1].s[1], ray[1].s[2]};
    double tmin = ray[0].s[3], tmax = ray[1].s[3], p[3][3], t;
    uint32_t prim = prim_of(hit);
    double limit = prim == HIT_NONE ? tmax : hit.s[0];
    double tol = 1e-3 * fmax(1.0, fabs(limit));
    if (prim != HIT_NONE) {
        if (instance >= s->num_instances || prim >= s->all.num_triangles)
            return false;
        const BvhMesh *mesh = &s->meshes[s->inst[instance].mesh];
        if (prim < mesh->first_triangle || prim >= mesh->first_triangle + mesh->num_triangles)
            return false;
        world_triangle(s, instance, prim, time, p);
        if (world_hit(o, d, p, &t) == 0 || fabs(t - hit.s[0]) > tol)
            return false;
    }
    for (uint32_t i = 0; i < s->num_instances; i++) {
        const BvhMesh *mesh = &s->meshes[s->inst[i].mesh];
        for (uint32_t q = mesh->first_triangle; q < mesh->first_triangle + mesh->num_triangles; q++) {
            world_triangle(s, i, q, time, p);
            if (world_hit(o, d, p, &t) == 1 && t > tmin + tol && t < limit - tol)
                return false;
        }
    }
    return true;
}

/* Closest and any hits of the walk (two levels, or flat) equal the brute force's, and the
 * world's. */
static void check_scene_levels(InstancedScene *s, uint32_t n, uint64_t seed, const char *name,
                               BvhLevels levels)
{
    SceneBvh probe;
    Instance inst[MAX_INSTANCES];
    InstanceMotion mot[MAX_INSTANCES];
    build_scene_bvh(s, &probe, 2, false, BVH_TWO_LEVEL, inst, mot); /* s->lo, s->hi for the rays */
    scene_bvh_free(&probe);
    float *times = malloc(n * sizeof *times);
    float4 *rays = random_rays(s, n, seed, times);
    if (levels == BVH_FLAT) /* a flat BVH has the instances where they stand */
        for (uint32_t i = 0; i < n; i++)
            times[i] = 0.0f;
    Traces tr = trace_all(s, rays, times, n, levels);
    uint32_t hits = 0, bad_brute = 0, bad_any = 0, bad_world = 0, world_checks = 0;
    for (uint32_t i = 0; i < n; i++) {
        float4 bvh = tr.hits[i], brute = tr.hits[2 * n + i];
        bool hit = prim_of(bvh) != HIT_NONE;
        hits += hit;
        if (memcmp(&bvh, &brute, sizeof bvh) != 0 || (hit && tr.instance[i] != tr.instance[2 * n + i])) {
            if (bad_brute++ < 5)
                cr_log_error("%s ray %u: bvh t %.9g prim %u instance %u, brute force t %.9g prim %u "
                             "instance %u", name, i, bvh.s[0], prim_of(bvh), tr.instance[i], brute.s[0],
                             prim_of(brute), tr.instance[2 * n + i]);
        }
        bool any = prim_of(tr.hits[n + i]) != HIT_NONE, brute_any = prim_of(tr.hits[3 * n + i]) != HIT_NONE;
        if (any != hit || brute_any != hit)
            bad_any++;
        if (i % 4 == 0) { /* the world check is slow: every 4th ray */
            world_checks++;
            if (!matches_world(s, &rays[2 * i], times[i], bvh, tr.instance[i]) && bad_world++ < 5)
                cr_log_error("%s ray %u: hit t %.9g prim %u instance %u is not the world's", name, i,
                             bvh.s[0], prim_of(bvh), tr.instance[i]);
        }
    }
    cr_log_info("%s: %u of %u rays hit", name, hits, n);
    cr_expect(hits > n / 4 && hits < n, "%s: %u of %u rays hit: the rays miss their aim", name, hits, n);
    cr_expect_eq(bad_brute, 0, "%s: %u of %u closest hits differ from the brute force", name, bad_brute, n);
    cr_expect_eq(bad_any, 0, "%s: %u of %u any-hit answers differ from the closest hit", name, bad_any, n);
    cr_expect_eq(bad_world, 0, "%s: %u of %u hits are not the world's", name, bad_world, world_checks);
    free(tr.hits);
    free(tr.instance);
    free(rays);
    free(times);
}

static void check_scene(InstancedScene *s, uint32_t n, uint64_t seed, const char *name)
{
    check_scene_levels(s, n, seed, name, BVH_TWO_LEVEL);
    test_mesh_free(&s->all);
}

Test(instances_bvh, overlapping_mirrored_and_composed_instances_match_brute_force, .timeout = 600)
{
    InstancedScene s = scene_with_meshes();
    uint64_t rng = 11;
    for (uint32_t i = 0; i < 24; i++)
        add_instance(&s, i % 3, random_transform(&rng, i % 3 == 1, 5.0), NULL);
    /* Overlapping copies: the same mesh a little moved, rotated about its own centre. */
    for (uint32_t i = 0; i < 4; i++) {
        Affine nudge = affine_translate(0.05 * i, 0.0, -0.03 * i), r = random_rotation(&rng);
        Affine turned = affine_mul(&s.inst[i].to_world, &r);
        add_instance(&s, s.inst[i].mesh, affine_mul(&nudge, &turned), NULL);
    }
    check_scene_levels(&s, 4000, 21, "static, flat", BVH_FLAT);
    check_scene(&s, 4000, 21, "static");
}

Test(instances_bvh, moving_instances_match_brute_force, .timeout = 600)
{
    InstancedScene s = scene_with_meshes();
    uint64_t rng = 12;
    for (uint32_t i = 0; i < 16; i++) {
        Affine start = random_transform(&rng, i % 5 == 2, 4.0);
        if (i % 2 == 0) {
            add_instance(&s, i % 3, start, NULL);
            continue;
        }
        Affine end = random_transform(&rng, i % 5 == 2, 4.0);
        add_instance(&s, i % 3, start, &end);
    }
    check_scene(&s, 4000, 22, "moving");
}

/* Instances 1 and 2, and 3 and 4, are the same mesh in the same place: every hit on either pair
 * names the lower index, whichever the TLAS presents first (instance 2's box is padded, so that
 * rays enter it before 1's; in the other pair the lower one's is). */
Test(instances_bvh, identical_instances_tie_to_the_lower_index, .timeout = 600)
{
    InstancedScene s = scene_with_meshes();
    uint64_t rng = 13;
    Affine a = random_transform(&rng, false, 2.0), b = random_transform(&rng, true, 2.0);
    Affine c = random_transform(&rng, false, 2.0);
    add_instance(&s, 1, c, NULL);
    add_instance(&s, 0, a, NULL);
    add_instance(&s, 0, a, NULL);
    add_instance(&s, 2, b, NULL);
    add_instance(&s, 2, b, NULL);
    s.inst[2].pad = 0.5f;
    s.inst[3].pad = 0.5f;
    SceneBvh probe;
    Instance inst[MAX_INSTANCES];
    InstanceMotion mot[MAX_INSTANCES];
    build_scene_bvh(&s, &probe, 2, false, BVH_TWO_LEVEL, inst, mot);
    scene_bvh_free(&probe);
    uint32_t n = 3000;
    float *times = calloc(n, sizeof *times); /* static instances: the time changes nothing */
    float4 *rays = random_rays(&s, n, 23, times);
    BvhLevels levels[2] = {BVH_TWO_LEVEL, BVH_FLAT};
    for (int l = 0; l < 2; l++) {
        uint32_t on_pair[5] = {0};
        Traces tr = trace_all(&s, rays, times, n, levels[l]);
        for (uint32_t mode = 0; mode < 3; mode += 2)
            for (uint32_t i = 0; i < n; i++)
                if (prim_of(tr.hits[mode * n + i]) != HIT_NONE)
                    on_pair[tr.instance[mode * n + i] < 5 ? tr.instance[mode * n + i] : 0]++;
        const char *name = l ? "flat" : "two levels";
        cr_expect(on_pair[1] > 50 && on_pair[3] > 50, "%s: too few hits on the pairs (%u, %u)", name,
                  on_pair[1], on_pair[3]);
        cr_expect_eq(on_pair[2] + on_pair[4], 0, "%s: %u hits named the higher instance of a pair",
                     name, on_pair[2] + on_pair[4]);
        free(tr.hits);
        free(tr.instance);
    }
    free(rays);
    free(times);
    test_mesh_free(&s.all);
}

/* No instances at all (an empty scene is two-level with none): every ray misses, in every layout
 * (the quantised TLAS's empty leaf, whose box a ray may pass, names no instance). */
Test(instances_bvh, empty_scene_misses_everything, .timeout = 600)
{
    InstancedScene s = scene_with_meshes();
    uint32_t n = 256;
    float4 *rays = malloc(2 * n * sizeof *rays);
    float *times = calloc(n, sizeof *times);
    uint64_t rng = 31;
    for (uint32_t i = 0; i < n; i++) {
        float d[3] = {mesh_rng_float(&rng) - 0.5f, mesh_rng_float(&rng) - 0.5f, mesh_rng_float(&rng) - 0.5f};
        rays[2 * i] = (float4){{0.0f, 0.0f, 0.0f, 0.0f}};
        rays[2 * i + 1] = (float4){{d[0], d[1], d[2], INFINITY}};
    }
    Traces tr = trace_all(&s, rays, times, n, BVH_TWO_LEVEL);
    uint32_t hits = 0;
    for (uint32_t i = 0; i < 4 * n; i++)
        hits += prim_of(tr.hits[i]) != HIT_NONE;
    cr_expect_eq(hits, 0, "%u hits in an empty scene", hits);
    free(tr.hits);
    free(tr.instance);
    free(rays);
    free(times);
    test_mesh_free(&s.all);
}
