/* SPDX-License-Identifier: MIT */
/* bvh.h: binned-SAH BVH over all scene triangles, flattened for cl/bvh_traverse.cl. */
#ifndef PT_BVH_H
#define PT_BVH_H

#include <stdint.h>

#include "shared_types.h"

typedef struct {
    BvhNode *nodes;     /* nodes[0] is the root */
    uint32_t num_nodes;
    BvhTriangle *tris;  /* triangles in leaf order; v0.w holds the original index */
    uint32_t num_tris;
    double sah_cost;    /* SAH cost of the whole tree (see bvh.c for the constants) */
} Bvh;

/* Builds over triangles[0..n) with corners in positions. Never fails on valid input (n >= 1). */
void bvh_build(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n);
void bvh_free(Bvh *bvh);

#endif
