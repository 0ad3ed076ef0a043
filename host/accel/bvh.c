// SPDX-License-Identifier: MIT
/* bvh.c: binned-SAH BVH over all triangles (Wald 2007, "On fast Construction of SAH-based Bounding
 * Volume Hierarchies"), written straight into the node array in the order cl/geometry/bvh_traverse.cl walks
 * it: depth first, pre-order, so an inner left child sits right after its parent. The build
 * reorders one array of per-triangle records in place; every leaf is a contiguous range of it,
 * and bvh->tris is that array's order. Box arithmetic runs on x, y, z (and a spare lane) at once:
 * SSE2 where the compiler offers it (every x86-64), plain C with the same results elsewhere. */
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

#include "base/error.h"
#include "base/lanes.h"

/* ---- Boxes and build records ----------------------------------------------------------------- */

/* An axis-aligned box in registers; lane 3 is spare. */
typedef struct {
    Lanes lo, hi;
} Box;

/* A triangle during the build, 32 bytes: its box, with the triangle's index in the bits of lo[3]
 * (offset by PRIM_INDEX_BIAS so that the lane holds a normal float: four-lane arithmetic on
 * denormals would stall on x86) and 0 in hi[3]. Centroids are lo + hi (twice the centre: the
 * factor cancels wherever they are used). */
typedef struct {
    _Alignas(16) float lo[4];
    float hi[4];
} BuildPrim;
#define PRIM_INDEX_BIAS 0x00800000u
#define PRIM_INDEX_LIMIT (0x7f800000u - PRIM_INDEX_BIAS)

typedef struct {
    uint32_t ref;   /* inner: node index; leaf: ~first triangle */
    uint32_t count; /* leaf: triangle count; inner: 0 */
} ChildRef;

typedef struct {
    double cost;   /* SAH cost of splitting, C_t + C_i (A_l N_l + A_r N_r) / A */
    int axis;      /* -1: no split found */
    int bin;       /* binned: first bin of the right side */
    float scale;   /* binned: bins per unit of (doubled) centroid along axis */
    uint32_t mid;  /* exact splits: index of the first right-side record */
} Split;

/* The two sides of an inner node: prims[begin, mid) and prims[mid, end). */
typedef struct {
    uint32_t mid;
    Box left_box, left_centroids, right_box, right_centroids;
} Partition;

typedef struct {
    BuildPrim *prims;
    double *scratch; /* full sweep: right-side areas */
    BvhNode *nodes;
    uint32_t num_nodes;
    bool full_sweep;
    BvhCosts costs;
    double cost_sum; /* SAH sum, not yet divided by the root's area */
} Builder;

static ALWAYS_INLINE Box empty_box(void)
{
    return (Box){lanes_splat(INFINITY), lanes_splat(-INFINITY)};
}

static ALWAYS_INLINE Box box_of(const BuildPrim *prim)
{
    return (Box){lanes_load(prim->lo), lanes_load(prim->hi)};
}

/* The index lane travels along: a record's box is its whole content. */
static ALWAYS_INLINE void prim_store(BuildPrim *prim, const Box *prim_box)
{
    lanes_store(prim->lo, prim_box->lo);
    lanes_store(prim->hi, prim_box->hi);
}

static ALWAYS_INLINE Lanes centroid_of(const Box *prim_box)
{
    return lanes_add(prim_box->lo, prim_box->hi);
}

static ALWAYS_INLINE void box_grow(Box *box, const Box *other)
{
    box->lo = lanes_min(box->lo, other->lo);
    box->hi = lanes_max(box->hi, other->hi);
}

/* acc[a] grows by other[a] for the three axes, written out: -O2 keeps acc in registers then. */
static ALWAYS_INLINE void box_grow_three(Box acc[3], const Box other[3])
{
    box_grow(&acc[0], &other[0]);
    box_grow(&acc[1], &other[1]);
    box_grow(&acc[2], &other[2]);
}

