// SPDX-License-Identifier: MIT
/* bvh_spatial.c: spatial splits for the BVH build (Stich, Friedrich & Dietrich 2009, "Spatial
 * Splits in Bounding Volume Hierarchies"). Where an object split leaves its two children
 * overlapping (large triangles: the walls of a room, a ground quad), a split plane may instead
 * cut the triangles that straddle it, each side keeping a reference to the triangle with the box
 * of the part on its side. A triangle may so sit in several leaves, each with a box of its own;
 * the traversal is unchanged (ties in t go to the lower triangle index, so a triangle met twice
 * is one hit). The build reserves room for the extra references (bvh_build.c). */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "accel/bvh_internal.h"
#include "base/error.h"

#define SPATIAL_BINS 32
/* A polygon clipped by up to six planes from a triangle has at most 3 + 6 corners. */
#define CLIP_MAX_CORNERS 9

/* Clips the convex polygon p[0..n) (x, y, z in double) to the half-space where coordinate axis
 * is >= plane (side 1) or <= plane (side -1); returns the corner count, into out. */
static int clip_polygon(const double (*p)[3], int n, int axis, double plane, int side,
                        double (*out)[3])
{
    int m = 0;
    for (int i = 0; i < n; i++) {
        const double *a = p[i], *b = p[(i + 1) % n];
        double da = side * (a[axis] - plane), db = side * (b[axis] - plane);
        if (da >= 0.0) {
            for (int k = 0; k < 3; k++)
                out[m][k] = a[k];
            m++;
        }
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            double t = da / (da - db);
            for (int k = 0; k < 3; k++)
                out[m][k] = a[k] + t * (b[k] - a[k]);
            out[m][axis] = plane;
            m++;
        }
    }
    return m;
}

/* The largest float <= x and the smallest >= x: the double box rounded outwards, and one float
 * step more for the double arithmetic's own rounding. */
static float float_below(double x)
{
    float f = (float)x;
    if ((double)f > x)
        f = nextafterf(f, -INFINITY);
    return nextafterf(f, -INFINITY);
}

static float float_above(double x)
{
    float f = (float)x;
    if ((double)f < x)
        f = nextafterf(f, INFINITY);
    return nextafterf(f, INFINITY);
}

/* The box of the part of triangle `index` inside [lo, hi], within [lo, hi]; false when the
 * triangle has no part there. It contains the exact part: the clipping runs in double and its box
 * is rounded outwards. */
bool bvh_clipped_box(const Builder *b, uint32_t index, const float lo[3], const float hi[3],
                     Box *out)
{
    double poly[2][CLIP_MAX_CORNERS][3];
    const uint4 v = b->triangles[index].v;
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 3; k++)
            poly[0][c][k] = b->positions[v.s[c]].s[k];
    int n = 3, cur = 0;
    for (int axis = 0; axis < 3 && n > 0; axis++) {
        n = clip_polygon((const double(*)[3])poly[cur], n, axis, lo[axis], 1, poly[!cur]);
        cur = !cur;
        n = n > 0 ? clip_polygon((const double(*)[3])poly[cur], n, axis, hi[axis], -1, poly[!cur]) : 0;
        cur = !cur;
    }
    if (n == 0)
        return false;
    double box_lo[3] = {INFINITY, INFINITY, INFINITY}, box_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            box_lo[k] = fmin(box_lo[k], poly[cur][i][k]);
            box_hi[k] = fmax(box_hi[k], poly[cur][i][k]);
        }
    _Alignas(16) float l[4] = {0}, h[4] = {0};
    for (int k = 0; k < 3; k++) {
        l[k] = fmaxf(float_below(box_lo[k]), lo[k]);
        h[k] = fminf(float_above(box_hi[k]), hi[k]);
    }
    *out = (Box){lanes_load(l), lanes_load(h)};
    return true;
}

/* The plane between bins i - 1 and i of [lo, hi]: the same float wherever it is computed. */
static float bin_plane(float lo, float hi, int i)
{
    return i >= SPATIAL_BINS ? hi : lo + (hi - lo) * ((float)i / SPATIAL_BINS);
}

static int bin_of(float x, float lo, float hi)
{
    float s = (x - lo) / (hi - lo) * SPATIAL_BINS;
    int i = s > 0.0f ? (int)s : 0; /* NaN goes to bin 0 */
    return i < SPATIAL_BINS - 1 ? i : SPATIAL_BINS - 1;
}

/* The record's triangle part in the slab [plane_lo, plane_hi] along axis (and inside its box). */
static bool record_in_slab(const Builder *b, const BuildPrim *prim, int axis, float plane_lo,
                           float plane_hi, Box *out)
{
    float lo[3] = {prim->lo[0], prim->lo[1], prim->lo[2]};
    float hi[3] = {prim->hi[0], prim->hi[1], prim->hi[2]};
    lo[axis] = fmaxf(lo[axis], plane_lo);
    hi[axis] = fminf(hi[axis], plane_hi);
    if (!(lo[axis] <= hi[axis]))
        return false;
    return bvh_clipped_box(b, prim_index(prim), lo, hi, out);
}

/* Best spatial split of prims[begin, end) (whose box is given): SPATIAL_BINS slabs on each axis,
 * each record's triangle clipped into every slab its box spans; a record counts on the left of a
 * plane when it enters below it, on the right when it leaves above it. */
