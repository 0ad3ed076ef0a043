/* SPDX-License-Identifier: MIT */
/* bvh.h: binned-SAH BVH over all scene triangles, flattened for cl/geometry/bvh_traverse.cl. */
#ifndef PT_BVH_H
#define PT_BVH_H

#include <stdint.h>

#include "base/shared_types.h"

/* Split search: centroid bins per axis, and the SAH costs in units of one triangle test. A node
 * costs about one triangle test: it is one 64-byte fetch and two box tests, against the
 * watertight test's permutation, shear and three edge functions. */
#define BVH_BINS 16
#define BVH_BIN_SAMPLE_FROM 1000 /* nodes this large bin every 2nd record, 10x larger every 3rd... */
#define BVH_SMALL_NODE 8          /* nodes up to this size sweep every split exactly instead */
/* The next three may be overridden with -D for experiments (tools/bench_bvh). */
#ifndef BVH_MAX_LEAF_SIZE
#define BVH_MAX_LEAF_SIZE 8
#endif
#ifndef BVH_COST_TRAVERSAL
#define BVH_COST_TRAVERSAL 1.0f
#endif
#ifndef BVH_COST_INTERSECT
#define BVH_COST_INTERSECT 1.0f
#endif

/* SAH costs; bvh_build uses BVH_COSTS_DEFAULT, the 2-wide layout's (bvh_wide.h has the others). */
typedef struct {
    float traversal, intersect;
} BvhCosts;
#define BVH_COSTS_DEFAULT ((BvhCosts){BVH_COST_TRAVERSAL, BVH_COST_INTERSECT})

typedef struct {
    BvhNode *nodes;     /* nodes[0] is the root */
    uint32_t num_nodes;
    BvhTriangle *tris;  /* triangles in leaf order; v0.w holds the original index */
    uint32_t num_tris;
    double sah_cost;    /* SAH cost: (C_t sum of inner areas + C_i sum of leaf areas x counts) / root area */
} Bvh;

/* Builds over triangles[0..n) with corners in positions. Never fails on valid input (n >= 1). */
void bvh_build(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n);
/* The same with other SAH costs (sah_cost is then in those units). */
void bvh_build_with_costs(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n,
                          BvhCosts costs);
/* Reference for tests and benchmarks: the same tree rules, but every split position between
 * sorted centroids is evaluated (O(n log^2 n), slow). Compare sah_cost with bvh_build's. */
void bvh_build_full_sweep(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n);
/* A tree over n boxes (an instance's world box each: the TLAS, host/accel/scene_bvh.h) with one
 * box per leaf, named by its index: leaf references are ~i with count 1; tris stays NULL. */
void bvh_build_over_boxes(Bvh *bvh, const float (*lo)[3], const float (*hi)[3], uint32_t n);
void bvh_free(Bvh *bvh);

#endif