static ALWAYS_INLINE void box_grow_point(Box *box, Lanes point)
{
    box->lo = lanes_min(box->lo, point);
    box->hi = lanes_max(box->hi, point);
}

/* Lanes x, y, z of a box as floats: lo[0..2], hi[0..2]. */
static ALWAYS_INLINE void box_corners(const Box *box, float lo[4], float hi[4])
{
    _Alignas(16) float l[4], h[4];
    lanes_store(l, box->lo);
    lanes_store(h, box->hi);
    memcpy(lo, l, sizeof l);
    memcpy(hi, h, sizeof h);
}

/* Half the surface area: only ratios of areas matter. Empty boxes have none. In double: the
 * product of two float extents overflows a float for scenes wider than 1e19. */
static double box_half_area(const Box *box)
{
    float lo[4], hi[4];
    box_corners(box, lo, hi);
    double dx = (double)hi[0] - lo[0], dy = (double)hi[1] - lo[1], dz = (double)hi[2] - lo[2];
    return dx >= 0.0 ? dx * dy + dy * dz + dz * dx : 0.0;
}

/* The same in float, times `unit` (1 / the largest extent of the node being split): cheap for
 * the split searches, and no product overflows since one factor of each is at most 1. Measures
 * what half_areas_of_three measures, so the two compare. */
static float box_half_area_in(const Box *box, float unit)
{
    float lo[4], hi[4];
    box_corners(box, lo, hi);
    float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx >= 0.0f ? dx * unit * (dy + dz) + dy * unit * dz : 0.0f;
}

static ALWAYS_INLINE float box_unit(const Box *box)
{
    float lo[4], hi[4], extent = 0.0f;
    box_corners(box, lo, hi);
    for (int k = 0; k < 3; k++)
        extent = hi[k] - lo[k] > extent ? hi[k] - lo[k] : extent;
    return extent > 0.0f ? 1.0f / extent : 1.0f;
}

static ALWAYS_INLINE void prim_set_index(BuildPrim *prim, uint32_t index)
{
    uint32_t bits = index + PRIM_INDEX_BIAS;
    memcpy(&prim->lo[3], &bits, sizeof bits);
}

static ALWAYS_INLINE uint32_t prim_index(const BuildPrim *prim)
{
    uint32_t bits;
    memcpy(&bits, &prim->lo[3], sizeof bits);
    return bits - PRIM_INDEX_BIAS;
}

static int ceil_log2(uint32_t n)
{
    int bits = 0;
    while (bits < 32 && (1ull << bits) < n)
        bits++;
    return bits;
}