SpatialSplit bvh_find_spatial_split(const Builder *b, uint32_t begin, uint32_t end, const Box *box)
{
    SpatialSplit best = {INFINITY, -1, 0.0f};
    float lo[4], hi[4];
    box_corners(box, lo, hi);
    double node_area = box_half_area(box);
    if (!(node_area > 0.0))
        return best;
    for (int axis = 0; axis < 3; axis++) {
        if (!(hi[axis] > lo[axis]))
            continue;
        Box bins[SPATIAL_BINS];
        uint32_t entries[SPATIAL_BINS] = {0}, exits[SPATIAL_BINS] = {0};
        for (int i = 0; i < SPATIAL_BINS; i++)
            bins[i] = empty_box();
        for (uint32_t r = begin; r < end; r++) {
            const BuildPrim *prim = &b->prims[r];
            int first = bin_of(prim->lo[axis], lo[axis], hi[axis]);
            int last = bin_of(prim->hi[axis], lo[axis], hi[axis]);
            entries[first]++;
            exits[last]++;
            if (first == last) {
                Box whole = box_of(prim);
                box_grow(&bins[first], &whole);
                continue;
            }
            for (int i = first; i <= last; i++) {
                Box part;
                if (record_in_slab(b, prim, axis, bin_plane(lo[axis], hi[axis], i),
                                   bin_plane(lo[axis], hi[axis], i + 1), &part))
                    box_grow(&bins[i], &part);
            }
        }
        /* Sweep: right sides from the top down, then every plane from the bottom up. */
        double right_term[SPATIAL_BINS];
        Box acc = empty_box();
        uint32_t count = 0;
        for (int i = SPATIAL_BINS - 1; i > 0; i--) {
            box_grow(&acc, &bins[i]);
            count += exits[i];
            right_term[i] = count ? box_half_area(&acc) * count : INFINITY;
        }
        acc = empty_box();
        count = 0;
        for (int i = 1; i < SPATIAL_BINS; i++) {
            box_grow(&acc, &bins[i - 1]);
            count += entries[i - 1];
            if (!count || right_term[i] == INFINITY)
                continue;
            double cost = b->costs.traversal +
                          b->costs.intersect * (box_half_area(&acc) * count + right_term[i]) / node_area;
            if (cost < best.cost)
                best = (SpatialSplit){cost, axis, bin_plane(lo[axis], hi[axis], i)};
        }
    }
    return best;
}

static void grow_side(Box *side, Box *centroids, const Box *prim_box)
{
    box_grow(side, prim_box);
    box_grow_point(centroids, centroid_of(prim_box));
}

/* Splits prims[begin, end) at the plane: records below it go left, above it right, and those
 * across it to both sides with the boxes of their parts, as long as there is room below limit;
 * past that, a record across goes whole to the side of its centre. The left side is written to
 * [begin, part->mid), the right to [part->mid, part->end). False when one side is empty (the
 * range then keeps its count: split it by objects). */
bool bvh_partition_spatial(Builder *b, uint32_t begin, uint32_t end, uint32_t limit,
                           SpatialSplit split, Partition *part)
{
    int axis = split.axis;
    float plane = split.plane;
    uint32_t room = limit - end;
    BuildPrim *right = malloc((size_t)(end - begin) * sizeof *right);
    if (!right)
        die("out of memory building the BVH (%u records)", end - begin);
    Box left_box = empty_box(), left_centroids = empty_box();
    Box right_box = empty_box(), right_centroids = empty_box();
    uint32_t write = begin, num_right = 0;
    for (uint32_t r = begin; r < end; r++) {
        BuildPrim prim = b->prims[r];
        Box whole = box_of(&prim), left_part, right_part;
        bool to_left, to_right;
        if (prim.hi[axis] <= plane) {
            to_left = true, to_right = false, left_part = whole;
        } else if (prim.lo[axis] >= plane) {
            to_left = false, to_right = true, right_part = whole;
        } else if (room == 0) {
            to_left = prim.lo[axis] + prim.hi[axis] < 2.0f * plane, to_right = !to_left;
            left_part = right_part = whole;
        } else {
            to_left = record_in_slab(b, &prim, axis, -INFINITY, plane, &left_part);
            to_right = record_in_slab(b, &prim, axis, plane, INFINITY, &right_part);
            if (!to_left && !to_right) /* rounding only: keep the record whole, on the left */
                to_left = true, left_part = whole;
            room -= to_left && to_right;
        }
        uint32_t index = prim_index(&prim);
        if (to_left) {
            prim_store(&b->prims[write], &left_part);
            prim_set_index(&b->prims[write], index);
            b->prims[write].hi[3] = 0.0f;
            grow_side(&left_box, &left_centroids, &left_part);
            write++;
        }
        if (to_right) {
            prim_store(&right[num_right], &right_part);
            prim_set_index(&right[num_right], index);
            right[num_right].hi[3] = 0.0f;
            grow_side(&right_box, &right_centroids, &right_part);
            num_right++;
        }
    }
    /* Every part on one side (rounding, or a plane that separates nothing): then no record went
     * to both, so the range keeps its count, its records still whole or clipped to their parts
     * in this node: the caller splits it by objects instead. */
    bool both_sides = write > begin && num_right > 0;
    for (uint32_t i = 0; i < num_right; i++)
        b->prims[write + i] = right[i];
    free(right);
    *part = (Partition){write, left_box, left_centroids, right_box, right_centroids, write + num_right};
    return both_sides;
}
