// SPDX-License-Identifier: MIT
/* BVH: the tree's invariants on the host (boxes contain what is below them, every triangle in
 * exactly one leaf, pre-order layout, bounded depth, stored SAH cost), and on PoCL: trace_closest
 * and trace_any reproduce a brute-force loop over the same watertight test for random rays into
 * procedural meshes, a triangle soup with exact ties and the public assets; rays aimed exactly at
 * shared edges and vertices of closed meshes never leak; secondary rays from offset_ray_origin
 * never re-hit their own triangle; binned SAH stays within 3% of a full-sweep build. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/bvh_quantized.h"
#include "accel/bvh_wide.h"
#include "io/obj_loader.h"
#include "procedural_mesh.h"
#include "support.h"

#define HIT_NONE_HOST HIT_NONE /* cl/shared.h */

/* ---- Host-side invariants ------------------------------------------------------------------ */

typedef struct {
    const Bvh *bvh;
    const Mesh *mesh;
    uint32_t *leaf_hits;  /* per leaf-order triangle: how many leaves hold it */
    uint8_t *node_seen;
    int max_depth;        /* deepest inner node, root = 0 */
    double cost_sum;
    uint32_t errors;
    BvhCosts costs;       /* the SAH costs the tree was built with */
} TreeCheck;

static bool box_contains(const float lo[3], const float hi[3], const float4 *p)
{
    for (int k = 0; k < 3; k++)
        if (!(p->s[k] >= lo[k] && p->s[k] <= hi[k]))
            return false;
    return true;
}

static double half_area(const float lo[3], const float hi[3])
{
    double d[3] = {(double)hi[0] - lo[0], (double)hi[1] - lo[1], (double)hi[2] - lo[2]};
    return d[0] >= 0.0 ? d[0] * d[1] + d[1] * d[2] + d[2] * d[0] : 0.0;
}

static void check_error(TreeCheck *check, const char *what, uint32_t node)
{
    if (check->errors++ < 5)
        cr_log_error("BVH invariant broken at node %u: %s", node, what);
}

static void check_node(TreeCheck *check, uint32_t index, const float lo[3], const float hi[3],
                       int depth);

/* A child box lies inside its parent's box, or is empty (an unused child slot). */
static bool child_box_inside(const float lo[3], const float hi[3], const float4 *child_lo,
                             const float4 *child_hi)
{
    if (child_lo->s[0] > child_hi->s[0])
        return true;
    return box_contains(lo, hi, child_lo) && box_contains(lo, hi, child_hi);
}

/* Checks one child slot of node `parent`: a leaf's triangles lie in its box, an inner reference is
 * valid and its subtree is checked. */
static void check_child(TreeCheck *check, uint32_t parent, const float4 *lo4, const float4 *hi4,
                        int depth)
{
    float lo[3] = {lo4->s[0], lo4->s[1], lo4->s[2]}, hi[3] = {hi4->s[0], hi4->s[1], hi4->s[2]};
    int32_t ref;
    uint32_t count;
    memcpy(&ref, &lo4->s[3], sizeof ref);
    memcpy(&count, &hi4->s[3], sizeof count);
    const Bvh *bvh = check->bvh;
    if (ref < 0) {
        uint32_t first = ~(uint32_t)ref;
        if (count > BVH_MAX_LEAF_SIZE || (uint64_t)first + count > bvh->num_tris) {
            check_error(check, "leaf range", parent);
            return;
        }
        check->cost_sum += check->costs.intersect * (double)count * half_area(lo, hi);
        for (uint32_t i = first; i < first + count; i++) {
            check->leaf_hits[i]++;
            const BvhTriangle *t = &bvh->tris[i];
            if (!box_contains(lo, hi, &t->v0) || !box_contains(lo, hi, &t->v1) ||
                !box_contains(lo, hi, &t->v2))
                check_error(check, "leaf box misses a triangle corner", parent);
        }
        return;
    }
    uint32_t index = (uint32_t)ref;
    if (count != 0 || index == 0 || index >= bvh->num_nodes || check->node_seen[index]++) {
        check_error(check, "inner reference", parent);
        return;
    }
    check_node(check, index, lo, hi, depth);
}

/* Checks inner node `index`, whose box (stored in its parent) is lo/hi. */
static void check_node(TreeCheck *check, uint32_t index, const float lo[3], const float hi[3],
                       int depth)
{
    check->cost_sum += check->costs.traversal * half_area(lo, hi);
    check->max_depth = depth > check->max_depth ? depth : check->max_depth;
    const BvhNode *node = &check->bvh->nodes[index];
    if (!child_box_inside(lo, hi, &node->lmin, &node->lmax) ||
        !child_box_inside(lo, hi, &node->rmin, &node->rmax))
        check_error(check, "child box outside its parent's", index);
    /* Pre-order: an inner left child comes right after its parent. */
    int32_t left;
    memcpy(&left, &node->lmin.s[3], sizeof left);
    if (left >= 0 && (uint32_t)left != index + 1)
        check_error(check, "left child not adjacent", index);
    check_child(check, index, &node->lmin, &node->lmax, depth + 1);
    check_child(check, index, &node->rmin, &node->rmax, depth + 1);
}

/* Every invariant of a built tree; returns the deepest inner node's depth. */
static int check_tree_with_costs(const Bvh *bvh, const Mesh *mesh, const char *name, BvhCosts costs)
{
    TreeCheck check = {bvh, mesh, calloc(bvh->num_tris + 1, 4), calloc(bvh->num_nodes, 1), 0, 0, 0, costs};
    cr_assert_eq(bvh->num_tris, mesh->num_triangles, "%s: triangle count", name);
    cr_assert_geq(bvh->num_nodes, 1u);
    /* The root is checked as the child of a virtual parent whose box is the mesh bounds. */
    float lo[3], hi[3];
    mesh_bounds(mesh, lo, hi);
    check.node_seen[0] = 1;
    check_node(&check, 0, lo, hi, 0);
    for (uint32_t i = 0; i < bvh->num_nodes; i++)
        if (check.node_seen[i] != 1)
            check_error(&check, "node unreachable or shared", i);
    /* Every triangle in exactly one leaf, and the leaf order is a permutation of the mesh. */
    uint8_t *original_seen = calloc(mesh->num_triangles + 1, 1);
    for (uint32_t i = 0; i < bvh->num_tris; i++) {
        uint32_t original;
        memcpy(&original, &bvh->tris[i].v0.s[3], sizeof original);
        if (check.leaf_hits[i] != 1 || original >= mesh->num_triangles || original_seen[original]++)
            check_error(&check, "triangle not in exactly one leaf", i);
        else {
            const uint4 v = mesh->triangles[original].v;
            if (memcmp(bvh->tris[i].v1.s, mesh->positions[v.s[1]].s, 12) != 0 ||
                memcmp(bvh->tris[i].v2.s, mesh->positions[v.s[2]].s, 12) != 0)
                check_error(&check, "triangle corners differ from the mesh", i);
        }
    }
    cr_expect_eq(check.errors, 0, "%s: %u invariant violations", name, check.errors);
    cr_expect_lt(check.max_depth + 1, BVH_STACK_SIZE + 1, "%s: depth %d overflows the stack", name,
                 check.max_depth);
    double root_area = half_area(lo, hi);
    if (root_area > 0.0) {
        double sah = check.cost_sum / root_area;
        cr_expect(fabs(sah - bvh->sah_cost) <= 1e-4 * sah, "%s: sah_cost %g, recomputed %g", name,
                  bvh->sah_cost, sah);
    }
    free(check.leaf_hits);
    free(check.node_seen);
    free(original_seen);
    return check.max_depth;
}

