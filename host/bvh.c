// SPDX-License-Identifier: MIT
/* bvh.c: binned-SAH BVH over all triangles (Wald 2007, "On fast Construction of SAH-based Bounding
 * Volume Hierarchies"), written straight into the node array in the order cl/bvh_traverse.cl walks
 * it: depth first, pre-order, so an inner left child sits right after its parent. The build
 * reorders one array of per-triangle records in place; every leaf is a contiguous range of it,
 * and bvh->tris is that array's order. */
#include "bvh.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "error.h"

/* An axis-aligned box; lane 3 is spare so that min/max run four lanes at a time. */
typedef struct {
    float lo[4], hi[4];
} Box;

/* A triangle during the build: its box, with the triangle's index in the bits of lo[3] (offset by
 * PRIM_INDEX_BIAS so that the lane holds a normal float: four-lane arithmetic on denormals would
 * stall on x86). Centroids are lo + hi (twice the centre: the factor cancels wherever they are
 * used). */
typedef Box BuildPrim;
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
    uint32_t mid;  /* full sweep: index of the first right-side record */
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
    double cost_sum; /* SAH sum, not yet divided by the root's area */
} Builder;

static const Box empty_box = {{INFINITY, INFINITY, INFINITY, INFINITY},
                              {-INFINITY, -INFINITY, -INFINITY, -INFINITY}};

static inline void box_grow(Box *box, const Box *other)
{
    for (int k = 0; k < 4; k++) {
        box->lo[k] = other->lo[k] < box->lo[k] ? other->lo[k] : box->lo[k];
        box->hi[k] = other->hi[k] > box->hi[k] ? other->hi[k] : box->hi[k];
    }
}

static inline void box_grow_centroid(Box *box, const BuildPrim *prim)
{
    for (int k = 0; k < 4; k++) {
        float c = prim->lo[k] + prim->hi[k];
        box->lo[k] = c < box->lo[k] ? c : box->lo[k];
        box->hi[k] = c > box->hi[k] ? c : box->hi[k];
    }
}

/* Half the surface area: only ratios of areas matter. Empty boxes have none. In double: the
 * product of two float extents overflows a float for scenes wider than 1e19. */
static inline double box_half_area(const Box *box)
{
    double dx = (double)box->hi[0] - box->lo[0], dy = (double)box->hi[1] - box->lo[1];
    double dz = (double)box->hi[2] - box->lo[2];
    return dx >= 0.0 ? dx * dy + dy * dz + dz * dx : 0.0;
}

/* The same in float after scaling the extents by `unit` (1 / the node's largest extent): cheap
 * for the bin sweeps, and it cannot overflow since it only compares boxes within one node. */
static inline float box_half_area_in(const Box *box, float unit)
{
    float dx = (box->hi[0] - box->lo[0]) * unit, dy = (box->hi[1] - box->lo[1]) * unit;
    float dz = (box->hi[2] - box->lo[2]) * unit;
    return dx >= 0.0f ? dx * dy + dy * dz + dz * dx : 0.0f;
}

static inline float box_unit(const Box *box)
{
    float extent = 0.0f;
    for (int k = 0; k < 3; k++)
        extent = box->hi[k] - box->lo[k] > extent ? box->hi[k] - box->lo[k] : extent;
    return extent > 0.0f ? 1.0f / extent : 1.0f;
}

static inline void prim_set_index(BuildPrim *prim, uint32_t index)
{
    uint32_t bits = index + PRIM_INDEX_BIAS;
    memcpy(&prim->lo[3], &bits, sizeof bits);
}

static inline uint32_t prim_index(const BuildPrim *prim)
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

