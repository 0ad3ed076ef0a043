// SPDX-License-Identifier: MIT
/* bvh_sah.c: the binned-SAH split search of the BVH build (Wald 2007, "On fast Construction of
 * SAH-based Bounding Volume Hierarchies"): centroid bins on all three axes at once for large nodes,
 * an exact sweep over every position for small ones (up to BVH_SMALL_NODE records, where most
 * nodes are). Both sweep with sweep_three_axes, axis a in lane a. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "accel/bvh_internal.h"

/* Three boxes' half areas, box a in lane a, times unit (1 / the node's largest extent) to keep
 * them in float range: only one factor of each product is scaled, so none overflows (the result
 * is in units of extent, not extent squared: fine for comparing within one node). An empty box
 * (lo +inf, hi -inf) has an infinite area; lane 3 is 0. */
static ALWAYS_INLINE Lanes half_areas_of_three(const Box box[3], Lanes unit)
{
    Lanes d[3];
    lanes_transpose3(lanes_sub(box[0].hi, box[0].lo), lanes_sub(box[1].hi, box[1].lo),
                     lanes_sub(box[2].hi, box[2].lo), d);
    Lanes dx_scaled = lanes_mul(d[0], unit), dy_scaled = lanes_mul(d[1], unit);
    return lanes_add(lanes_mul(dx_scaled, lanes_add(d[1], d[2])), lanes_mul(dy_scaled, d[2]));
}

#define SWEEP_MAX (BVH_BINS > BVH_SMALL_NODE ? BVH_BINS : BVH_SMALL_NODE)

typedef struct {
    float sum; /* A_l N_l + A_r N_r as half_areas_of_three measures it; INFINITY: no valid cut */
    int axis, cut;
} SweepResult;

/* Sweeps m candidates along all three axes together: box[i][a] is candidate i's box on axis a
 * and count[i] its triangle counts, axis a in lane a; cut i puts candidates [0, i) left and
 * [i, m) right. A side without triangles has an empty box, and its term is inf * 0 = NaN: NaN
 * sums never compare less, and lanes_min keeps its second operand, so such cuts drop out
 * without a test. Ties go to the first cut, then the lowest axis. */
static SweepResult sweep_three_axes(Box (*box)[3], const Lanes *count, int m, float unit)
{
    const Lanes unit_lanes = lanes_splat(unit), one = lanes_splat(1.0f);
    Lanes right_term[SWEEP_MAX];
    Box acc[3] = {empty_box(), empty_box(), empty_box()};
    Lanes total = lanes_splat(0.0f);
    for (int i = m - 1; i > 0; i--) {
        box_grow_three(acc, box[i]);
        total = lanes_add(total, count[i]);
        right_term[i] = lanes_mul(half_areas_of_three(acc, unit_lanes), total);
    }
    acc[0] = acc[1] = acc[2] = empty_box();
    total = lanes_splat(0.0f);
    Lanes best = lanes_splat(INFINITY), best_cut = lanes_splat(0.0f), cut = one;
    for (int i = 1; i < m; i++) {
        box_grow_three(acc, box[i - 1]);
        total = lanes_add(total, count[i - 1]);
        Lanes left_term = lanes_mul(half_areas_of_three(acc, unit_lanes), total);
        Lanes sum = lanes_add(left_term, right_term[i]);
        best_cut = lanes_select_less(sum, best, cut, best_cut);
        best = lanes_min(sum, best);
        cut = lanes_add(cut, one);
    }
    _Alignas(16) float sums[4], cuts[4];
    lanes_store(sums, best);
    lanes_store(cuts, best_cut);
    SweepResult result = {INFINITY, -1, 0};
    for (int axis = 0; axis < 3; axis++)
        if (sums[axis] < result.sum)
            result = (SweepResult){sums[axis], axis, (int)cuts[axis]};
    return result;
}

/* Bins of all three axes, box[bin][axis] and count[bin][axis]; binning fills two sets, even and
 * odd records apart, so that runs of records in one bin (meshes are coherent) make two dependency
 * chains through memory, not one. */
typedef struct {
    Box box[BVH_BINS][3];
    uint32_t count[BVH_BINS][4]; /* lane 3: 0 */
} BinSet;

