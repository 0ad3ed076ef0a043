// SPDX-License-Identifier: MIT
/* bvh_wide.c: collapses the 2-wide BVH of bvh.h into the 4- or 8-wide layout of
 * cl/geometry/bvh_traverse_wide.cl. Nodes are written depth first, parent before children; packs in leaf
 * order. */
#include "accel/bvh_wide.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh_quantized.h"
#include "base/error.h"

_Static_assert(offsetof(BvhNode4, child) == 6 * 4 * sizeof(float), "BvhNode4: six rows, then child");
_Static_assert(offsetof(BvhNode8, child) == 6 * 8 * sizeof(float), "BvhNode8: six rows, then child");
_Static_assert(offsetof(TrianglePack4, prim) == 9 * 4 * sizeof(float), "TrianglePack4: nine rows, then prim");
_Static_assert(offsetof(TrianglePack8, prim) == 9 * 8 * sizeof(float), "TrianglePack8: nine rows, then prim");
/* A leaf's packs are counted in BVH_WIDE_LEAF_PACK_BITS bits. */
_Static_assert(BVH_MAX_LEAF_SIZE <= 4 << BVH_WIDE_LEAF_PACK_BITS, "leaves too large for a pack count");

/* One child of a 2-wide node: its box and reference (inner: index, count 0; leaf: ~first, count). */
typedef struct {
    float lo[3], hi[3];
    uint32_t ref, count;
} Child;

typedef struct {
    const Bvh *bvh;
    int width;
    uint8_t *nodes, *packs;
    size_t node_size, pack_size;
    uint32_t num_nodes, num_packs;
    uint8_t *height;      /* per 2-wide node: inner levels below it, itself included */
    bool instance_leaves; /* a TLAS: leaves name instances (~i), no packs */
    uint32_t max_stack;
} Widener;

static Child child_of(const BvhNode *node, int right)
{
    const float4 *lo = right ? &node->rmin : &node->lmin, *hi = right ? &node->rmax : &node->lmax;
    Child c;
    for (int k = 0; k < 3; k++)
        c.lo[k] = lo->s[k], c.hi[k] = hi->s[k];
    memcpy(&c.ref, &lo->s[3], sizeof c.ref);
    memcpy(&c.count, &hi->s[3], sizeof c.count);
    return c;
}

static bool is_inner(const Child *c) { return c->count == 0 && (int32_t)c->ref >= 0; }

