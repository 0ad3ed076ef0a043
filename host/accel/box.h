/* SPDX-License-Identifier: MIT */
/* box.h: axis-aligned boxes in registers for the BVH build (accel/bvh_*.c). Box arithmetic runs on
 * x, y, z (and a spare lane) at once: SSE2 where the compiler offers it (every x86-64), plain C
 * with the same results elsewhere (base/lanes.h). */
#ifndef PT_BOX_H
#define PT_BOX_H

#include <math.h>
#include <string.h>

#include "base/lanes.h"

/* An axis-aligned box in registers; lane 3 is spare. */
typedef struct {
    Lanes lo, hi;
} Box;

static ALWAYS_INLINE Box empty_box(void)
{
    return (Box){lanes_splat(INFINITY), lanes_splat(-INFINITY)};
}

/* Twice the centre of a triangle's box: the factor cancels wherever centroids are used. */
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
static inline double box_half_area(const Box *box)
{
    float lo[4], hi[4];
    box_corners(box, lo, hi);
    double dx = (double)hi[0] - lo[0], dy = (double)hi[1] - lo[1], dz = (double)hi[2] - lo[2];
    return dx >= 0.0 ? dx * dy + dy * dz + dz * dx : 0.0;
}

/* The same in float, times `unit` (1 / the largest extent of the node being split): cheap for
 * the split searches, and no product overflows since one factor of each is at most 1. Measures
 * what half_areas_of_three (accel/bvh_sah.c) measures, so the two compare. */
static inline float box_half_area_in(const Box *box, float unit)
{
    float lo[4], hi[4];
    box_corners(box, lo, hi);
    float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    return dx >= 0.0f ? dx * unit * (dy + dz) + dy * unit * dz : 0.0f;
}

/* 1 / the box's largest extent (1 for a point or an empty box). */
static ALWAYS_INLINE float box_unit(const Box *box)
{
    float lo[4], hi[4], extent = 0.0f;
    box_corners(box, lo, hi);
    for (int k = 0; k < 3; k++)
        extent = hi[k] - lo[k] > extent ? hi[k] - lo[k] : extent;
    return extent > 0.0f ? 1.0f / extent : 1.0f;
}

#endif