static int check_tree(const Bvh *bvh, const Mesh *mesh, const char *name)
{
    return check_tree_with_costs(bvh, mesh, name, BVH_COSTS_DEFAULT);
}

static int build_and_check(const Mesh *mesh, const char *name)
{
    Bvh bvh;
    bvh_build(&bvh, mesh->positions, mesh->triangles, mesh->num_triangles);
    int depth = check_tree(&bvh, mesh, name);
    bvh_free(&bvh);
    return depth;
}

/* Three chains of unit triangles along the axes, the i-th at distance (16/15)^i (up to 1e36).
 * A binned split only takes the far sixteenth of one axis's range off (a few dozen triangles),
 * so SAH alone would build a tree about 90 levels deep. */
static Mesh mesh_axis_chains(uint32_t per_axis)
{
    Mesh mesh = mesh_alloc(9 * per_axis, 3 * per_axis);
    for (uint32_t i = 0; i < per_axis; i++)
        for (int axis = 0; axis < 3; axis++) {
            float p[3] = {0, 0, 0};
            p[axis] = (float)pow(16.0 / 15.0, (double)i);
            uint32_t base = mesh.num_positions;
            for (int c = 0; c < 3; c++) {
                float q[3] = {p[0], p[1], p[2]};
                if (c > 0)
                    q[(axis + c) % 3] += 1.0f;
                mesh.positions[mesh.num_positions++] = mesh_point(q[0], q[1], q[2]);
            }
            mesh_add_triangle(&mesh, base, base + 1, base + 2);
        }
    return mesh;
}

static Mesh mesh_copies(uint32_t n)
{
    Mesh mesh = mesh_alloc(3, n);
    mesh.positions[mesh.num_positions++] = mesh_point(0, 0, 0);
    mesh.positions[mesh.num_positions++] = mesh_point(1, 0, 0);
    mesh.positions[mesh.num_positions++] = mesh_point(0, 1, 0);
    for (uint32_t i = 0; i < n; i++)
        mesh_add_triangle(&mesh, 0, 1, 2);
    return mesh;
}

Test(bvh, build_invariants_hold_on_procedural_meshes)
{
    struct {
        const char *name;
        Mesh mesh;
    } cases[] = {{"icosphere", mesh_icosphere(4)}, {"cube", mesh_cube_grid(9)},
                 {"torus", mesh_torus(30000)},   {"soup", mesh_soup(5000, 7)},
                 {"one", mesh_soup(1, 1)},       {"two", mesh_soup(2, 2)},
                 {"nine", mesh_soup(9, 3)},      {"copies", mesh_copies(5000)}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        build_and_check(&cases[i].mesh, cases[i].name);
        mesh_free(&cases[i].mesh);
    }
}

Test(bvh, depth_stays_within_the_traversal_stack)
{
    Mesh mesh = mesh_axis_chains(1280);
    int depth = build_and_check(&mesh, "axis chains");
    /* Deep enough that the depth limit had to act (a balanced tree would be 9 levels deep). */
    cr_expect_geq(depth, 48, "chains depth %d: too shallow to exercise the limit", depth);
    mesh_free(&mesh);
}

Test(bvh, binned_sah_is_within_3_percent_of_full_sweep)
{
    Mesh meshes[] = {mesh_torus(20000), mesh_icosphere(5), mesh_soup(10000, 11)};
    const char *names[] = {"torus", "icosphere", "soup"};
    for (int i = 0; i < 3; i++) {
        Bvh binned, swept;
        bvh_build(&binned, meshes[i].positions, meshes[i].triangles, meshes[i].num_triangles);
        bvh_build_full_sweep(&swept, meshes[i].positions, meshes[i].triangles,
                             meshes[i].num_triangles);
        check_tree(&swept, &meshes[i], names[i]);
        cr_log_info("%s: SAH binned %.3f, full sweep %.3f", names[i], binned.sah_cost, swept.sah_cost);
        cr_expect_leq(binned.sah_cost, 1.03 * swept.sah_cost, "%s: binned %g vs full sweep %g",
                      names[i], binned.sah_cost, swept.sah_cost);
        bvh_free(&binned);
        bvh_free(&swept);
        mesh_free(&meshes[i]);
    }
}

/* ---- Tracing on the device ----------------------------------------------------------------- */

/* Ray as the test kernels read it: origin with tmin in w, direction with tmax in w. */
typedef struct {
    float4 origin;
    float4 dir;
} Ray;

static float4 vec(float x, float y, float z, float w)
{
    float4 v = {{x, y, z, w}};
    return v;
}

typedef struct {
    Device *dev;
    Mesh mesh;
    Bvh bvh;
    cl_mem nodes, tris;
    uint32_t num_prims; /* entries of tris (triangles, or packs of the wide layout) */
    float4 *spheres; /* per triangle, for the brute-force reference's culling */
    float lo[3], hi[3];
} TraceScene;