static void bin_set_clear(BinSet *set, int bins)
{
    Box empty = empty_box();
    for (int i = 0; i < bins; i++)
        set->box[i][0] = set->box[i][1] = set->box[i][2] = empty;
    memset(set->count, 0, (size_t)bins * sizeof set->count[0]);
}

/* The bins of one record on all three axes. The clamp also sends NaN to the last bin. */
static ALWAYS_INLINE void bin_prim(BinSet *set, const BuildPrim *prim, Lanes origin,
                                   Lanes scale, Lanes last)
{
    Box box = box_of(prim);
    int32_t bin[4];
    lanes_truncate(lanes_min(lanes_mul(lanes_sub(centroid_of(&box), origin), scale), last), bin);
    set->count[bin[0]][0]++;
    set->count[bin[1]][1]++;
    set->count[bin[2]][2]++;
    box_grow(&set->box[bin[0]][0], &box);
    box_grow(&set->box[bin[1]][1], &box);
    box_grow(&set->box[bin[2]][2], &box);
}

/* Binning looks at every k-th record of a large node only: the split position it finds from a
 * sample is about as good, at a fraction of the cost (the partition then computes the sides'
 * exact bounds). k grows with log10(n), after Wald 2007. */
static uint32_t bin_stride(uint32_t n)
{
    uint32_t stride = 1;
    for (uint32_t m = n; m >= BVH_BIN_SAMPLE_FROM; m /= 10)
        stride++;
    return stride;
}

