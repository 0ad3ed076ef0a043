/* SPDX-License-Identifier: MIT */
/* bvh_fixtures.h: what the BVH tests (tests/test_accel_bvh_*.c) share. bvh_fixtures.c: the host-side
 * invariants of a built tree and the builder's awkward meshes; bvh_fixtures_trace.c: a mesh on the
 * test device, traced by the batch kernels of tests/cl/bvh_test.cl, and random rays into it;
 * bvh_fixtures_reference.c: the brute-force reference those traces are compared with. */
#ifndef PT_BVH_FIXTURES_H
#define PT_BVH_FIXTURES_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "accel/bvh.h"
#include "device/device.h"
#include "procedural_mesh.h"


/* ---- Host-side invariants (bvh_fixtures.c) ------------------------------------------------- */

/* Every invariant of a built tree (boxes contain what is below them, every triangle in exactly
 * one leaf, pre-order layout, bounded depth, stored SAH cost in the given costs); returns the
 * deepest inner node's depth. */
int check_tree_with_costs(const Bvh *bvh, const TestMesh *mesh, const char *name, BvhCosts costs);

/* Three chains of unit triangles along the axes, the i-th at distance (16/15)^i (up to 1e36).
 * A binned split only takes the far sixteenth of one axis's range off (a few dozen triangles),
 * so SAH alone would build a tree about 90 levels deep. */
TestMesh mesh_axis_chains(uint32_t per_axis);
/* n copies of one triangle. */
TestMesh mesh_copies(uint32_t n);

/* ---- Tracing on the device (bvh_fixtures_trace.c) ------------------------------------------ */

/* Ray as the test kernels read it: origin with tmin in w, direction with tmax in w. */
typedef struct {
    float4 origin;
    float4 dir;
} Ray;

typedef struct {
    Device *dev;
    TestMesh mesh;
    Bvh bvh;
    cl_mem nodes, tris;
    uint32_t num_prims; /* entries of tris (triangles, or packs of the wide layout) */
    float4 *spheres; /* per triangle, for the brute-force reference's culling */
    float lo[3], hi[3];
} TraceScene;

/* Builds mesh's tree for the device's layout and uploads it; takes the mesh over. */
TraceScene trace_scene_create(Device *dev, TestMesh mesh);
void trace_scene_release(TraceScene *scene);
/* Runs bvh_test_trace_closest or _any over rays; out gets one float4 (closest) or uint (any) per
 * ray. */
void trace(TraceScene *scene, const char *kernel_name, const Ray *rays, uint32_t n, void *out);

void random_direction(uint64_t *rng, float dir[3]);
/* A mix of the rays a renderer traces and the awkward ones (malloc'ed). */
Ray *random_rays(const TraceScene *scene, uint32_t n, uint64_t seed);

static inline float4 vec(float x, float y, float z, float w)
{
    float4 v = {{x, y, z, w}};
    return v;
}

static inline uint32_t hit_prim(float4 hit)
{
    uint32_t prim;
    memcpy(&prim, &hit.s[3], sizeof prim);
    return prim;
}

static inline Ray make_ray(const float origin[3], const float dir[3], float tmin, float tmax)
{
    Ray ray = {vec(origin[0], origin[1], origin[2], tmin), vec(dir[0], dir[1], dir[2], tmax)};
    return ray;
}

static inline void normalize3(float v[3])
{
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++)
        v[k] /= len;
}

/* ---- Host reference (bvh_fixtures_reference.c) --------------------------------------------- */

/* Closest hit of r over every triangle of the scene's mesh, by the kernel's watertight test. */
float4 brute_force_closest(const TraceScene *scene, const Ray *r);
/* The BVH's closest hits equal the brute-force loop's for every ray, and any-hit answers as the
 * closest hit does; then, for rays that hit, any-hit with tmax at the hit sees nothing and with
 * tmax one ulp further sees it. Returns how many rays hit. */
uint32_t check_against_brute_force(TraceScene *scene, const Ray *rays, uint32_t n, const char *name);

#endif