static TraceScene scene_create(Device *dev, Mesh mesh)
{
    TraceScene scene = {dev, mesh, {0}, NULL, NULL, 0, NULL, {0}, {0}};
    Error err = {0};
    bvh_build_for_width(&scene.bvh, mesh.positions, mesh.triangles, mesh.num_triangles, dev->bvh_width);
    mesh_bounds(&mesh, scene.lo, scene.hi);
    BvhLayout layout;
    bvh_layout(&layout, &scene.bvh, dev->bvh_width, dev->bvh_quantized);
    scene.nodes = device_buffer(dev, "bvh_nodes", CL_MEM_READ_ONLY,
                                layout.num_nodes * layout.node_size, layout.nodes, &err);
    scene.tris = device_buffer(dev, "bvh_triangles", CL_MEM_READ_ONLY,
                               layout.num_prims * layout.prim_size, layout.prims, &err);
    scene.num_prims = layout.num_prims;
    bvh_layout_free(&layout);
    cr_assert(!error_is_set(&err), "%s", err.message);
    scene.spheres = malloc((mesh.num_triangles + 1) * sizeof *scene.spheres);
    for (uint32_t i = 0; i < mesh.num_triangles; i++) {
        /* Centre at the corners' mean, radius to the farthest corner, rounded up. */
        const float4 *p[3];
        double center[3] = {0, 0, 0}, radius = 0.0;
        for (int c = 0; c < 3; c++) {
            p[c] = &mesh.positions[mesh.triangles[i].v.s[c]];
            for (int k = 0; k < 3; k++)
                center[k] += p[c]->s[k] / 3.0;
        }
        for (int c = 0; c < 3; c++) {
            double d2 = 0.0;
            for (int k = 0; k < 3; k++)
                d2 += (p[c]->s[k] - center[k]) * (p[c]->s[k] - center[k]);
            radius = fmax(radius, sqrt(d2));
        }
        scene.spheres[i] =
            vec((float)center[0], (float)center[1], (float)center[2], (float)(radius * 1.001));
    }
    return scene;
}

static void scene_release(TraceScene *scene)
{
    clReleaseMemObject(scene->nodes);
    clReleaseMemObject(scene->tris);
    free(scene->spheres);
    bvh_free(&scene->bvh);
    mesh_free(&scene->mesh);
}

/* Runs bvh_test_trace_closest or _any over rays; out gets one float4 (closest) or uint (any) per
 * ray. */
static void trace(TraceScene *scene, const char *kernel_name, const Ray *rays, uint32_t n, void *out)
{
    Device *dev = scene->dev;
    Error err = {0};
    bool closest = strstr(kernel_name, "closest") != NULL;
    size_t out_size = n * (closest ? sizeof(float4) : sizeof(cl_uint));
    cl_mem ray_buf = device_buffer(dev, "rays", CL_MEM_READ_ONLY, n * sizeof(Ray), rays, &err);
    cl_mem out_buf = device_buffer(dev, "results", CL_MEM_WRITE_ONLY, out_size, NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, kernel_name);
    cl_uint arg = 0, num_tris = scene->num_prims, num_rays = n;
    KERNEL_ARG(kernel, arg++, scene->nodes);
    KERNEL_ARG(kernel, arg++, scene->tris);
    KERNEL_ARG(kernel, arg++, num_tris);
    KERNEL_ARG(kernel, arg++, ray_buf);
    KERNEL_ARG(kernel, arg++, num_rays);
    KERNEL_ARG(kernel, arg++, out_buf);
    double ms = 0.0;
    device_run(dev, kernel, n, 0, &ms);
    if (getenv("BVH_TEST_TIMES"))
        cr_log_info("%s: %u rays, %u triangles: %.1f ms", kernel_name, n, num_tris, ms);
    device_read(dev, out_buf, 0, out_size, out);
    clReleaseKernel(kernel);
    clReleaseMemObject(ray_buf);
    clReleaseMemObject(out_buf);
}

static uint32_t hit_prim(float4 hit)
{
    uint32_t prim;
    memcpy(&prim, &hit.s[3], sizeof prim);
    return prim;
}

static Ray make_ray(const float origin[3], const float dir[3], float tmin, float tmax)
{
    Ray ray = {vec(origin[0], origin[1], origin[2], tmin), vec(dir[0], dir[1], dir[2], tmax)};
    return ray;
}

static void normalize3(float v[3])
{
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= len;
}

static void random_direction(uint64_t *rng, float dir[3])
{
    float z = 2.0f * mesh_rng_float(rng) - 1.0f, phi = 6.2831853f * mesh_rng_float(rng);
    float r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    dir[0] = r * cosf(phi);
    dir[1] = r * sinf(phi);
    dir[2] = z;
}

/* A mix of the rays a renderer traces and the awkward ones: from outside the bounds toward points
 * inside them, from inside the bounds in any direction, exactly axis-parallel (with +0 and -0 in
 * the other components, origins on vertex coordinates so they lie in box planes), aimed exactly
 * at vertices, some with tmin > 0 and some with finite tmax. */
static Ray *random_rays(const TraceScene *scene, uint32_t n, uint64_t seed)
{
    Ray *rays = malloc(n * sizeof *rays);
    uint64_t rng = seed;
    float center[3], extent[3], radius = 0.0f;
    for (int k = 0; k < 3; k++) {
        center[k] = 0.5f * (scene->lo[k] + scene->hi[k]);
        extent[k] = scene->hi[k] - scene->lo[k];
        radius += 0.25f * extent[k] * extent[k];
    }
    radius = sqrtf(radius);
    const Mesh *mesh = &scene->mesh;
    for (uint32_t i = 0; i < n; i++) {
        float kind = mesh_rng_float(&rng), origin[3], target[3], dir[3];
        const float4 vertex =
            mesh->positions[mesh->triangles[mesh_rng_next(&rng) % mesh->num_triangles].v.s[0]];
        for (int k = 0; k < 3; k++)
            target[k] = scene->lo[k] + extent[k] * mesh_rng_float(&rng);
        if (kind < 0.45f || kind >= 0.85f) {
            /* From a sphere around the bounds toward a point inside them or a vertex. */
            random_direction(&rng, dir);
            for (int k = 0; k < 3; k++) {
                origin[k] = center[k] + 1.5f * radius * dir[k];
                dir[k] = (kind >= 0.85f ? vertex.s[k] : target[k]) - origin[k];
            }
            normalize3(dir);
        } else if (kind < 0.7f) {
            memcpy(origin, target, sizeof origin);
            random_direction(&rng, dir);
        } else {
            int axis = (int)(mesh_rng_next(&rng) % 3);
            float sign = mesh_rng_float(&rng) < 0.5f ? -1.0f : 1.0f;
            for (int k = 0; k < 3; k++) {
                origin[k] = mesh_rng_float(&rng) < 0.5f ? vertex.s[k] : target[k];
                dir[k] = mesh_rng_float(&rng) < 0.5f ? 0.0f : -0.0f;
            }
            origin[axis] = center[axis] - sign * (mesh_rng_float(&rng) < 0.5f ? 2.0f * radius : 0.0f);
            dir[axis] = sign;
        }
        float tmin = mesh_rng_float(&rng) < 0.1f ? radius * mesh_rng_float(&rng) : 0.0f;
        float tmax = mesh_rng_float(&rng) < 0.2f ? tmin + 2.0f * radius * mesh_rng_float(&rng)
                                                 : INFINITY;
        rays[i] = make_ray(origin, dir, tmin, tmax);
    }
    return rays;
}

