/* SPDX-License-Identifier: MIT */
/* bvh_wide.h: the BVH as a device traverses it. GPUs take the 2-wide tree of bvh.h as it is; CPUs
 * take it collapsed into 4- or 8-wide nodes over triangle packs (cl/shared.h, BvhNode4/8), which
 * cl/geometry/bvh_traverse_wide.cl tests with one SIMD operation per node or pack. */
#ifndef PT_BVH_WIDE_H
#define PT_BVH_WIDE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "accel/bvh.h"

typedef struct {
    int width;           /* 2, 4 or 8 */
    const void *nodes;   /* BvhNode, BvhNode4 or BvhNode8; nodes[0] is the root */
    size_t node_size;
    uint32_t num_nodes;
    const void *prims;   /* BvhTriangle, TrianglePack4 or TrianglePack8 */
    size_t prim_size;
    uint32_t num_prims;
    uint32_t max_stack;  /* wide: the most stack entries any traversal can hold */
    void *owned;         /* wide: the arrays above, freed by bvh_layout_free */
} BvhLayout;

/* The layout of bvh for the given width (2: bvh's own arrays, which must outlive the layout, or
 * with quantized its nodes quantised to 32 bytes (bvh_quantized.h); 4 or 8: collapsed copies). Each wide node takes the 2-wide children and opens the one with the
 * largest surface area until it has width children (Wald et al. 2008, "Getting rid of packets"),
 * as far as the traversal stack allows; each leaf becomes ceil(count / width) packs. */
void bvh_layout(BvhLayout *out, const Bvh *bvh, int width, bool quantized);

/* A TLAS (bvh_build_over_boxes) collapsed to 4 or 8 wide: its leaves stay ~instance, no packs. */
void bvh_layout_tlas(BvhLayout *out, const Bvh *tlas, int width);

/* The SAH costs to build the 2-wide tree with for a layout. A wide layout tests a leaf's pack of
 * up to `width` triangles in about the time of one triangle, so its leaves may be fuller: a
 * triangle costs 0.3 of a node step there (PoCL, dragon in a lit box: +15-20% Mpaths/s against
 * 1.0; Cornell box within noise). */
#define BVH_WIDE_COST_INTERSECT 0.3f
BvhCosts bvh_costs_for_width(int width);
/* bvh_build with bvh_costs_for_width(width). */
void bvh_build_for_width(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n,
                         int width);
void bvh_layout_free(BvhLayout *layout);

#endif
