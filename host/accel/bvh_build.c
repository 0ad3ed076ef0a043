// SPDX-License-Identifier: MIT
/* bvh_build.c: binned-SAH BVH over all triangles (Wald 2007, "On fast Construction of SAH-based
 * Bounding Volume Hierarchies"), written straight into the node array in the order
 * cl/geometry/bvh_traverse.cl walks it: depth first, pre-order, so an inner left child sits right
 * after its parent. The build reorders one array of per-triangle records in place; every leaf is a
 * contiguous range of it, and bvh->tris is that array's order. This file holds the tree and the
 * API; the split searches are in bvh_sah.c (and bvh_full_sweep.c), the partitions in
 * bvh_partition.c, the box arithmetic in box.h. */
#ifdef __linux__
#define _DEFAULT_SOURCE /* madvise */
#endif
#include "accel/bvh.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#ifdef __linux__
#include <sys/mman.h>
#endif

#include "accel/bvh_internal.h"
#include "base/error.h"

typedef struct {
    uint32_t ref;   /* inner: node index; leaf: ~first triangle */
    uint32_t count; /* leaf: triangle count; inner: 0 */
} ChildRef;

static int ceil_log2(uint32_t n)
{
    int bits = 0;
    while (bits < 32 && (1ull << bits) < n)
        bits++;
    return bits;
}

/* Splits prims[begin, end) for an inner node (reordering it, filling part), or returns false
 * when the range should be a leaf. */
static bool choose_split(Builder *b, uint32_t begin, uint32_t end, const Box *box,
                         const Box *centroids, int depth, Partition *part)
{
    const bool leaf = false;
    uint32_t n = end - begin;
    /* Past this depth only balanced splits keep the traversal stack from overflowing: along any
     * path depth + ceil(log2(n)) never exceeds BVH_STACK_SIZE (see the tests). The log is at
     * most 32: shallower nodes need not take it. */
    bool must_balance = depth + 32 >= BVH_STACK_SIZE && depth + ceil_log2(n) >= BVH_STACK_SIZE;
    if (n == 1 || (n <= b->max_leaf && must_balance))
        return leaf;
    if (!must_balance) {
        if (!b->full_sweep && n <= BVH_SMALL_NODE)
            return bvh_split_small_node(b, begin, end, box, part);
        Split split = b->full_sweep ? bvh_find_full_sweep_split(b, begin, end, box)
                                    : bvh_find_binned_split(b, begin, end, box, centroids);
        if (split.axis >= 0) {
            if (n <= b->max_leaf && b->costs.intersect * (double)n <= split.cost)
                return leaf;
            if (b->full_sweep) {
                *part = bvh_partition_at(b, begin, split.mid, end);
                return true;
            }
            float lo[4], hi[4];
            box_corners(centroids, lo, hi);
            float plane = lo[split.axis] + (float)split.bin / split.scale;
            *part = bvh_partition_at_plane(b, begin, end, split.axis, plane);
            if (part->mid != begin && part->mid != end)
                return true;
        }
    }
    if (n <= b->max_leaf)
        return leaf;
    /* Object median on the widest centroid axis (all centroids equal: any order will do). */
    float lo[4], hi[4];
    box_corners(centroids, lo, hi);
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (hi[k] - lo[k] > hi[axis] - lo[axis])
            axis = k;
    if (hi[axis] > lo[axis])
        bvh_sort_by_centroid(b, begin, end, axis);
    *part = bvh_partition_at(b, begin, begin + n / 2, end);
    return true;
}

static void set_child(float4 *lo, float4 *hi, const Box *box, ChildRef ref)
{
    lanes_store(lo->s, box->lo);
    lanes_store(hi->s, box->hi);
    memcpy(&lo->s[3], &ref.ref, sizeof ref.ref);
    memcpy(&hi->s[3], &ref.count, sizeof ref.count);
}

/* Builds the subtree over prims[begin, end), whose box and centroid box are given. */
static ChildRef build_subtree(Builder *b, uint32_t begin, uint32_t end, const Box *box,
                              const Box *centroids, int depth)
{
    Partition part;
    if (!choose_split(b, begin, end, box, centroids, depth, &part)) {
        b->cost_sum += b->costs.intersect * (end - begin) * box_half_area(box);
        return (ChildRef){~begin, end - begin};
    }
    b->cost_sum += b->costs.traversal * box_half_area(box);
    uint32_t index = b->num_nodes++; /* pre-order: the left subtree follows */
    ChildRef left = build_subtree(b, begin, part.mid, &part.left_box, &part.left_centroids, depth + 1);
    ChildRef right = build_subtree(b, part.mid, end, &part.right_box, &part.right_centroids, depth + 1);
    BvhNode *node = &b->nodes[index];
    set_child(&node->lmin, &node->lmax, &part.left_box, left);
    set_child(&node->rmin, &node->rmax, &part.right_box, right);
    return (ChildRef){index, 0};
}