/* Two closest hits agree: the same triangle, or ties at the same distance (1e-6 relative). */
static bool same_closest(float4 a, float4 b)
{
    if (hit_prim(a) == hit_prim(b))
        return hit_prim(a) == HIT_NONE_HOST || fabsf(a.s[0] - b.s[0]) <= 1e-6f * fabsf(b.s[0]);
    return hit_prim(a) != HIT_NONE_HOST && hit_prim(b) != HIT_NONE_HOST &&
           fabsf(a.s[0] - b.s[0]) <= 1e-6f * fmaxf(fabsf(a.s[0]), fabsf(b.s[0]));
}

/* ---- Host reference: the watertight test of cl/geometry/intersect_triangle.cl, operation for operation,
 * over every triangle in file order (C runs this loop some 30 times faster than PoCL). ISO C
 * compiles without fma contraction, so the explicit fmaf calls round exactly as the kernel's. One
 * step is written the other way round on purpose: the kernel permutes (vertex - origin), this
 * subtracts the permuted origin from the permuted vertex; the two are exactly equal, and the
 * bit-for-bit comparisons below hold the kernel to that. */

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
static float4 brute_force_closest(const TraceScene *scene, const Ray *r)
{
    const float *o = r->origin.s, *d = r->dir.s;
    RefRay ray = ref_ray(o, d);
    float line_scale = 1.7320509f * max_abs3(d[0], d[1], d[2]);
    float best_t = r->dir.s[3], best_u = 0.0f, best_v = 0.0f;
    uint32_t best = HIT_NONE_HOST;
    const Mesh *mesh = &scene->mesh;
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

/* The BVH's closest hits equal the brute-force loop's for every ray, and any-hit answers as the
 * closest hit does; then, for rays that hit, any-hit with tmax at the hit sees nothing and with
 * tmax one ulp further sees it. Returns how many rays hit. */
static uint32_t check_against_brute_force(TraceScene *scene, const Ray *rays, uint32_t n, const char *name)
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
        bool hit = hit_prim(hits[i]) != HIT_NONE_HOST;
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

#define RAYS_PER_MESH 10000

static void check_mesh_against_brute_force(Mesh mesh, const char *name, uint64_t seed)
{
    Device *dev = test_device();
    TraceScene scene = scene_create(dev, mesh);
    check_tree_with_costs(&scene.bvh, &scene.mesh, name, bvh_costs_for_width(dev->bvh_width));
    Ray *rays = random_rays(&scene, RAYS_PER_MESH, seed);
    uint32_t num_hits = check_against_brute_force(&scene, rays, RAYS_PER_MESH, name);
    /* Most rays are aimed into the bounds: a test where nothing hits would prove little. */
    cr_expect_gt(num_hits, RAYS_PER_MESH / 5, "%s: only %u of %u rays hit", name, num_hits,
                 RAYS_PER_MESH);
    free(rays);
    scene_release(&scene);
    test_device_release(dev);
}

Test(bvh, matches_brute_force_on_icosphere) { check_mesh_against_brute_force(mesh_icosphere(5), "icosphere", 1); }
Test(bvh, matches_brute_force_on_cube_grid) { check_mesh_against_brute_force(mesh_cube_grid(16), "cube", 2); }
Test(bvh, matches_brute_force_on_torus) { check_mesh_against_brute_force(mesh_torus(20000), "torus", 3); }
Test(bvh, matches_brute_force_on_overlapping_soup) { check_mesh_against_brute_force(mesh_soup(20000, 4), "soup", 4); }
/* The depth-limited tree (tested for depth above), traced: rays from near the chains' common
 * corner toward the centroids of their first 200 triangles (farther ones are too far apart for
 * a float direction to reach), and every fourth one along a chain through its triangles, starting
 * past a random number of them: these meet both children on every level of the chain, so they
 * fill the traversal stack as deep as the tree goes. */
Test(bvh, matches_brute_force_on_depth_limited_tree)
{
    Device *dev = test_device();
    TraceScene scene = scene_create(dev, mesh_axis_chains(1280));
    Ray *rays = malloc(RAYS_PER_MESH * sizeof *rays);
    uint64_t rng = 5;
    for (uint32_t i = 0; i < RAYS_PER_MESH; i++) {
        uint32_t tri = 3 * (uint32_t)(mesh_rng_next(&rng) % 200) + (uint32_t)(mesh_rng_next(&rng) % 3);
        float origin[3], dir[3];
        for (int k = 0; k < 3; k++) {
            origin[k] = 3.0f * mesh_rng_float(&rng) - 1.0f;
            dir[k] = -origin[k];
            for (int c = 0; c < 3; c++)
                dir[k] += scene.mesh.positions[scene.mesh.triangles[tri].v.s[c]].s[k] / 3.0f;
        }
        normalize3(dir);
        rays[i] = make_ray(origin, dir, 0.0f, INFINITY);
        if (i % 4 == 0) {
            int axis = (int)(tri % 3);
            float start = (float)pow(16.0 / 15.0, 200.0 * mesh_rng_float(&rng));
            for (int k = 0; k < 3; k++) {
                origin[k] = k == axis ? -1.0f : 0.05f + 0.4f * mesh_rng_float(&rng);
                dir[k] = k == axis ? 1.0f : 0.0f;
            }
            rays[i] = make_ray(origin, dir, start, INFINITY);
        }
    }
    uint32_t num_hits = check_against_brute_force(&scene, rays, RAYS_PER_MESH, "axis chains");
    cr_expect_gt(num_hits, RAYS_PER_MESH / 2, "axis chains: only %u of %u rays hit", num_hits,
                 RAYS_PER_MESH);
    free(rays);
    scene_release(&scene);
    test_device_release(dev);
}
Test(bvh, matches_brute_force_on_single_triangle) { check_mesh_against_brute_force(mesh_soup(1, 6), "one triangle", 6); }

static void check_asset_against_brute_force(const char *relative_path, uint64_t seed)
{
    REQUIRE_ASSETS();
    char path[512];
    snprintf(path, sizeof path, "%s/%s", ASSETS_DIR, relative_path);
    ObjMesh obj;
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(obj_load(path, &obj, &err), "%s", err.message);
    Mesh mesh = mesh_from_obj(&obj);
    obj_free(&obj);
    check_mesh_against_brute_force(mesh, relative_path, seed);
}

Test(bvh, matches_brute_force_on_bunny) { check_asset_against_brute_force("stanford-bunny/stanford-bunny.obj", 11); }
Test(bvh, matches_brute_force_on_dragon) { check_asset_against_brute_force("stanford-dragon/dragon.obj", 12); }
Test(bvh, matches_brute_force_on_skull) { check_asset_against_brute_force("skull/skull.obj", 13); }
Test(bvh, matches_brute_force_on_cornell_original) { check_asset_against_brute_force("cornell-box/CornellBox-Original.obj", 14); }
Test(bvh, matches_brute_force_on_cornell_sphere) { check_asset_against_brute_force("cornell-box/CornellBox-Sphere.obj", 15); }

/* ---- Wide layouts (bvh_wide.c) ---------------------------------------------------------------- */

typedef struct {
    const BvhLayout *layout;
    const Mesh *mesh;
    uint32_t *tri_seen;   /* per original triangle: in how many leaves (padding lanes not counted) */
    uint8_t *node_seen;
    uint32_t max_stack;   /* the deepest stack a walk can fill, recomputed */
    uint32_t errors;
} WideCheck;

static void wide_error(WideCheck *c, const char *what, uint32_t index)
{
    if (c->errors++ < 5)
        cr_log_error("%d-wide: %s at %u", c->layout->width, what, index);
}

static const float *wide_rows(const BvhLayout *l, uint32_t node)
{
    return (const float *)((const uint8_t *)l->nodes + (size_t)node * l->node_size);
}

static const float *pack_rows(const BvhLayout *l, uint32_t pack)
{
    return (const float *)((const uint8_t *)l->prims + (size_t)pack * l->prim_size);
}

/* A leaf's packs: original indices valid, corners inside the lane's box, padding lanes repeat the
 * lane before them. */
static void check_wide_leaf(WideCheck *c, uint32_t ref, const float lo[3], const float hi[3])
{
    int w = c->layout->width;
    uint32_t code = ~ref, first = code >> BVH_WIDE_LEAF_PACK_BITS;
    uint32_t count = (code & ((1u << BVH_WIDE_LEAF_PACK_BITS) - 1u)) + 1u;
    for (uint32_t p = first; p < first + count; p++) {
        if (p >= c->layout->num_prims) {
            wide_error(c, "pack index out of range", p);
            return;
        }
        const float *rows = pack_rows(c->layout, p);
        const uint32_t *prim = (const uint32_t *)(rows + 9 * w);
        for (int lane = 0; lane < w; lane++) {
            if (prim[lane] >= c->mesh->num_triangles) {
                wide_error(c, "pack lane holds no triangle", p);
                continue;
            }
            bool padding = lane > 0 && prim[lane] == prim[lane - 1];
            if (!padding)
                c->tri_seen[prim[lane]]++;
            for (int corner = 0; corner < 3; corner++)
                for (int k = 0; k < 3; k++) {
                    float x = rows[(3 * corner + k) * w + lane];
                    if (!(x >= lo[k] && x <= hi[k]))
                        wide_error(c, "triangle outside its leaf's box", p);
                }
        }
    }
}

/* A node's used lanes come first and lie in the parent's box; pushes along the path are counted as
 * the traversal makes them (all hit children but the nearest). */
static void check_wide_node(WideCheck *c, uint32_t node, const float lo[3], const float hi[3],
                            uint32_t stacked)
{
    if (node >= c->layout->num_nodes || c->node_seen[node]++) {
        wide_error(c, "node out of range or shared", node);
        return;
    }
    int w = c->layout->width;
    const float *rows = wide_rows(c->layout, node);
    const uint32_t *child = (const uint32_t *)(rows + 6 * w);
    int used = 0;
    for (int lane = 0; lane < w; lane++) {
        bool empty = rows[lane] > rows[3 * w + lane];
        if (empty && (child[lane] != 0 || rows[lane] != INFINITY))
            wide_error(c, "unused lane not marked empty", node);
        if (!empty && used++ != lane)
            wide_error(c, "used lane after an unused one", node);
    }
    uint32_t pushes = used > 0 ? (uint32_t)used - 1 : 0;
    if (stacked + pushes > c->max_stack)
        c->max_stack = stacked + pushes;
    for (int lane = 0; lane < used; lane++) {
        float child_lo[3], child_hi[3];
        for (int k = 0; k < 3; k++) {
            child_lo[k] = rows[k * w + lane];
            child_hi[k] = rows[(3 + k) * w + lane];
            if (!(child_lo[k] >= lo[k] && child_hi[k] <= hi[k]))
                wide_error(c, "child box outside its parent's", node);
        }
        if ((int32_t)child[lane] < 0)
            check_wide_leaf(c, child[lane], child_lo, child_hi);
        else
            check_wide_node(c, child[lane], child_lo, child_hi, stacked + pushes);
    }
}

/* Every invariant of the wide layout of mesh's tree; returns its stack need. */
static uint32_t check_wide_layout(const Mesh *mesh, int width, const char *name)
{
    Bvh bvh;
    bvh_build_for_width(&bvh, mesh->positions, mesh->triangles, mesh->num_triangles, width);
    BvhLayout layout;
    bvh_layout(&layout, &bvh, width, false);
    cr_assert_eq(layout.width, width);
    cr_assert_eq(layout.node_size, width == 4 ? sizeof(BvhNode4) : sizeof(BvhNode8));
    WideCheck c = {&layout, mesh, calloc(mesh->num_triangles + 1, 4), calloc(layout.num_nodes, 1), 0, 0};
    float lo[3], hi[3];
    mesh_bounds(mesh, lo, hi);
    check_wide_node(&c, 0, lo, hi, 0);
    for (uint32_t i = 0; i < layout.num_nodes; i++)
        if (c.node_seen[i] != 1)
            wide_error(&c, "node unreachable or shared", i);
    for (uint32_t i = 0; i < mesh->num_triangles; i++)
        if (c.tri_seen[i] != 1)
            wide_error(&c, "triangle not in exactly one leaf", i);
    cr_expect_eq(c.errors, 0, "%s: %u invariant violations in the %d-wide layout", name, c.errors, width);
    cr_expect_eq(c.max_stack, layout.max_stack, "%s: stack need %u, layout reports %u", name,
                 c.max_stack, layout.max_stack);
    cr_expect_leq(c.max_stack, BVH_WIDE_STACK_SIZE, "%s: %d-wide stack need %u", name, width, c.max_stack);
    free(c.tri_seen);
    free(c.node_seen);
    bvh_layout_free(&layout);
    bvh_free(&bvh);
    return c.max_stack;
}

/* The meshes every layout is checked on: the awkward cases of the builder (one triangle, nine,
 * identical copies, none, chains along the axes) and a torus far from the origin and small against
 * its coordinates, where quantised frames lose the most bits. */
typedef struct {
    const char *name;
    Mesh mesh;
} NamedMesh;
#define LAYOUT_MESHES 9
static void layout_meshes(NamedMesh out[LAYOUT_MESHES])
{
    NamedMesh cases[LAYOUT_MESHES] = {
        {"icosphere", mesh_icosphere(4)}, {"torus", mesh_torus(30000)},
        {"soup", mesh_soup(5000, 7)},     {"one", mesh_soup(1, 1)},
        {"nine", mesh_soup(9, 3)},        {"copies", mesh_copies(5000)},
        {"empty", mesh_soup(0, 1)},       {"axis chains", mesh_axis_chains(1280)},
        {"far torus", mesh_torus(30000)}};
    Mesh *far = &cases[8].mesh;
    for (uint32_t v = 0; v < far->num_positions; v++)
        for (int k = 0; k < 3; k++)
            far->positions[v].s[k] = far->positions[v].s[k] * 1e-3f - 3.0e4f * (k + 1) * (k == 1 ? -1 : 1);
    memcpy(out, cases, sizeof cases);
}

Test(bvh, wide_layout_invariants_hold)
{
    NamedMesh cases[LAYOUT_MESHES];
    layout_meshes(cases);
    for (size_t i = 0; i < LAYOUT_MESHES; i++) {
        for (int width = 4; width <= 8; width += 4) {
            uint32_t stack = check_wide_layout(&cases[i].mesh, width, cases[i].name);
            cr_log_info("%s, %d-wide: stack need %u", cases[i].name, width, stack);
        }
        mesh_free(&cases[i].mesh);
    }
}

/* Every quantised child box holds its exact box with the margin the traversal relies on
 * (host/accel/bvh_quantized.c), is at most two steps looser per side, and keeps its reference; an empty
 * child is inverted on every axis with no triangles. */
static void check_quantized(const Mesh *mesh, const char *name)
{
    Bvh bvh;
    bvh_build(&bvh, mesh->positions, mesh->triangles, mesh->num_triangles);
    BvhNodeQuantized *q = bvh_quantize(&bvh);
    unsigned errors = 0;
    for (uint32_t i = 0; i < bvh.num_nodes; i++) {
        const BvhNode *n = &bvh.nodes[i];
        const float4 *lo[2] = {&n->lmin, &n->rmin}, *hi[2] = {&n->lmax, &n->rmax};
        const uint32_t refs[2] = {q[i].refs.s[2], q[i].refs.s[3]};
        for (int c = 0; c < 2; c++) {
            double qlo[3], qhi[3];
            bvh_quantized_child_box(&q[i], c, qlo, qhi);
            uint32_t ref, count;
            memcpy(&ref, &lo[c]->s[3], sizeof ref);
            memcpy(&count, &hi[c]->s[3], sizeof count);
            bool empty = !(lo[c]->s[0] <= hi[c]->s[0]);
            for (int k = 0; k < 3; k++) {
                double step = ldexp(1.0, (int)(q[i].frame.s[k] & 0xffu) - 127), margin = step / 1024;
                bool ok = empty ? qlo[k] > qhi[k]
                                : qlo[k] <= lo[c]->s[k] - margin && qhi[k] >= hi[c]->s[k] + margin &&
                                      qlo[k] >= lo[c]->s[k] - 2 * step && qhi[k] <= hi[c]->s[k] + 2 * step;
                if (!ok && errors++ < 5)
                    cr_log_error("%s: node %u child %d axis %d: [%.9g, %.9g] against [%.9g, %.9g]", name,
                                 i, c, k, qlo[k], qhi[k], lo[c]->s[k], hi[c]->s[k]);
            }
            uint32_t want = (int32_t)ref >= 0 ? ref
                                              : BVH_QUANTIZED_LEAF | ~ref << BVH_QUANTIZED_COUNT_BITS | count;
            if (refs[c] != want && errors++ < 5)
                cr_log_error("%s: node %u child %d: reference %08x, want %08x", name, i, c, refs[c], want);
        }
    }
    cr_expect_eq(errors, 0, "%s: %u quantisation errors", name, errors);
    free(q);
    bvh_free(&bvh);
}

Test(bvh, quantized_nodes_hold_their_children)
{
    NamedMesh cases[LAYOUT_MESHES];
    layout_meshes(cases);
    for (size_t i = 0; i < LAYOUT_MESHES; i++) {
        check_quantized(&cases[i].mesh, cases[i].name);
        mesh_free(&cases[i].mesh);
    }
}

/* ---- Watertightness, axis-parallel rays and ray offsets ------------------------------------ */

/* Rays aimed exactly at every vertex and edge midpoint of a closed mesh around the origin: from
 * outside (from the side the point faces) and from inside (near the centre). Every one must hit,
 * in the BVH and in the reference; a test with a rounding gap at shared edges leaks some. */
static void check_watertight(Mesh mesh, const char *name)
{
    Device *dev = test_device();
    TraceScene scene = scene_create(dev, mesh);
    uint32_t n = 0, capacity = 16 * mesh.num_triangles;
    Ray *rays = malloc(capacity * sizeof *rays);
    uint64_t rng = 99;
    for (uint32_t i = 0; i < mesh.num_triangles && n + 8 <= capacity; i++)
        for (int c = 0; c < 3; c++) {
            const float4 *a = &mesh.positions[mesh.triangles[i].v.s[c]];
            const float4 *b = &mesh.positions[mesh.triangles[i].v.s[(c + 1) % 3]];
            float points[2][3];
            for (int k = 0; k < 3; k++) {
                points[0][k] = a->s[k];
                points[1][k] = 0.5f * (a->s[k] + b->s[k]);
            }
            for (int p = 0; p < 2; p++) {
                float outside[3], inside[3], dir_in[3], dir_out[3], jitter[3];
                random_direction(&rng, jitter);
                for (int k = 0; k < 3; k++) {
                    outside[k] = 3.0f * points[p][k] + 0.5f * jitter[k];
                    inside[k] = 0.2f * jitter[k];
                    dir_in[k] = points[p][k] - outside[k];
                    dir_out[k] = points[p][k] - inside[k];
                }
                normalize3(dir_in);
                normalize3(dir_out);
                rays[n++] = make_ray(outside, dir_in, 0.0f, INFINITY);
                rays[n++] = make_ray(inside, dir_out, 0.0f, INFINITY);
            }
        }
    float4 *hits = malloc(n * sizeof *hits);
    trace(&scene, "bvh_test_trace_closest", rays, n, hits);
    uint32_t leaks = 0, reference_leaks = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (hit_prim(hits[i]) == HIT_NONE_HOST && leaks++ < 5)
            cr_log_error("%s: ray %u at a shared edge or vertex leaks through the BVH", name, i);
        if (hit_prim(brute_force_closest(&scene, &rays[i])) == HIT_NONE_HOST)
            reference_leaks++;
    }
    cr_expect_eq(leaks, 0, "%s: %u of %u rays through edges and vertices leak", name, leaks, n);
    cr_expect_eq(reference_leaks, 0, "%s: %u of %u leak through the reference test", name,
                 reference_leaks, n);
    free(rays);
    free(hits);
    scene_release(&scene);
    test_device_release(dev);
}