/* Sweeps one axis's bins: the cheapest cut between bins, written to best when it beats it. */
static void sweep_bins(const Box *bin_box, const uint32_t *bin_count, int bins, int axis, float unit,
                       Split *best, float *best_sum)
{
    float right_area[BVH_BINS];
    uint32_t right_count[BVH_BINS];
    Box acc = empty_box;
    uint32_t count = 0;
    for (int i = bins - 1; i > 0; i--) {
        box_grow(&acc, &bin_box[i]);
        count += bin_count[i];
        right_area[i] = box_half_area_in(&acc, unit);
        right_count[i] = count;
    }
    acc = empty_box;
    count = 0;
    for (int i = 1; i < bins; i++) {
        box_grow(&acc, &bin_box[i - 1]);
        count += bin_count[i - 1];
        if (count == 0 || right_count[i] == 0)
            continue;
        float sum = box_half_area_in(&acc, unit) * (float)count + right_area[i] * (float)right_count[i];
        if (sum < *best_sum) {
            *best_sum = sum;
            best->axis = axis;
            best->bin = i;
        }
    }
}

/* Bins of one axis each; binning fills two sets, even and odd records apart, so that runs of
 * records in one bin (meshes are coherent) make two dependency chains through memory, not one. */
typedef struct {
    Box box[3][BVH_BINS];
    uint32_t count[3][BVH_BINS];
} BinSet;

static void bin_set_clear(BinSet *set, int bins)
{
    for (int axis = 0; axis < 3; axis++)
        for (int i = 0; i < bins; i++) {
            set->box[axis][i] = empty_box;
            set->count[axis][i] = 0;
        }
}

