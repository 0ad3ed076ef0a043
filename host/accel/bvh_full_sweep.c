// SPDX-License-Identifier: MIT
/* bvh_full_sweep.c: the reference split search for tests and benchmarks (bvh_build_full_sweep):
 * every position between sorted centroids on every axis, O(n log n) per node. The binned build
 * uses the sort too, for its object-median fallback. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "accel/bvh_internal.h"

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

void bvh_sort_by_centroid(Builder *b, uint32_t begin, uint32_t end, int axis)
{
    int (*const compare[3])(const void *, const void *) = {compare_axis0, compare_axis1,
                                                           compare_axis2};
    qsort(b->prims + begin, end - begin, sizeof *b->prims, compare[axis]);
}

/* Reference split for tests and benchmarks: every position between sorted centroids on every
 * axis (O(n log n) per node). Leaves the range sorted on the best axis. */
Split bvh_find_full_sweep_split(Builder *b, uint32_t begin, uint32_t end, const Box *box)
{
    Split best = {.cost = INFINITY, .axis = -1};
    double best_sum = INFINITY;
    for (int axis = 0; axis < 3; axis++) {
        bvh_sort_by_centroid(b, begin, end, axis);
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
        bvh_sort_by_centroid(b, begin, end, best.axis);
    best.cost = b->costs.traversal + b->costs.intersect * best_sum / box_half_area(box);
    return best;
}