Test(bvh, watertight_at_icosphere_edges_and_vertices) { check_watertight(mesh_icosphere(4), "icosphere"); }
Test(bvh, watertight_at_cube_edges_and_vertices) { check_watertight(mesh_cube_grid(8), "cube"); }

/* Axis-parallel rays (+0 and -0 in the other components) along every grid line of the cube's
 * faces: they run exactly through shared edges and vertices, in the planes of the boxes (a face
 * is a flat box), some in the plane of a side face. From outside they hit at t = 3, from the
 * centre at t = 1; the exact distances leave no room for a wrong triangle. */
Test(bvh, axis_parallel_rays_through_grid_lines_hit_at_the_exact_distance)
{
    const int k = 4;
    Device *dev = test_device();
    TraceScene scene = scene_create(dev, mesh_cube_grid(k));
    Ray *rays = malloc(6 * 2 * 2 * (k + 1) * (k + 1) * sizeof *rays);
    float *expected_t = malloc(6 * 2 * 2 * (k + 1) * (k + 1) * sizeof *expected_t);
    uint32_t n = 0;
    for (int axis = 0; axis < 3; axis++)
        for (int sign = -1; sign <= 1; sign += 2)
            for (int i = 0; i <= k; i++)
                for (int j = 0; j <= k; j++)
                    for (int from_inside = 0; from_inside < 2; from_inside++) {
                        float origin[3], dir[3];
                        origin[(axis + 1) % 3] = 2.0f * (float)i / (float)k - 1.0f;
                        origin[(axis + 2) % 3] = 2.0f * (float)j / (float)k - 1.0f;
                        origin[axis] = from_inside ? 0.0f : -4.0f * (float)sign;
                        dir[(axis + 1) % 3] = (i + j) % 2 ? 0.0f : -0.0f;
                        dir[(axis + 2) % 3] = i % 2 ? -0.0f : 0.0f;
                        dir[axis] = (float)sign;
                        expected_t[n] = from_inside ? 1.0f : 3.0f;
                        rays[n++] = make_ray(origin, dir, 0.0f, INFINITY);
                    }
    float4 *hits = malloc(n * sizeof *hits);
    cl_uint *any = malloc(n * sizeof *any);
    trace(&scene, "bvh_test_trace_closest", rays, n, hits);
    trace(&scene, "bvh_test_trace_any", rays, n, any);
    uint32_t wrong = 0;
    for (uint32_t i = 0; i < n; i++)
        if ((hit_prim(hits[i]) == HIT_NONE_HOST || hits[i].s[0] != expected_t[i] || !any[i]) &&
            wrong++ < 5)
            cr_log_error("ray %u o=(%g %g %g) d=(%g %g %g): prim %d t %g, expected t %g", i,
                         rays[i].origin.s[0], rays[i].origin.s[1], rays[i].origin.s[2],
                         rays[i].dir.s[0], rays[i].dir.s[1], rays[i].dir.s[2],
                         (int)hit_prim(hits[i]), hits[i].s[0], expected_t[i]);
    cr_expect_eq(wrong, 0, "%u of %u axis-parallel rays missed or hit at the wrong distance", wrong, n);
    check_against_brute_force(&scene, rays, n, "axis-parallel grid rays");
    free(rays);
    free(expected_t);
    free(hits);
    free(any);
    scene_release(&scene);
    test_device_release(dev);
}

