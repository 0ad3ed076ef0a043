/* SPDX-License-Identifier: MIT */
/* triangulate.h: ear-clipping triangulation of one planar polygon (convex or concave, either
 * winding) given by its 3-D corners. */
#ifndef PT_TRIANGULATE_H
#define PT_TRIANGULATE_H

#include <stddef.h>
#include <stdint.h>

/* Writes up to n - 2 triangles (indices into points, 0..n-1) to out (3 * (n - 2) entries), keeping
 * the polygon's orientation. Returns the number of triangles written: n - 2 for a simple polygon;
 * degenerate polygons (collinear or repeated corners) may yield fewer, never a triangle outside the
 * polygon. points: xyz per corner. n == 3 always gives {0, 1, 2}; n < 3 or zero area give 0. A
 * non-planar face whose projection folds over still gets n - 2 triangles. */
size_t triangulate_polygon(const float *points, size_t n, uint32_t *out);

#endif