/* Best binned split of prims[begin, end); axis -1 when no axis has a centroid extent. */
Split bvh_find_binned_split(const Builder *b, uint32_t begin, uint32_t end, const Box *box,
                               const Box *centroids)
{
    int bins = end - begin < BVH_BINS ? (int)(end - begin) : BVH_BINS;
    uint32_t stride = bin_stride(end - begin);
    _Alignas(16) float lo[4], hi[4], scale[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    box_corners(centroids, lo, hi);
    for (int axis = 0; axis < 3; axis++) {
        float extent = hi[axis] - lo[axis];
        /* Slightly under bins / extent so that the largest centroid stays in the last bin. */
        scale[axis] = extent > 0.0f ? (float)bins * 0.99999f / extent : 0.0f;
    }
    lo[3] = 0.0f; /* the index lane bins to 0 */
    Lanes origin = lanes_load(lo), scale_lanes = lanes_load(scale);
    Lanes last = lanes_splat((float)(bins - 1));
    /* Two sets pay off only where runs are long enough to stall on memory. */
    BinSet set[2];
    bool two_sets = end - begin >= 64;
    bin_set_clear(&set[0], bins);
    if (two_sets)
        bin_set_clear(&set[1], bins);
    uint32_t i = begin;
    for (; two_sets && i + stride < end; i += 2 * stride) {
        bin_prim(&set[0], &b->prims[i], origin, scale_lanes, last);
        bin_prim(&set[1], &b->prims[i + stride], origin, scale_lanes, last);
    }
    for (; i < end; i += stride)
        bin_prim(&set[0], &b->prims[i], origin, scale_lanes, last);
    Lanes count[BVH_BINS];
    for (int k = 0; k < bins; k++) {
        count[k] = lanes_from_ints(set[0].count[k]);
        if (two_sets) {
            box_grow_three(set[0].box[k], set[1].box[k]);
            count[k] = lanes_add(count[k], lanes_from_ints(set[1].count[k]));
        }
    }
    float unit = box_unit(box);
    SweepResult sweep = sweep_three_axes(set[0].box, count, bins, unit);
    Split best = {.cost = INFINITY, .axis = sweep.axis, .bin = sweep.cut};
    if (best.axis >= 0) {
        best.scale = scale[best.axis];
        best.cost = b->costs.traversal +
                    b->costs.intersect * (float)stride * sweep.sum / box_half_area_in(box, unit);
    }
    return best;
}

/* A small node's sides, written back in order: prims[k] = local[order[k]], the first `mid` of
 * them left. Fills part with both sides' bounds and centroid bounds. */
static void write_small_sides(BuildPrim *prims, const Box *local, const uint8_t *order,
                              uint32_t n, uint32_t mid, Partition *part)
{
    Box left = empty_box(), left_centroids = empty_box();
    Box right = empty_box(), right_centroids = empty_box();
    for (uint32_t k = 0; k < mid; k++) {
        const Box *prim_box = &local[order[k]];
        prim_store(&prims[k], prim_box);
        box_grow(&left, prim_box);
        box_grow_point(&left_centroids, centroid_of(prim_box));
    }
    for (uint32_t k = mid; k < n; k++) {
        const Box *prim_box = &local[order[k]];
        prim_store(&prims[k], prim_box);
        box_grow(&right, prim_box);
        box_grow_point(&right_centroids, centroid_of(prim_box));
    }
    part->left_box = left;
    part->left_centroids = left_centroids;
    part->right_box = right;
    part->right_centroids = right_centroids;
}

/* Exact split of a small node (n <= BVH_SMALL_NODE, where most nodes are): rank the records by
 * centroid along each axis and sweep every position; cheaper than binning there, and exact.
 * Returns false when a leaf is cheaper, else reorders the range and fills part. */
bool bvh_split_small_node(const Builder *b, uint32_t begin, uint32_t end, const Box *box,
                             Partition *part)
{
    uint32_t n = end - begin;
    BuildPrim *prims = b->prims + begin;
    float unit = box_unit(box);
    Box local[BVH_SMALL_NODE];
    uint8_t order[3][BVH_SMALL_NODE];
    if (n == 2) {
        /* A pair has one split, whatever the axis (the most common node: about half of them). */
        local[0] = box_of(&prims[0]);
        local[1] = box_of(&prims[1]);
        _Alignas(16) float area[4]; /* both triangles' and the node's, in one go */
        lanes_store(area, half_areas_of_three((const Box[3]){local[0], local[1], *box},
                                              lanes_splat(unit)));
        double cost = b->costs.traversal + b->costs.intersect * (area[0] + area[1]) / area[2];
        if (b->max_leaf >= 2 && b->costs.intersect * 2.0 <= cost)
            return false;
        part->mid = begin + 1;
        write_small_sides(prims, local, (const uint8_t[]){0, 1}, n, 1, part);
        return true;
    }
    /* Rank i on axis a, in lane a: how many records come before record i in centroid order, ties
     * going to the lower index. Start from "before every later one"; each pair then moves one.
     * Centroids are never NaN (make_prims), so each axis's ranks are a permutation. */
    Lanes centroid[BVH_SMALL_NODE], rank[BVH_SMALL_NODE], count[BVH_SMALL_NODE];
    /* Every entry set (the sweep reads n of them) so that -O1 builds see no uninitialised use. */
    for (uint32_t i = 0; i < BVH_SMALL_NODE; i++)
        count[i] = lanes_splat(1.0f);
    for (uint32_t i = 0; i < n; i++) {
        local[i] = box_of(&prims[i]);
        centroid[i] = centroid_of(&local[i]);
        rank[i] = lanes_splat((float)(n - 1 - i));
        for (uint32_t j = 0; j < i; j++) {
            Lanes j_first = lanes_one_if_less_equal(centroid[j], centroid[i]);
            rank[i] = lanes_add(rank[i], j_first);
            rank[j] = lanes_sub(rank[j], j_first);
        }
    }
    Box sorted[BVH_SMALL_NODE][3];
    for (uint32_t i = 0; i < n; i++) {
        int32_t r[4];
        lanes_truncate(rank[i], r);
        for (int axis = 0; axis < 3; axis++) {
            order[axis][r[axis]] = (uint8_t)i;
            sorted[r[axis]][axis] = local[i];
        }
    }
    SweepResult sweep = sweep_three_axes(sorted, count, (int)n, unit);
    double cost = b->costs.traversal +
                  b->costs.intersect * sweep.sum / box_half_area_in(box, unit);
    if (sweep.axis < 0 || (n <= b->max_leaf && b->costs.intersect * (double)n <= cost)) {
        if (n <= b->max_leaf)
            return false;
        sweep = (SweepResult){0.0f, 0, (int)n / 2}; /* no split compares: halve it */
    }
    part->mid = begin + (uint32_t)sweep.cut;
    write_small_sides(prims, local, order[sweep.axis], n, (uint32_t)sweep.cut, part);
    return true;
}