/* The bins of one record on all three axes, four lanes at a time. */
static inline void bin_prim(BinSet *set, const BuildPrim *prim, const float origin[4],
                            const float scale[4], float last)
{
    float f[4];
    for (int k = 0; k < 4; k++) {
        f[k] = (prim->lo[k] + prim->hi[k] - origin[k]) * scale[k];
        f[k] = f[k] < last ? f[k] : last;
    }
    int x = (int)f[0], y = (int)f[1], z = (int)f[2];
    set->count[0][x]++;
    set->count[1][y]++;
    set->count[2][z]++;
    box_grow(&set->box[0][x], prim);
    box_grow(&set->box[1][y], prim);
    box_grow(&set->box[2][z], prim);
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

/* Best binned split of prims[begin, end); axis -1 when no axis has a centroid extent. Small
 * nodes get one bin per triangle: the sweep, not the binning, dominates their cost. */
static Split find_binned_split(const Builder *b, uint32_t begin, uint32_t end, const Box *box,
                               const Box *centroids)
{
    int bins = end - begin < BVH_BINS ? (int)(end - begin) : BVH_BINS;
    uint32_t stride = bin_stride(end - begin);
    float origin[4] = {centroids->lo[0], centroids->lo[1], centroids->lo[2], 0.0f};
    float scale[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int axis = 0; axis < 3; axis++) {
        float extent = centroids->hi[axis] - centroids->lo[axis];
        /* Slightly under bins / extent so that the largest centroid stays in the last bin. */
        scale[axis] = extent > 0.0f ? (float)bins * 0.99999f / extent : 0.0f;
    }
    /* Two sets pay off only where runs are long enough to stall on memory. */
    BinSet set[2];
    bool two_sets = end - begin >= 64;
    bin_set_clear(&set[0], bins);
    if (two_sets)
        bin_set_clear(&set[1], bins);
    const float last = (float)(bins - 1);
    uint32_t i = begin;
    for (; two_sets && i + stride < end; i += 2 * stride) {
        bin_prim(&set[0], &b->prims[i], origin, scale, last);
        bin_prim(&set[1], &b->prims[i + stride], origin, scale, last);
    }
    for (; i < end; i += stride)
        bin_prim(&set[0], &b->prims[i], origin, scale, last);
    for (int axis = 0; two_sets && axis < 3; axis++)
        for (int k = 0; k < bins; k++) {
            box_grow(&set[0].box[axis][k], &set[1].box[axis][k]);
            set[0].count[axis][k] += set[1].count[axis][k];
        }
    Split best = {.cost = INFINITY, .axis = -1};
    float best_sum = INFINITY, unit = box_unit(box);
    for (int axis = 0; axis < 3; axis++)
        if (scale[axis] > 0.0f)
            sweep_bins(set[0].box[axis], set[0].count[axis], bins, axis, unit, &best, &best_sum);
    if (best.axis >= 0) {
        best.scale = scale[best.axis];
        best.cost = BVH_COST_TRAVERSAL +
                    BVH_COST_INTERSECT * (float)stride * best_sum / box_half_area_in(box, unit);
    }
    return best;
}

/* Exact split of a small node (n <= BVH_SMALL_NODE, where most nodes are): insertion-sort the
 * records by centroid along each axis and sweep every position. Cheaper than binning there, and
 * exact. Leaves the range ordered along the best axis. */
static Split find_small_split(Builder *b, uint32_t begin, uint32_t end, const Box *box)
{
    uint32_t n = end - begin;
    BuildPrim *prims = b->prims + begin;
    uint8_t order[3][BVH_SMALL_NODE];
    Split best = {.cost = INFINITY, .axis = -1};
    float best_sum = INFINITY, unit = box_unit(box);
    if (n == 2) {
        /* A pair has one split, whatever the axis (the most common node: about half of them). */
        best.axis = 0;
        best.mid = begin + 1;
        best_sum = box_half_area_in(&prims[0], unit) + box_half_area_in(&prims[1], unit);
        best.cost = BVH_COST_TRAVERSAL + BVH_COST_INTERSECT * best_sum / box_half_area_in(box, unit);
        return best;
    }
    for (int axis = 0; axis < 3; axis++) {
        float key[BVH_SMALL_NODE];
        uint8_t *o = order[axis];
        for (uint32_t i = 0; i < n; i++) {
            float c = prims[i].lo[axis] + prims[i].hi[axis];
            uint32_t j = i;
            for (; j > 0 && key[j - 1] > c; j--) {
                key[j] = key[j - 1];
                o[j] = o[j - 1];
            }
            key[j] = c;
            o[j] = (uint8_t)i;
        }
        float right_area[BVH_SMALL_NODE];
        Box acc = empty_box;
        for (uint32_t i = n - 1; i > 0; i--) {
            box_grow(&acc, &prims[o[i]]);
            right_area[i] = box_half_area_in(&acc, unit);
        }
        acc = empty_box;
        for (uint32_t i = 1; i < n; i++) {
            box_grow(&acc, &prims[o[i - 1]]);
            float sum = box_half_area_in(&acc, unit) * (float)i + right_area[i] * (float)(n - i);
            if (sum < best_sum) {
                best_sum = sum;
                best.axis = axis;
                best.mid = begin + i;
            }
        }
    }
    BuildPrim sorted[BVH_SMALL_NODE];
    for (uint32_t i = 0; i < n; i++)
        sorted[i] = prims[order[best.axis][i]];
    memcpy(prims, sorted, n * sizeof *prims);
    best.cost = BVH_COST_TRAVERSAL + BVH_COST_INTERSECT * best_sum / box_half_area_in(box, unit);
    return best;
}

/* Both sides' bounds, by scanning them, for the splits that do not bin. */
static Partition partition_at(const Builder *b, uint32_t begin, uint32_t mid, uint32_t end)
{
    Partition part = {mid, empty_box, empty_box, empty_box, empty_box};
    for (uint32_t i = begin; i < end; i++) {
        Box *bounds = i < mid ? &part.left_box : &part.right_box;
        box_grow(bounds, &b->prims[i]);
        box_grow_centroid(i < mid ? &part.left_centroids : &part.right_centroids, &b->prims[i]);
    }
    return part;
}

/* Partitions at the split's bin boundary, Hoare style: only misplaced pairs move. Collects both
 * sides' bounds and centroid bounds on the way (the bins may have seen a sample only, and a
 * record right at the boundary may round to either side: the partition decides). */
static Partition partition_at_plane(Builder *b, uint32_t begin, uint32_t end, int axis, float plane)
{
    Partition part = {0, empty_box, empty_box, empty_box, empty_box};
    BuildPrim *prims = b->prims;
    uint32_t i = begin, j = end;
    for (;;) {
        while (i < j && prims[i].lo[axis] + prims[i].hi[axis] < plane) {
            box_grow(&part.left_box, &prims[i]);
            box_grow_centroid(&part.left_centroids, &prims[i]);
            i++;
        }
        while (i < j && !(prims[j - 1].lo[axis] + prims[j - 1].hi[axis] < plane)) {
            j--;
            box_grow(&part.right_box, &prims[j]);
            box_grow_centroid(&part.right_centroids, &prims[j]);
        }
        if (i == j)
            break;
        /* prims[i] belongs right and prims[j - 1] left. */
        j--;
        BuildPrim tmp = prims[i];
        prims[i] = prims[j];
        prims[j] = tmp;
        box_grow(&part.left_box, &prims[i]);
        box_grow_centroid(&part.left_centroids, &prims[i]);
        box_grow(&part.right_box, &prims[j]);
        box_grow_centroid(&part.right_centroids, &prims[j]);
        i++;
    }
    part.mid = i;
    return part;
}

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
        Box acc = empty_box;
        for (uint32_t i = end - 1; i > begin; i--) {
            box_grow(&acc, &b->prims[i]);
            b->scratch[i] = box_half_area(&acc);
        }
        acc = empty_box;
        for (uint32_t i = begin + 1; i < end; i++) {
            box_grow(&acc, &b->prims[i - 1]);
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
    best.cost = BVH_COST_TRAVERSAL + BVH_COST_INTERSECT * best_sum / box_half_area(box);
    return best;
}

/* Splits prims[begin, end) for an inner node (reordering it), or returns mid == end when the
 * range should be a leaf. */
static Partition choose_split(Builder *b, uint32_t begin, uint32_t end, const Box *box,
                              const Box *centroids, int depth)
{
    Partition leaf = {.mid = end};
    uint32_t n = end - begin;
    /* Past this depth only balanced splits keep the traversal stack from overflowing: along any
     * path depth + ceil(log2(n)) never exceeds BVH_STACK_SIZE (see the tests). */
    bool must_balance = depth + ceil_log2(n) >= BVH_STACK_SIZE;
    if (n == 1 || (n <= BVH_MAX_LEAF_SIZE && must_balance))
        return leaf;
    if (!must_balance) {
        bool small = n <= BVH_SMALL_NODE;
        Split split = b->full_sweep ? find_full_sweep_split(b, begin, end, box)
                      : small       ? find_small_split(b, begin, end, box)
                                    : find_binned_split(b, begin, end, box, centroids);
        if (split.axis >= 0) {
            if (n <= BVH_MAX_LEAF_SIZE && BVH_COST_INTERSECT * (double)n <= split.cost)
                return leaf;
            if (b->full_sweep || small)
                return partition_at(b, begin, split.mid, end);
            float plane = centroids->lo[split.axis] + (float)split.bin / split.scale;
            Partition part = partition_at_plane(b, begin, end, split.axis, plane);
            if (part.mid != begin && part.mid != end)
                return part;
        }
    }
    if (n <= BVH_MAX_LEAF_SIZE)
        return leaf;
    /* Object median on the widest centroid axis (all centroids equal: any order will do). */
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (centroids->hi[k] - centroids->lo[k] > centroids->hi[axis] - centroids->lo[axis])
            axis = k;
    if (centroids->hi[axis] > centroids->lo[axis])
        sort_by_centroid(b, begin, end, axis);
    return partition_at(b, begin, begin + n / 2, end);
}

static void set_child(float4 *lo, float4 *hi, const Box *box, ChildRef ref)
{
    for (int k = 0; k < 3; k++) {
        lo->s[k] = box->lo[k];
        hi->s[k] = box->hi[k];
    }
    memcpy(&lo->s[3], &ref.ref, sizeof ref.ref);
    memcpy(&hi->s[3], &ref.count, sizeof ref.count);
}

/* Builds the subtree over prims[begin, end), whose box and centroid box are given. */
static ChildRef build_subtree(Builder *b, uint32_t begin, uint32_t end, const Box *box,
                              const Box *centroids, int depth)
{
    Partition part = choose_split(b, begin, end, box, centroids, depth);
    if (part.mid == end) {
        b->cost_sum += BVH_COST_INTERSECT * (end - begin) * box_half_area(box);
        return (ChildRef){~begin, end - begin};
    }
    b->cost_sum += BVH_COST_TRAVERSAL * box_half_area(box);
    uint32_t index = b->num_nodes++; /* pre-order: the left subtree follows */
    ChildRef left = build_subtree(b, begin, part.mid, &part.left_box, &part.left_centroids, depth + 1);
    ChildRef right = build_subtree(b, part.mid, end, &part.right_box, &part.right_centroids, depth + 1);
    BvhNode *node = &b->nodes[index];
    set_child(&node->lmin, &node->lmax, &part.left_box, left);
    set_child(&node->rmin, &node->rmax, &part.right_box, right);
    return (ChildRef){index, 0};
}

static void build(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n,
                  bool full_sweep)
{
    memset(bvh, 0, sizeof *bvh);
    /* Leaves hold ~first in an int lane, and build records a biased index: both fit. */
    if (n > PRIM_INDEX_LIMIT)
        die("BVH: %u triangles is more than the %u a BVH can index", n, PRIM_INDEX_LIMIT);
    Builder b = {0};
    b.full_sweep = full_sweep;
    b.prims = malloc((n ? n : 1) * sizeof *b.prims);
    b.scratch = full_sweep ? malloc((n ? n : 1) * sizeof *b.scratch) : NULL;
    /* A binary tree over n >= 1 leaves has n - 1 inner nodes; one more when the root is a leaf. */
    b.nodes = malloc((n ? n : 1) * sizeof *b.nodes);
    bvh->tris = malloc((n ? n : 1) * sizeof *bvh->tris);
    if (!b.prims || !b.nodes || !bvh->tris || (full_sweep && !b.scratch))
        die("out of memory building the BVH (%u triangles)", n);

    Box box = empty_box, centroids = empty_box;
    for (uint32_t i = 0; i < n; i++) {
        BuildPrim *prim = &b.prims[i];
        *prim = empty_box;
        for (int corner = 0; corner < 3; corner++) {
            const float4 *p = &positions[triangles[i].v.s[corner]];
            for (int k = 0; k < 3; k++) {
                prim->lo[k] = p->s[k] < prim->lo[k] ? p->s[k] : prim->lo[k];
                prim->hi[k] = p->s[k] > prim->hi[k] ? p->s[k] : prim->hi[k];
            }
        }
        prim_set_index(prim, i);
        prim->hi[3] = 0.0f;
        box_grow(&box, prim);
        box_grow_centroid(&centroids, prim);
    }

    ChildRef root = n ? build_subtree(&b, 0, n, &box, &centroids, 0) : (ChildRef){~0u, 0};
    if (b.num_nodes == 0) {
        /* The whole tree is one leaf: give it a root node with an empty right child, whose
         * inverted infinite box every ray misses. */
        b.cost_sum += BVH_COST_TRAVERSAL * box_half_area(&box);
        set_child(&b.nodes[0].lmin, &b.nodes[0].lmax, &box, root);
        set_child(&b.nodes[0].rmin, &b.nodes[0].rmax, &empty_box, (ChildRef){~0u, 0});
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
    build(bvh, positions, triangles, n, false);
}

void bvh_build_full_sweep(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n)
{
    build(bvh, positions, triangles, n, true);
}

void bvh_free(Bvh *bvh)
{
    free(bvh->nodes);
    free(bvh->tris);
    memset(bvh, 0, sizeof *bvh);
}
