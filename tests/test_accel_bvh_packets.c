// SPDX-License-Identifier: MIT
/* trace_packet (cl/geometry/bvh_traverse_packet.cl): eight rays walked together through the 8-wide
 * layout report, lane by lane, what trace_bvh reports for each ray alone, bit for bit (closest hit
 * with its t, barycentrics and triangle; any-hit answer), and so what the brute-force loop reports
 * (test_accel_bvh_traverse.c). Rays come as packets of eight: the renderer's mix of awkward rays (tmin >
 * 0, finite tmax, axis-parallel with signed zeros) one per lane, bundles of nearly parallel rays
 * from nearly one point (which walk together deep into the tree), identical lanes, and two bundles
 * interleaved (which part at the root); the count is no multiple of eight, so the last packet has
 * empty lanes. The device is asked for the 8-wide layout (PT_BVH_WIDTH=8), on GPUs too. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh_fixtures.h"
#include "io/obj_loader.h"
#include "procedural_mesh.h"
#include "support.h"

#define PACKETS 2500
#define NUM_RAYS (8 * PACKETS - 3)

/* Lane i of a bundle: base moved by up to `spread` (of the bounds' radius) in origin and about as
 * much in direction. */
static Ray jittered(const Ray *base, float radius, float spread, uint64_t *rng)
{
    float origin[3], dir[3];
    for (int k = 0; k < 3; k++) {
        origin[k] = base->origin.s[k] + spread * radius * (mesh_rng_float(rng) - 0.5f);
        dir[k] = base->dir.s[k] + spread * (mesh_rng_float(rng) - 0.5f);
    }
    normalize3(dir);
    return make_ray(origin, dir, base->origin.s[3], base->dir.s[3]);
}

static Ray *packet_rays(const TraceScene *scene, uint64_t seed)
{
    Ray *base = random_rays(scene, 2 * PACKETS, seed);
    Ray *rays = malloc(8 * PACKETS * sizeof *rays);
    float radius = 0.0f;
    for (int k = 0; k < 3; k++)
        radius += 0.25f * (scene->hi[k] - scene->lo[k]) * (scene->hi[k] - scene->lo[k]);
    radius = sqrtf(radius);
    uint64_t rng = seed * 7919u + 1u;
    for (uint32_t p = 0; p < PACKETS; p++) {
        Ray *lane = &rays[8 * p];
        switch (p % 4) {
        case 0: /* eight unrelated rays */
            for (int i = 0; i < 8; i++)
                lane[i] = base[(8 * p + (uint32_t)i) % (2 * PACKETS)];
            break;
        case 1: /* a tight bundle */
            for (int i = 0; i < 8; i++)
                lane[i] = jittered(&base[2 * p], radius, 0.01f, &rng);
            break;
        case 2: /* one ray eight times (ties between lanes) */
            for (int i = 0; i < 8; i++)
                lane[i] = base[2 * p];
            break;
        default: /* two loose bundles, interleaved */
            for (int i = 0; i < 8; i++)
                lane[i] = jittered(&base[2 * p + (uint32_t)(i & 1)], radius, 0.1f, &rng);
        }
    }
    free(base);
    return rays;
}

static void check_packets_equal_single_rays(TestMesh mesh, const char *name, uint64_t seed)
{
    setenv("PT_BVH_WIDTH", "8", 1);
    Device *dev = test_device();
    unsetenv("PT_BVH_WIDTH");
    cr_assert_eq(dev->bvh_width, 8, "the device did not take the 8-wide layout");
    TraceScene scene = trace_scene_create(dev, mesh);
    Ray *rays = packet_rays(&scene, seed);
    uint32_t n = NUM_RAYS;
    float4 *single = malloc(n * sizeof *single), *packed = malloc(n * sizeof *packed);
    cl_uint *any_single = malloc(n * sizeof *any_single), *any_packed = malloc(n * sizeof *any_packed);
    trace(&scene, "bvh_test_trace_closest", rays, n, single);
    trace(&scene, "bvh_test_trace_closest_packet", rays, n, packed);
    trace(&scene, "bvh_test_trace_any", rays, n, any_single);
    trace(&scene, "bvh_test_trace_any_packet", rays, n, any_packed);
    uint32_t closest_differ = 0, any_differ = 0, hits = 0, first = n;
    for (uint32_t i = 0; i < n; i++) {
        bool differs = memcmp(&single[i], &packed[i], sizeof single[i]) != 0;
        closest_differ += differs;
        any_differ += any_single[i] != any_packed[i];
        hits += hit_prim(single[i]) != 0xffffffffu;
        if ((differs || any_single[i] != any_packed[i]) && first == n)
            first = i;
    }
    cr_expect_eq(closest_differ, 0, "%s: %u of %u closest hits differ (first: ray %u, t %g prim %u "
                 "alone, t %g prim %u in its packet)", name, closest_differ, n, first,
                 first < n ? single[first].s[0] : 0.0f, first < n ? hit_prim(single[first]) : 0u,
                 first < n ? packed[first].s[0] : 0.0f, first < n ? hit_prim(packed[first]) : 0u);
    cr_expect_eq(any_differ, 0, "%s: %u of %u any-hit answers differ (first: ray %u)", name,
                 any_differ, n, first);
    /* A test where nothing hits, or everything, would prove little. */
    cr_expect(hits > n / 5 && hits < n - n / 20, "%s: %u of %u rays hit", name, hits, n);
    free(single), free(packed), free(any_single), free(any_packed), free(rays);
    trace_scene_release(&scene);
    test_device_release(dev);
}

Test(bvh_packets, equal_single_rays_on_icosphere) { check_packets_equal_single_rays(mesh_icosphere(5), "icosphere", 1); }
Test(bvh_packets, equal_single_rays_on_cube_grid) { check_packets_equal_single_rays(mesh_cube_grid(16), "cube", 2); }
Test(bvh_packets, equal_single_rays_on_torus) { check_packets_equal_single_rays(mesh_torus(20000), "torus", 3); }
/* Overlapping triangles, some coplanar: hits tie at one t and go to the lower index. */
Test(bvh_packets, equal_single_rays_on_overlapping_soup) { check_packets_equal_single_rays(mesh_soup(20000, 4), "soup", 4); }
Test(bvh_packets, equal_single_rays_on_one_triangle) { check_packets_equal_single_rays(mesh_soup(1, 6), "one triangle", 6); }

Test(bvh_packets, equal_single_rays_on_dragon)
{
    REQUIRE_ASSETS();
    Mesh obj;
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(obj_load(ASSETS_DIR "/stanford-dragon/dragon.obj", &obj, &err), "%s", err.message);
    TestMesh mesh = mesh_from_obj(&obj);
    mesh_free(&obj);
    check_packets_equal_single_rays(mesh, "dragon", 12);
}
