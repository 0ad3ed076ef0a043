// SPDX-License-Identifier: MIT
/* bvh_partition.c: an inner node's two sides and their bounds, for the BVH build: by scanning
 * already ordered records, or by partitioning them at a split plane. */
#include <stdint.h>

#include "accel/bvh_internal.h"

/* Both sides' bounds, by scanning them, for the splits that do not bin. */
Partition bvh_partition_at(const Builder *b, uint32_t begin, uint32_t mid, uint32_t end)
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
Partition bvh_partition_at_plane(Builder *b, uint32_t begin, uint32_t end, int axis, float plane)
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