static double half_area(const Child *c)
{
    double d[3];
    for (int k = 0; k < 3; k++)
        d[k] = fmax(0.0, (double)c->hi[k] - (double)c->lo[k]);
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

static uint8_t measure_height(Widener *w, uint32_t index)
{
    uint8_t h = 0;
    for (int side = 0; side < 2; side++) {
        Child c = child_of(&w->bvh->nodes[index], side);
        if (is_inner(&c)) {
            uint8_t below = measure_height(w, c.ref);
            h = below > h ? below : h;
        }
    }
    w->height[index] = (uint8_t)(h + 1);
    return w->height[index];
}

static float *node_row(Widener *w, uint32_t node, int row)
{
    return (float *)(w->nodes + node * w->node_size) + row * w->width;
}

/* The packs of a leaf; returns its reference. */
static uint32_t emit_leaf(Widener *w, const Child *leaf)
{
    if (w->instance_leaves)
        return leaf->ref;
    uint32_t first = ~leaf->ref, count = leaf->count, width = (uint32_t)w->width;
    uint32_t num = (count + width - 1) / width;
    if (num > 1u << BVH_WIDE_LEAF_PACK_BITS)
        die("BVH: a leaf of %u triangles is more than %u packs of %u", count,
            1u << BVH_WIDE_LEAF_PACK_BITS, width);
    uint32_t pack0 = w->num_packs;
    for (uint32_t p = 0; p < num; p++) {
        float *rows = (float *)(w->packs + (size_t)w->num_packs++ * w->pack_size);
        uint32_t *prim = (uint32_t *)(rows + 9 * width);
        for (uint32_t lane = 0; lane < width; lane++) {
            uint32_t i = p * width + lane;
            const BvhTriangle *t = &w->bvh->tris[first + (i < count ? i : count - 1)];
            const float4 *corner[3] = {&t->v0, &t->v1, &t->v2};
            for (int c = 0; c < 3; c++)
                for (int k = 0; k < 3; k++)
                    rows[(3 * c + k) * width + lane] = corner[c]->s[k];
            memcpy(&prim[lane], &t->v0.s[3], sizeof prim[lane]);
        }
    }
    return ~(pack0 << BVH_WIDE_LEAF_PACK_BITS | (num - 1));
}

/* The wide node for 2-wide node `index`, reached with `stacked` entries on the traversal stack;
 * returns its index. */
static uint32_t emit_node(Widener *w, uint32_t index, uint32_t stacked)
{
    Child c[8];
    c[0] = child_of(&w->bvh->nodes[index], 0);
    c[1] = child_of(&w->bvh->nodes[index], 1);
    int n = 2;
    while (n < w->width) {
        /* The stack this node fills (n - 1 entries, n after opening one more child) plus the
         * deepest 2-wide walk below must fit: then every subtree can at least stay 2-wide. */
        int best = -1;
        double best_area = -1.0;
        uint32_t deepest = 0;
        for (int i = 0; i < n; i++)
            if (is_inner(&c[i])) {
                deepest = w->height[c[i].ref] > deepest ? w->height[c[i].ref] : deepest;
                if (half_area(&c[i]) > best_area)
                    best = i, best_area = half_area(&c[i]);
            }
        if (best < 0 || stacked + (uint32_t)n + deepest > BVH_WIDE_STACK_SIZE)
            break;
        const BvhNode *opened = &w->bvh->nodes[c[best].ref];
        c[best] = child_of(opened, 0);
        c[n++] = child_of(opened, 1);
    }
    uint32_t node = w->num_nodes++;
    int used = 0;
    for (int i = 0; i < n; i++)
        used += is_inner(&c[i]) || c[i].count > 0;
    uint32_t pushes = used > 0 ? (uint32_t)used - 1 : 0;
    if (stacked + pushes > w->max_stack)
        w->max_stack = stacked + pushes;
    uint32_t refs[8];
    int lane = 0;
    for (int i = 0; i < n; i++) {
        if (is_inner(&c[i]))
            refs[lane] = emit_node(w, c[i].ref, stacked + pushes);
        else if (c[i].count > 0)
            refs[lane] = emit_leaf(w, &c[i]);
        else
            continue; /* an empty leaf (the empty scene's): nothing to test */
        for (int k = 0; k < 3; k++) {
            node_row(w, node, k)[lane] = c[i].lo[k];
            node_row(w, node, 3 + k)[lane] = c[i].hi[k];
        }
        lane++;
    }
    uint32_t *child = (uint32_t *)node_row(w, node, 6);
    for (int i = 0; i < w->width; i++) {
        child[i] = i < lane ? refs[i] : 0u;
        if (i >= lane)
            for (int k = 0; k < 3; k++) {
                node_row(w, node, k)[i] = INFINITY;
                node_row(w, node, 3 + k)[i] = -INFINITY;
            }
    }
    return node;
}

static void collapse(BvhLayout *out, const Bvh *bvh, int width, bool instance_leaves);

void bvh_layout(BvhLayout *out, const Bvh *bvh, int width, bool quantized)
{
    memset(out, 0, sizeof *out);
    out->width = width;
    if (width == 2 && quantized) {
        BvhNodeQuantized *nodes = bvh_quantize(bvh);
        *out = (BvhLayout){2, nodes, sizeof *nodes, bvh->num_nodes, bvh->tris, sizeof(BvhTriangle),
                           bvh->num_tris, BVH_STACK_SIZE, nodes};
        return;
    }
    if (width == 2) {
        *out = (BvhLayout){2, bvh->nodes, sizeof(BvhNode), bvh->num_nodes, bvh->tris,
                           sizeof(BvhTriangle), bvh->num_tris, BVH_STACK_SIZE, NULL};
        return;
    }
    collapse(out, bvh, width, false);
}

void bvh_layout_tlas(BvhLayout *out, const Bvh *tlas, int width)
{
    collapse(out, tlas, width, true);
}

static void collapse(BvhLayout *out, const Bvh *bvh, int width, bool instance_leaves)
{
    if (width != 4 && width != 8)
        die("BVH width %d: the layouts are 2, 4 and 8 wide", width);
    Widener w = {.bvh = bvh, .width = width, .instance_leaves = instance_leaves};
    w.node_size = width == 4 ? sizeof(BvhNode4) : sizeof(BvhNode8);
    w.pack_size = width == 4 ? sizeof(TrianglePack4) : sizeof(TrianglePack8);
    /* At most one wide node per 2-wide node, and one pack per triangle. */
    size_t node_bytes = (size_t)bvh->num_nodes * w.node_size;
    size_t pack_bytes = (size_t)(bvh->num_tris ? bvh->num_tris : 1) * w.pack_size;
    size_t total = (node_bytes + pack_bytes + 63) / 64 * 64;
    uint8_t *memory = aligned_alloc(64, total);
    w.height = malloc(bvh->num_nodes);
    if (!memory || !w.height)
        die("out of memory for the %d-wide BVH (%u nodes)", width, bvh->num_nodes);
    memset(memory, 0, total); /* the empty scene's pack stays zero (and unused) */
    w.nodes = memory;
    w.packs = memory + node_bytes;
    measure_height(&w, 0);
    emit_node(&w, 0, 0);
    free(w.height);
    if (w.max_stack > BVH_WIDE_STACK_SIZE)
        die("BVH: the %d-wide tree needs %u stack entries, more than %d", width, w.max_stack,
            BVH_WIDE_STACK_SIZE);
    *out = (BvhLayout){width, w.nodes, w.node_size, w.num_nodes, w.packs, w.pack_size,
                       w.num_packs, w.max_stack, memory};
}

void bvh_layout_free(BvhLayout *layout)
{
    free(layout->owned);
    memset(layout, 0, sizeof *layout);
}

BvhCosts bvh_costs_for_width(int width)
{
    return width == 2 ? BVH_COSTS_DEFAULT : (BvhCosts){BVH_COST_TRAVERSAL, BVH_WIDE_COST_INTERSECT};
}

void bvh_build_for_width(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n,
                         int width)
{
    bvh_build_with_costs(bvh, positions, triangles, n, bvh_costs_for_width(width));
}