/* Scales the mesh about the origin, then moves it. */
static Mesh mesh_transformed(Mesh mesh, float scale, float dx, float dy, float dz)
{
    for (uint32_t i = 0; i < mesh.num_positions; i++) {
        mesh.positions[i].s[0] = mesh.positions[i].s[0] * scale + dx;
        mesh.positions[i].s[1] = mesh.positions[i].s[1] * scale + dy;
        mesh.positions[i].s[2] = mesh.positions[i].s[2] * scale + dz;
    }
    return mesh;
}

/* Secondary rays from the closest hits of rays from outside, made as an integrator makes them
 * (bvh_test_bounce_rays: interpolated hit point, offset_ray_origin, tmin = 0), to the side the ray
 * came from and through the surface. None may hit the triangle it starts on. On a convex mesh,
 * reflected rays must escape and transmitted rays must reach another triangle. */
static void check_offset_rays(Mesh mesh, const char *name, bool convex)
{
    Device *dev = test_device();
    TraceScene scene = scene_create(dev, mesh);
    const uint32_t n = RAYS_PER_MESH;
    Ray *rays = random_rays(&scene, n, 21);
    uint64_t rng = 22;
    float center[3], radius = 0.0f;
    for (int k = 0; k < 3; k++) {
        center[k] = 0.5f * (scene.lo[k] + scene.hi[k]);
        radius = fmaxf(radius, scene.hi[k] - scene.lo[k]);
    }
    for (uint32_t i = 0; i < n; i++) {
        /* From outside only, toward a point of the bounds. */
        float origin[3], dir[3];
        random_direction(&rng, origin);
        for (int k = 0; k < 3; k++) {
            origin[k] = center[k] + 2.0f * radius * origin[k];
            dir[k] = scene.lo[k] + (scene.hi[k] - scene.lo[k]) * mesh_rng_float(&rng) - origin[k];
        }
        normalize3(dir);
        rays[i] = make_ray(origin, dir, 0.0f, INFINITY);
    }
    float4 *corners = malloc(3 * mesh.num_triangles * sizeof *corners);
    for (uint32_t i = 0; i < mesh.num_triangles; i++)
        for (int c = 0; c < 3; c++)
            corners[3 * i + c] = mesh.positions[mesh.triangles[i].v.s[c]];
    float4 *hits = malloc(n * sizeof *hits), *bounce_hits = malloc(n * sizeof *bounce_hits);
    Ray *bounce = malloc(n * sizeof *bounce);
    trace(&scene, "bvh_test_trace_closest", rays, n, hits);
    Error err = {0};
    cl_mem corner_buf = device_buffer(dev, "corners", CL_MEM_READ_ONLY,
                                      3 * mesh.num_triangles * sizeof(float4), corners, &err);
    cl_mem ray_buf = device_buffer(dev, "rays", CL_MEM_READ_ONLY, n * sizeof(Ray), rays, &err);
    cl_mem hit_buf = device_buffer(dev, "hits", CL_MEM_READ_ONLY, n * sizeof(float4), hits, &err);
    cl_mem bounce_buf = device_buffer(dev, "bounce", CL_MEM_WRITE_ONLY, n * sizeof(Ray), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "bvh_test_bounce_rays");
    for (cl_uint reflect = 0; reflect < 2; reflect++) {
        cl_uint num_rays = n, seed = 7 + reflect;
        KERNEL_ARG(kernel, 0, corner_buf);
        KERNEL_ARG(kernel, 1, ray_buf);
        KERNEL_ARG(kernel, 2, hit_buf);
        KERNEL_ARG(kernel, 3, num_rays);
        KERNEL_ARG(kernel, 4, seed);
        KERNEL_ARG(kernel, 5, reflect);
        KERNEL_ARG(kernel, 6, bounce_buf);
        device_run(dev, kernel, n, 0, NULL);
        device_read(dev, bounce_buf, 0, n * sizeof(Ray), bounce);
        trace(&scene, "bvh_test_trace_closest", bounce, n, bounce_hits);
        uint32_t sources = 0, self_hits = 0, wrong = 0;
        for (uint32_t i = 0; i < n; i++) {
            uint32_t source = hit_prim(hits[i]), prim = hit_prim(bounce_hits[i]);
            if (source == HIT_NONE_HOST)
                continue;
            sources++;
            if (prim == source && self_hits++ < 5)
                cr_log_error("%s: %s ray %u re-hits its triangle %u at t %g", name,
                             reflect ? "reflected" : "transmitted", i, source, bounce_hits[i].s[0]);
            if (convex && (reflect ? prim != HIT_NONE_HOST : prim == HIT_NONE_HOST) && wrong++ < 5)
                cr_log_error("%s: %s ray %u from triangle %u %s", name,
                             reflect ? "reflected" : "transmitted", i, source,
                             reflect ? "hits the convex mesh again" : "escapes the convex mesh");
        }
        cr_expect_gt(sources, n / 4, "%s: only %u of %u rays hit", name, sources, n);
        cr_expect_eq(self_hits, 0, "%s: %u of %u %s rays re-hit their own triangle", name, self_hits,
                     sources, reflect ? "reflected" : "transmitted");
        cr_expect_eq(wrong, 0, "%s: %u of %u %s rays wrong on a convex mesh", name, wrong, sources,
                     reflect ? "reflected" : "transmitted");
    }
    clReleaseKernel(kernel);
    clReleaseMemObject(corner_buf);
    clReleaseMemObject(ray_buf);
    clReleaseMemObject(hit_buf);
    clReleaseMemObject(bounce_buf);
    free(corners);
    free(hits);
    free(bounce_hits);
    free(bounce);
    free(rays);
    scene_release(&scene);
    test_device_release(dev);
}

