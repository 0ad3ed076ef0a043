/* SPDX-License-Identifier: MIT */
/* scene_bvh.h: the acceleration structure of a whole scene as the kernels traverse it. One level:
 * the BVH of the one mesh, laid out for the device (bvh_wide.h), exactly v1's. Two levels: one
 * BVH per mesh (BLAS), built once however many instances use it, and a top-level BVH (TLAS) over
 * the instances' world boxes, in one node array (TLAS first, root 0) and one prim array
 * (cl/shared.h "Instances"; cl/geometry/bvh_traverse*.cl walk it). Flat: every instance's
 * triangles baked into world space under one BVH, numbered instance by instance, with each one's
 * (instance, triangle) in flat_prims (cl/geometry/scene_trace.cl maps hits back through it): no
 * per-instance ray set-up, and one tree where the instances' boxes overlap, for memory that grows
 * with the instances. */
#ifndef PT_SCENE_BVH_H
#define PT_SCENE_BVH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/shared_types.h"
#include "base/transform.h"

/* A mesh: its range of the scene's triangle array. */
typedef struct {
    uint32_t first_triangle, num_triangles;
} BvhMesh;

/* An instance as the TLAS sees it: its mesh and its world box (swept over the shutter when it
 * moves), and for a flat BVH its object-to-world matrix (rows of the 3x4, p' = M p). */
typedef struct {
    uint32_t mesh;
    float lo[3], hi[3];
    Affine to_world;
} BvhInstance;

typedef enum {
    BVH_ONE_LEVEL, /* the one mesh, in world space */
    BVH_TWO_LEVEL, /* a TLAS over the instances, a BLAS per mesh */
    BVH_FLAT,      /* the instances baked into one world-space BVH (static instances only) */
} BvhLevels;

typedef struct {
    int width;      /* 2, 4 or 8 (bvh_wide.h) */
    bool quantized; /* 2-wide with 32-byte nodes */
    BvhLevels levels;
    void *nodes;    /* BvhNode, BvhNodeQuantized, BvhNode4 or BvhNode8; nodes[0] is the root */
    size_t node_size;
    uint32_t num_nodes;
    void *prims;    /* BvhTriangle or triangle packs; prim indices are the scene's triangles (flat:
                       indices into flat_prims) */
    size_t prim_size;
    uint32_t num_prims;
    uint32_t *flat_prims;     /* BVH_FLAT: (instance, triangle) pairs, in (instance, triangle) order */
    uint32_t num_flat_prims;  /* pairs */
    /* Per mesh (two levels; one level: mesh 0 only): its BLAS root in nodes, and its range of
     * prims (the brute-force ablation's). */
    uint32_t *blas_root, *first_prim, *num_mesh_prims;
    uint32_t num_meshes;
    uint32_t tlas_nodes;   /* nodes of the TLAS (0 for one level and flat) */
    double blas_seconds, tlas_seconds; /* build times */
    double sah_cost;       /* one level: the BVH's SAH cost (bvh.h) */
} SceneBvh;

/* Builds for the device layout (width, quantized). BVH_ONE_LEVEL needs num_meshes == 1 and
 * ignores the instances (the mesh is in world space). Dies only on a tree the layouts cannot
 * index (as bvh_build) and when out of memory. */
void scene_bvh_build(SceneBvh *out, const float4 *positions, const Triangle *triangles,
                     const BvhMesh *meshes, uint32_t num_meshes, const BvhInstance *instances,
                     uint32_t num_instances, int width, bool quantized, BvhLevels levels);
void scene_bvh_free(SceneBvh *bvh);
/* Frees the nodes, prims and flat_prims once the device holds its copies (a flat BVH at the
 * budget is ~90 MiB); the counts, levels, per-mesh arrays and build times stay. */
void scene_bvh_drop_arrays(SceneBvh *bvh);

#endif
