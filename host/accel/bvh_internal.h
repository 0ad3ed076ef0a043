/* SPDX-License-Identifier: MIT */
/* bvh_internal.h: what the files of the BVH build share (accel/bvh_build.c drives it; the split
 * searches are in bvh_sah.c and bvh_full_sweep.c, the partitions in bvh_partition.c). Not for use
 * outside host/accel/. */
#ifndef PT_BVH_INTERNAL_H
#define PT_BVH_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "accel/box.h"
#include "accel/bvh.h"

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
    uint32_t max_leaf; /* records per leaf at most: BVH_MAX_LEAF_SIZE, 1 over instance boxes */
    double cost_sum; /* SAH sum, not yet divided by the root's area */
} Builder;

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

/* bvh_sah.c: best binned split of prims[begin, end); axis -1 when no axis has a centroid extent. */
Split bvh_find_binned_split(const Builder *b, uint32_t begin, uint32_t end, const Box *box,
                            const Box *centroids);
/* bvh_sah.c: exact split of a small node (n <= BVH_SMALL_NODE). Returns false when a leaf is
 * cheaper, else reorders the range and fills part. */
bool bvh_split_small_node(const Builder *b, uint32_t begin, uint32_t end, const Box *box,
                          Partition *part);

/* bvh_partition.c: both sides' bounds, by scanning them, for the splits that do not bin. */
Partition bvh_partition_at(const Builder *b, uint32_t begin, uint32_t mid, uint32_t end);
/* bvh_partition.c: partitions at a plane across axis (centroids below it go left). */
Partition bvh_partition_at_plane(Builder *b, uint32_t begin, uint32_t end, int axis, float plane);

/* bvh_full_sweep.c: sorts prims[begin, end) by centroid along axis (ties by triangle index). */
void bvh_sort_by_centroid(Builder *b, uint32_t begin, uint32_t end, int axis);
/* bvh_full_sweep.c: the reference split, every position between sorted centroids on every axis.
 * Leaves the range sorted on the best axis. */
Split bvh_find_full_sweep_split(Builder *b, uint32_t begin, uint32_t end, const Box *box);

#endif