/* One record per triangle, and the bounds of their boxes and centroids. */
static void make_prims(BuildPrim *prims, const float4 *positions, const Triangle *triangles,
                       uint32_t n, Box *box, Box *centroids)
{
    *box = *centroids = empty_box();
    for (uint32_t i = 0; i < n; i++) {
        const uint4 v = triangles[i].v;
        Lanes p0 = lanes_load(positions[v.s[0]].s), p1 = lanes_load(positions[v.s[1]].s);
        Lanes p2 = lanes_load(positions[v.s[2]].s);
        Box prim_box = {lanes_min(p2, lanes_min(p1, p0)), lanes_max(p2, lanes_max(p1, p0))};
        /* Within +-FLT_MAX, a NaN corner widening the box to all of it: centroids are then never
         * NaN (inf - inf), so they always have an order. */
        prim_box.lo = lanes_max(prim_box.lo, lanes_splat(-FLT_MAX));
        prim_box.hi = lanes_min(prim_box.hi, lanes_splat(FLT_MAX));
        /* Lane 3 of the bounds is never read: grow them before it takes the index. */
        box_grow(box, &prim_box);
        box_grow_point(centroids, centroid_of(&prim_box));
        lanes_store(prims[i].lo, prim_box.lo);
        lanes_store(prims[i].hi, prim_box.hi);
        prim_set_index(&prims[i], i);
        prims[i].hi[3] = 0.0f;
    }
}

/* count elements of size bytes (at least one), free()-able. Large arrays go on transparent huge
 * pages where Linux offers them on request: the build writes ~150 bytes per triangle to fresh
 * memory, and its 4 KiB page faults took about a tenth of the build time. */
static void *alloc_array(uint32_t count, size_t size)
{
    size_t bytes = (count ? count : 1) * size;
#ifdef MADV_HUGEPAGE
    const size_t huge_page = (size_t)2 << 20;
    void *pages = NULL;
    if (bytes >= 4 * huge_page && posix_memalign(&pages, huge_page, bytes) == 0) {
        madvise(pages, bytes, MADV_HUGEPAGE); /* only advice: failure leaves 4 KiB pages */
        return pages;
    }
#endif
    return malloc(bytes);
}

/* The tree over b->prims[0, n) (whose bounds are given) into b->nodes, with bvh's SAH cost;
 * leaves refer to ranges of b->prims as the build left it. */
static void build_tree(Bvh *bvh, Builder *b, uint32_t n, const Box *box, const Box *centroids)
{
    ChildRef root = n ? build_subtree(b, 0, n, box, centroids, 0) : (ChildRef){~0u, 0};
    if (b->num_nodes == 0) {
        /* The whole tree is one leaf: give it a root node with an empty right child, whose
         * inverted infinite box every ray misses. */
        Box nothing = empty_box();
        b->cost_sum += b->costs.traversal * box_half_area(box);
        set_child(&b->nodes[0].lmin, &b->nodes[0].lmax, box, root);
        set_child(&b->nodes[0].rmin, &b->nodes[0].rmax, &nothing, (ChildRef){~0u, 0});
        b->num_nodes = 1;
    }
    double root_area = box_half_area(box);
    bvh->sah_cost = root_area > 0.0 ? b->cost_sum / root_area : 0.0;
    BvhNode *shrunk = realloc(b->nodes, b->num_nodes * sizeof *b->nodes);
    bvh->nodes = shrunk ? shrunk : b->nodes;
    bvh->num_nodes = b->num_nodes;
}