/* ---- Split search ---------------------------------------------------------------------------- */

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
static Split find_binned_split(const Builder *b, uint32_t begin, uint32_t end, const Box *box,
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
static bool split_small_node(const Builder *b, uint32_t begin, uint32_t end, const Box *box,
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
        if (b->costs.intersect * 2.0 <= cost)
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
    if (sweep.axis < 0 || (n <= BVH_MAX_LEAF_SIZE && b->costs.intersect * (double)n <= cost)) {
        if (n <= BVH_MAX_LEAF_SIZE)
            return false;
        sweep = (SweepResult){0.0f, 0, (int)n / 2}; /* no split compares: halve it */
    }
    part->mid = begin + (uint32_t)sweep.cut;
    write_small_sides(prims, local, order[sweep.axis], n, (uint32_t)sweep.cut, part);
    return true;
}

/* ---- Partition ------------------------------------------------------------------------------- */

/* Both sides' bounds, by scanning them, for the splits that do not bin. */
static Partition partition_at(const Builder *b, uint32_t begin, uint32_t mid, uint32_t end)
{
    Box left = empty_box(), left_centroids = empty_box();
    Box right = empty_box(), right_centroids = empty_box();
    for (uint32_t i = begin; i < mid; i++) {
        Box prim_box = box_of(&b->prims[i]);
        box_grow(&left, &prim_box);
        box_grow_point(&left_centroids, centroid_of(&prim_box));
    }
    for (uint32_t i = mid; i < end; i++) {
        Box prim_box = box_of(&b->prims[i]);
        box_grow(&right, &prim_box);
        box_grow_point(&right_centroids, centroid_of(&prim_box));
    }
    return (Partition){mid, left, left_centroids, right, right_centroids};
}

/* Partitions at the split's bin boundary, Hoare style: only misplaced pairs move. Collects both
 * sides' bounds and centroid bounds on the way (the bins may have seen a sample only, and a
 * record right at the boundary may round to either side: the partition decides). */
static Partition partition_at_plane(Builder *b, uint32_t begin, uint32_t end, int axis, float plane)
{
    Box left = empty_box(), left_centroids = empty_box();
    Box right = empty_box(), right_centroids = empty_box();
    const Lanes plane_lanes = lanes_splat(plane);
    const int left_bit = 1 << axis;
    BuildPrim *prims = b->prims;
    uint32_t i = begin, j = end;
    Box to_right = left, to_left = right;
    Lanes right_centroid = plane_lanes, left_centroid = plane_lanes;
    for (;;) {
        for (; i < j; i++) {
            to_right = box_of(&prims[i]);
            right_centroid = centroid_of(&to_right);
            if (!(lanes_less_bits(right_centroid, plane_lanes) & left_bit))
                break;
            box_grow(&left, &to_right);
            box_grow_point(&left_centroids, right_centroid);
        }
        for (; i < j; j--) {
            to_left = box_of(&prims[j - 1]);
            left_centroid = centroid_of(&to_left);
            if (lanes_less_bits(left_centroid, plane_lanes) & left_bit)
                break;
            box_grow(&right, &to_left);
            box_grow_point(&right_centroids, left_centroid);
        }
        if (i == j)
            break;
        /* prims[i] belongs right and prims[j - 1] left: swap them (both are in registers). */
        j--;
        prim_store(&prims[i], &to_left);
        prim_store(&prims[j], &to_right);
        box_grow(&left, &to_left);
        box_grow_point(&left_centroids, left_centroid);
        box_grow(&right, &to_right);
        box_grow_point(&right_centroids, right_centroid);
        i++;
    }
    return (Partition){i, left, left_centroids, right, right_centroids};
}

/* ---- Full-sweep reference -------------------------------------------------------------------- */

#define DEFINE_COMPARE_AXIS(axis)                                                   \
    static int compare_axis##axis(const void *pa, const void *pb)                  \
    {                                                                               \
        const BuildPrim *a = pa, *b = pb;                                           \
        float ca = a->lo[axis] + a->hi[axis], cb = b->lo[axis] + b->hi[axis];       \
        if (ca != cb)                                                               \
            return ca < cb ? -1 : 1;                                                \
        return prim_index(a) < prim_index(b) ? -1 : prim_index(a) > prim_index(b); \
    }
DEFINE_COMPARE_AXIS(0)
DEFINE_COMPARE_AXIS(1)
DEFINE_COMPARE_AXIS(2)

static void sort_by_centroid(Builder *b, uint32_t begin, uint32_t end, int axis)
{
    int (*const compare[3])(const void *, const void *) = {compare_axis0, compare_axis1,
                                                           compare_axis2};
    qsort(b->prims + begin, end - begin, sizeof *b->prims, compare[axis]);
}

/* Reference split for tests and benchmarks: every position between sorted centroids on every
 * axis (O(n log n) per node). Leaves the range sorted on the best axis. */
static Split find_full_sweep_split(Builder *b, uint32_t begin, uint32_t end, const Box *box)
{
    Split best = {.cost = INFINITY, .axis = -1};
    double best_sum = INFINITY;
    for (int axis = 0; axis < 3; axis++) {
        sort_by_centroid(b, begin, end, axis);
        Box acc = empty_box();
        for (uint32_t i = end - 1; i > begin; i--) {
            Box prim_box = box_of(&b->prims[i]);
            box_grow(&acc, &prim_box);
            b->scratch[i] = box_half_area(&acc);
        }
        acc = empty_box();
        for (uint32_t i = begin + 1; i < end; i++) {
            Box prim_box = box_of(&b->prims[i - 1]);
            box_grow(&acc, &prim_box);
            double sum = box_half_area(&acc) * (i - begin) + b->scratch[i] * (end - i);
            if (sum < best_sum) {
                best_sum = sum;
                best.axis = axis;
                best.mid = i;
            }
        }
    }
    if (best.axis >= 0 && best.axis != 2)
        sort_by_centroid(b, begin, end, best.axis);
    best.cost = b->costs.traversal + b->costs.intersect * best_sum / box_half_area(box);
    return best;
}

/* ---- Tree ------------------------------------------------------------------------------------ */

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
    if (n == 1 || (n <= BVH_MAX_LEAF_SIZE && must_balance))
        return leaf;
    if (!must_balance) {
        if (!b->full_sweep && n <= BVH_SMALL_NODE)
            return split_small_node(b, begin, end, box, part);
        Split split = b->full_sweep ? find_full_sweep_split(b, begin, end, box)
                                    : find_binned_split(b, begin, end, box, centroids);
        if (split.axis >= 0) {
            if (n <= BVH_MAX_LEAF_SIZE && b->costs.intersect * (double)n <= split.cost)
                return leaf;
            if (b->full_sweep) {
                *part = partition_at(b, begin, split.mid, end);
                return true;
            }
            float lo[4], hi[4];
            box_corners(centroids, lo, hi);
            float plane = lo[split.axis] + (float)split.bin / split.scale;
            *part = partition_at_plane(b, begin, end, split.axis, plane);
            if (part->mid != begin && part->mid != end)
                return true;
        }
    }
    if (n <= BVH_MAX_LEAF_SIZE)
        return leaf;
    /* Object median on the widest centroid axis (all centroids equal: any order will do). */
    float lo[4], hi[4];
    box_corners(centroids, lo, hi);
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (hi[k] - lo[k] > hi[axis] - lo[axis])
            axis = k;
    if (hi[axis] > lo[axis])
        sort_by_centroid(b, begin, end, axis);
    *part = partition_at(b, begin, begin + n / 2, end);
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
    b.prims = alloc_array(n, sizeof *b.prims);
    b.scratch = full_sweep ? malloc((n ? n : 1) * sizeof *b.scratch) : NULL;
    /* A binary tree over n >= 1 leaves has n - 1 inner nodes; one more when the root is a leaf. */
    b.nodes = alloc_array(n, sizeof *b.nodes);
    bvh->tris = alloc_array(n, sizeof *bvh->tris);
    if (!b.prims || !b.nodes || !bvh->tris || (full_sweep && !b.scratch))
        die("out of memory building the BVH (%u triangles)", n);

    Box box, centroids;
    make_prims(b.prims, positions, triangles, n, &box, &centroids);
    ChildRef root = n ? build_subtree(&b, 0, n, &box, &centroids, 0) : (ChildRef){~0u, 0};
    if (b.num_nodes == 0) {
        /* The whole tree is one leaf: give it a root node with an empty right child, whose
         * inverted infinite box every ray misses. */
        Box nothing = empty_box();
        b.cost_sum += b.costs.traversal * box_half_area(&box);
        set_child(&b.nodes[0].lmin, &b.nodes[0].lmax, &box, root);
        set_child(&b.nodes[0].rmin, &b.nodes[0].rmax, &nothing, (ChildRef){~0u, 0});
        b.num_nodes = 1;
    }
    double root_area = box_half_area(&box);
    bvh->sah_cost = root_area > 0.0 ? b.cost_sum / root_area : 0.0;

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
    BvhNode *shrunk = realloc(b.nodes, b.num_nodes * sizeof *b.nodes);
    bvh->nodes = shrunk ? shrunk : b.nodes;
    bvh->num_nodes = b.num_nodes;
    bvh->num_tris = n;
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