Test(bvh, offset_rays_leave_a_small_sphere_at_the_origin)
{
    check_offset_rays(mesh_transformed(mesh_icosphere(4), 1e-3f, 0, 0, 0), "icosphere r=1e-3", true);
}
Test(bvh, offset_rays_leave_a_unit_sphere)
{
    check_offset_rays(mesh_transformed(mesh_icosphere(4), 1.0f, 0.3f, -0.2f, 0.1f), "icosphere r=1", true);
}
Test(bvh, offset_rays_leave_a_large_sphere_far_away)
{
    check_offset_rays(mesh_transformed(mesh_icosphere(4), 1e3f, 2e4f, -3e4f, 1e4f), "icosphere r=1e3 at 3e4", true);
}
Test(bvh, offset_rays_leave_a_small_sphere_far_away)
{
    check_offset_rays(mesh_transformed(mesh_icosphere(4), 1.0f, 500.0f, 700.0f, -300.0f), "icosphere r=1 at 900", true);
}
Test(bvh, offset_rays_leave_the_torus) { check_offset_rays(mesh_torus(20000), "torus", false); }

Test(bvh, empty_scene_misses_everything)
{
    Device *dev = test_device();
    TraceScene scene = scene_create(dev, mesh_soup(0, 1));
    cr_expect_eq(scene.bvh.num_nodes, 1u);
    cr_expect_eq(scene.bvh.num_tris, 0u);
    float lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
    memcpy(scene.lo, lo, sizeof lo);
    memcpy(scene.hi, hi, sizeof hi);
    uint64_t rng = 3;
    Ray rays[64];
    for (int i = 0; i < 64; i++) {
        float origin[3] = {0, 0, 0}, dir[3];
        random_direction(&rng, dir);
        rays[i] = make_ray(origin, dir, 0.0f, INFINITY);
    }
    float4 hits[64];
    cl_uint any[64];
    trace(&scene, "bvh_test_trace_closest", rays, 64, hits);
    trace(&scene, "bvh_test_trace_any", rays, 64, any);
    for (int i = 0; i < 64; i++) {
        cr_expect_eq(hit_prim(hits[i]), HIT_NONE_HOST, "ray %d hits an empty scene", i);
        cr_expect_eq(any[i], 0u, "ray %d is occluded in an empty scene", i);
    }
    scene_release(&scene);
    test_device_release(dev);
}