static void build(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n,
                  bool full_sweep, BvhCosts costs)
{
    memset(bvh, 0, sizeof *bvh);
    /* Leaves hold ~first in an int lane, and build records a biased index: both fit. */
    if (n > PRIM_INDEX_LIMIT)
        die("BVH: %u triangles is more than the %u a BVH can index", n, PRIM_INDEX_LIMIT);
    Builder b = {0};
    b.full_sweep = full_sweep;
    b.costs = costs;
    b.max_leaf = BVH_MAX_LEAF_SIZE;
    b.prims = alloc_array(n, sizeof *b.prims);
    b.scratch = full_sweep ? malloc((n ? n : 1) * sizeof *b.scratch) : NULL;
    /* A binary tree over n >= 1 leaves has n - 1 inner nodes; one more when the root is a leaf. */
    b.nodes = alloc_array(n, sizeof *b.nodes);
    bvh->tris = alloc_array(n, sizeof *bvh->tris);
    if (!b.prims || !b.nodes || !bvh->tris || (full_sweep && !b.scratch))
        die("out of memory building the BVH (%u triangles)", n);

    Box box, centroids;
    make_prims(b.prims, positions, triangles, n, &box, &centroids);
    build_tree(bvh, &b, n, &box, &centroids);

    for (uint32_t i = 0; i < n; i++) {
        uint32_t index = prim_index(&b.prims[i]);
        const uint4 v = triangles[index].v;
        bvh->tris[i].v0 = positions[v.s[0]];
        bvh->tris[i].v1 = positions[v.s[1]];
        bvh->tris[i].v2 = positions[v.s[2]];
        memcpy(&bvh->tris[i].v0.s[3], &index, sizeof index);
        bvh->tris[i].v1.s[3] = 0.0f;
        bvh->tris[i].v2.s[3] = 0.0f;
    }
    free(b.prims);
    free(b.scratch);
    bvh->num_tris = n;
}

void bvh_build_over_boxes(Bvh *bvh, const float (*lo)[3], const float (*hi)[3], uint32_t n)
{
    memset(bvh, 0, sizeof *bvh);
    if (n > PRIM_INDEX_LIMIT)
        die("BVH: %u boxes is more than the %u a BVH can index", n, PRIM_INDEX_LIMIT);
    Builder b = {0};
    b.costs = BVH_COSTS_DEFAULT;
    b.max_leaf = 1;
    b.prims = alloc_array(n, sizeof *b.prims);
    b.nodes = alloc_array(n, sizeof *b.nodes);
    if (!b.prims || !b.nodes)
        die("out of memory building the BVH (%u boxes)", n);
    Box box = empty_box(), centroids = empty_box();
    for (uint32_t i = 0; i < n; i++) {
        _Alignas(16) float l[4] = {lo[i][0], lo[i][1], lo[i][2], 0.0f};
        _Alignas(16) float h[4] = {hi[i][0], hi[i][1], hi[i][2], 0.0f};
        Box prim_box = {lanes_load(l), lanes_load(h)};
        prim_box.lo = lanes_max(prim_box.lo, lanes_splat(-FLT_MAX));
        prim_box.hi = lanes_min(prim_box.hi, lanes_splat(FLT_MAX));
        box_grow(&box, &prim_box);
        box_grow_point(&centroids, centroid_of(&prim_box));
        prim_store(&b.prims[i], &prim_box);
        prim_set_index(&b.prims[i], i);
        b.prims[i].hi[3] = 0.0f;
    }
    build_tree(bvh, &b, n, &box, &centroids);
    /* Leaves of one record: name the box itself, ~index, instead of its place in the records. */
    for (uint32_t i = 0; i < bvh->num_nodes; i++) {
        float4 *refs[2] = {&bvh->nodes[i].lmin, &bvh->nodes[i].rmin};
        float4 *counts[2] = {&bvh->nodes[i].lmax, &bvh->nodes[i].rmax};
        for (int c = 0; c < 2; c++) {
            uint32_t ref, count;
            memcpy(&ref, &refs[c]->s[3], sizeof ref);
            memcpy(&count, &counts[c]->s[3], sizeof count);
            if (count == 1) {
                ref = ~prim_index(&b.prims[~ref]);
                memcpy(&refs[c]->s[3], &ref, sizeof ref);
            }
        }
    }
    free(b.prims);
}

void bvh_build(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n)
{
    build(bvh, positions, triangles, n, false, BVH_COSTS_DEFAULT);
}

void bvh_build_with_costs(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n,
                          BvhCosts costs)
{
    build(bvh, positions, triangles, n, false, costs);
}

void bvh_build_full_sweep(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n)
{
    build(bvh, positions, triangles, n, true, BVH_COSTS_DEFAULT);
}

void bvh_free(Bvh *bvh)
{
    free(bvh->nodes);
    free(bvh->tris);
    memset(bvh, 0, sizeof *bvh);
}
