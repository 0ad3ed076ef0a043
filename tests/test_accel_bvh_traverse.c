// SPDX-License-Identifier: MIT
/* BVH traversal on the test device (PoCL), in the layout PT_BVH_WIDTH / PT_BVH_QUANTIZED choose:
 * trace_closest and trace_any reproduce a brute-force loop over the same watertight test for
 * random rays into procedural meshes, a triangle soup with exact ties, the depth-limited tree and
 * the public assets; rays aimed exactly at shared edges and vertices of closed meshes never leak;
 * axis-parallel rays along grid lines hit at the exact distance; secondary rays from
 * offset_ray_origin never re-hit their own triangle; an empty scene misses everything. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/bvh_wide.h"
#include "bvh_fixtures.h"
#include "io/obj_loader.h"
#include "procedural_mesh.h"
#include "support.h"

#define RAYS_PER_MESH 10000

static void check_mesh_against_brute_force(TestMesh mesh, const char *name, uint64_t seed)
{
    Device *dev = test_device();
    TraceScene scene = trace_scene_create(dev, mesh);
    check_tree_with_costs(&scene.bvh, &scene.mesh, name, bvh_costs_for_width(dev->bvh_width));
    Ray *rays = random_rays(&scene, RAYS_PER_MESH, seed);
    uint32_t num_hits = check_against_brute_force(&scene, rays, RAYS_PER_MESH, name);
    /* Most rays are aimed into the bounds: a test where nothing hits would prove little. */
    cr_expect_gt(num_hits, RAYS_PER_MESH / 5, "%s: only %u of %u rays hit", name, num_hits,
                 RAYS_PER_MESH);
    free(rays);
    trace_scene_release(&scene);
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
    TraceScene scene = trace_scene_create(dev, mesh_axis_chains(1280));
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
    trace_scene_release(&scene);
    test_device_release(dev);
}
Test(bvh, matches_brute_force_on_single_triangle) { check_mesh_against_brute_force(mesh_soup(1, 6), "one triangle", 6); }

static void check_asset_against_brute_force(const char *relative_path, uint64_t seed)
{
    REQUIRE_ASSETS();
    char path[512];
    snprintf(path, sizeof path, "%s/%s", ASSETS_DIR, relative_path);
    Mesh obj;
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(obj_load(path, &obj, &err), "%s", err.message);
    TestMesh mesh = mesh_from_obj(&obj);
    mesh_free(&obj);
    check_mesh_against_brute_force(mesh, relative_path, seed);
}

Test(bvh, matches_brute_force_on_bunny) { check_asset_against_brute_force("stanford-bunny/stanford-bunny.obj", 11); }
Test(bvh, matches_brute_force_on_dragon) { check_asset_against_brute_force("stanford-dragon/dragon.obj", 12); }
Test(bvh, matches_brute_force_on_skull) { check_asset_against_brute_force("skull/skull.obj", 13); }
Test(bvh, matches_brute_force_on_cornell_original) { check_asset_against_brute_force("cornell-box/CornellBox-Original.obj", 14); }
Test(bvh, matches_brute_force_on_cornell_sphere) { check_asset_against_brute_force("cornell-box/CornellBox-Sphere.obj", 15); }

/* Rays aimed exactly at every vertex and edge midpoint of a closed mesh around the origin: from
 * outside (from the side the point faces) and from inside (near the centre). Every one must hit,
 * in the BVH and in the reference; a test with a rounding gap at shared edges leaks some. */
static void check_watertight(TestMesh mesh, const char *name)
{
    Device *dev = test_device();
    TraceScene scene = trace_scene_create(dev, mesh);
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
        if (hit_prim(hits[i]) == HIT_NONE && leaks++ < 5)
            cr_log_error("%s: ray %u at a shared edge or vertex leaks through the BVH", name, i);
        if (hit_prim(brute_force_closest(&scene, &rays[i])) == HIT_NONE)
            reference_leaks++;
    }
    cr_expect_eq(leaks, 0, "%s: %u of %u rays through edges and vertices leak", name, leaks, n);
    cr_expect_eq(reference_leaks, 0, "%s: %u of %u leak through the reference test", name,
                 reference_leaks, n);
    free(rays);
    free(hits);
    trace_scene_release(&scene);
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
    TraceScene scene = trace_scene_create(dev, mesh_cube_grid(k));
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
        if ((hit_prim(hits[i]) == HIT_NONE || hits[i].s[0] != expected_t[i] || !any[i]) &&
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
    trace_scene_release(&scene);
    test_device_release(dev);
}

/* Scales the mesh about the origin, then moves it. */
static TestMesh mesh_transformed(TestMesh mesh, float scale, float dx, float dy, float dz)
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
static void check_offset_rays(TestMesh mesh, const char *name, bool convex)
{
    Device *dev = test_device();
    TraceScene scene = trace_scene_create(dev, mesh);
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
        KERNEL_ARGS(kernel, 0, KARG(corner_buf), KARG(ray_buf), KARG(hit_buf), KARG(num_rays),
                    KARG(seed), KARG(reflect), KARG(bounce_buf));
        device_run(dev, kernel, n, 0, NULL);
        device_read(dev, bounce_buf, 0, n * sizeof(Ray), bounce);
        trace(&scene, "bvh_test_trace_closest", bounce, n, bounce_hits);
        uint32_t sources = 0, self_hits = 0, wrong = 0;
        for (uint32_t i = 0; i < n; i++) {
            uint32_t source = hit_prim(hits[i]), prim = hit_prim(bounce_hits[i]);
            if (source == HIT_NONE)
                continue;
            sources++;
            if (prim == source && self_hits++ < 5)
                cr_log_error("%s: %s ray %u re-hits its triangle %u at t %g", name,
                             reflect ? "reflected" : "transmitted", i, source, bounce_hits[i].s[0]);
            if (convex && (reflect ? prim != HIT_NONE : prim == HIT_NONE) && wrong++ < 5)
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
    trace_scene_release(&scene);
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
    TraceScene scene = trace_scene_create(dev, mesh_soup(0, 1));
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
        cr_expect_eq(hit_prim(hits[i]), HIT_NONE, "ray %d hits an empty scene", i);
        cr_expect_eq(any[i], 0u, "ray %d is occluded in an empty scene", i);
    }
    trace_scene_release(&scene);
    test_device_release(dev);
}
