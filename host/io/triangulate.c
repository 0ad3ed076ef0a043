// SPDX-License-Identifier: MIT
/* Ear clipping of one planar polygon. The polygon is projected onto the coordinate plane its Newell
 * normal is most aligned with (dropping a coordinate keeps the float inputs exact), and every
 * orientation test runs in double, where the cross product of float differences is exact up to one
 * rounding. Each step removes one corner, by the first rule that finds one (next_corner):
 *   1. a zero-area detour (repeated corner, spike tip): removed, no triangle;
 *   2. an ear with no other corner inside or on it: clipped;
 *   3. an ear with corners only on its new diagonal: clipped;
 *   4. a corner on a straight run: removed, no triangle (a simple polygon rarely gets here);
 *   5. the most convex corner, clipped regardless: only when the projection folds over (a twisted,
 *      non-planar face), so such faces still get n - 2 triangles.
 * Collinear corners are thus never clipped while a real ear exists, and a polygon with collinear
 * corners still yields n - 2 triangles. Cost is O(n^2) per corner; OBJ faces are small. */
#include "io/triangulate.h"

#include <float.h>
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

/* Polygons up to this size are triangulated without touching the heap. */
#define STACK_CORNERS 64

typedef struct {
    double u, v;
} Point2;

typedef struct {
    const Point2 *points;
    uint32_t *prev, *next; /* ring of the corners not yet clipped */
    double orientation;    /* +1 when the projected polygon is counter-clockwise, -1 otherwise */
    double collinear_eps;  /* |cross| at or below this is treated as zero */
} Ring;

static double cross2(Point2 a, Point2 b, Point2 c)
{
    return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

static bool same_point(Point2 a, Point2 b) { return a.u == b.u && a.v == b.v; }

/* Projects onto the plane of the largest Newell-normal component, keeping its cyclic axis order so
 * that the 2-D signed area has the sign of that component. Returns false for zero area. */
static bool project_polygon(const float *points, size_t n, Point2 *out, double *orientation)
{
    double normal[3] = {0, 0, 0};
    for (size_t i = 0; i < n; i++) {
        const float *a = points + 3 * i, *b = points + 3 * ((i + 1) % n);
        normal[0] += ((double)a[1] - b[1]) * ((double)a[2] + b[2]);
        normal[1] += ((double)a[2] - b[2]) * ((double)a[0] + b[0]);
        normal[2] += ((double)a[0] - b[0]) * ((double)a[1] + b[1]);
    }
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(normal[k]) > fabs(normal[axis]))
            axis = k;
    if (!(fabs(normal[axis]) > 0.0)) /* also rejects NaN */
        return false;
    int axis_u = (axis + 1) % 3, axis_v = (axis + 2) % 3;
    for (size_t i = 0; i < n; i++)
        out[i] = (Point2){points[3 * i + axis_u], points[3 * i + axis_v]};
    *orientation = normal[axis] > 0 ? 1.0 : -1.0;
    return true;
}

/* Tolerance for "collinear": the cross product error that rounding the corners to float can
 * cause (about 4 * extent * float ulp of the largest coordinate), so corners meant to lie on a
 * line are recognised even far from the origin. */
static double collinear_tolerance(const Point2 *p, size_t n)
{
    double min_u = p[0].u, max_u = p[0].u, min_v = p[0].v, max_v = p[0].v, largest = 0;
    for (size_t i = 0; i < n; i++) {
        min_u = fmin(min_u, p[i].u);
        max_u = fmax(max_u, p[i].u);
        min_v = fmin(min_v, p[i].v);
        max_v = fmax(max_v, p[i].v);
        largest = fmax(largest, fmax(fabs(p[i].u), fabs(p[i].v)));
    }
    double extent = fmax(max_u - min_u, max_v - min_v);
    return fmax(1e-12 * extent * extent, 4.0 * FLT_EPSILON * largest * extent);
}

/* Signed turn at corner c (positive = convex for this polygon's orientation). */
static double turn(const Ring *r, uint32_t c)
{
    return r->orientation * cross2(r->points[r->prev[c]], r->points[c], r->points[r->next[c]]);
}

/* Where p lies against triangle abc (oriented like the polygon): 1 inside, 0 on its boundary
 * (within the collinear tolerance, so a diagonal through a corner rounded off it counts as
 * touching), -1 outside. */
static int triangle_side(const Ring *r, Point2 a, Point2 b, Point2 c, Point2 p)
{
    double ab = r->orientation * cross2(a, b, p), bc = r->orientation * cross2(b, c, p),
           ca = r->orientation * cross2(c, a, p);
    double eps = r->collinear_eps;
    if (ab < -eps || bc < -eps || ca < -eps)
        return -1;
    return ab > eps && bc > eps && ca > eps ? 1 : 0;
}

/* A strictly convex corner whose triangle holds no other remaining corner (strict) or none
 * strictly inside (touching: corners on the new diagonal are allowed). Corners that coincide with
 * the triangle's own corners (pinch points of a weakly simple polygon) never block. */
static bool is_ear_with(const Ring *r, uint32_t c, int blocking_side)
{
    if (turn(r, c) <= r->collinear_eps)
        return false;
    Point2 a = r->points[r->prev[c]], b = r->points[c], d = r->points[r->next[c]];
    for (uint32_t q = r->next[r->next[c]]; q != r->prev[c]; q = r->next[q]) {
        Point2 p = r->points[q];
        if (same_point(p, a) || same_point(p, b) || same_point(p, d))
            continue;
        if (triangle_side(r, a, b, d, p) >= blocking_side)
            return false;
    }
    return true;
}

static bool is_strict_ear(const Ring *r, uint32_t c) { return is_ear_with(r, c, 0); }
static bool is_touching_ear(const Ring *r, uint32_t c) { return is_ear_with(r, c, 1); }

/* A zero-area detour: a corner repeating a neighbour, or the tip of a spike that runs back along
 * itself. Removing it changes nothing, and left in place it would hide outside area from the ear
 * test (the spike's base coincides with a corner, which does not block). */
static bool is_detour(const Ring *r, uint32_t c)
{
    Point2 a = r->points[r->prev[c]], b = r->points[c], d = r->points[r->next[c]];
    if (same_point(a, b) || same_point(b, d))
        return true;
    double forward = (b.u - a.u) * (d.u - b.u) + (b.v - a.v) * (d.v - b.v);
    return fabs(turn(r, c)) <= r->collinear_eps && forward < 0;
}

/* A corner on a straight run: removing it loses no area, but also one triangle. */
static bool is_straight(const Ring *r, uint32_t c) { return fabs(turn(r, c)) <= r->collinear_eps; }

static void unlink_corner(Ring *r, uint32_t c)
{
    r->next[r->prev[c]] = r->next[c];
    r->prev[r->next[c]] = r->prev[c];
}

/* Writes the triangle at corner c in ring order, which is the polygon's orientation. */
static size_t emit_corner(const Ring *r, uint32_t c, uint32_t *out)
{
    out[0] = r->prev[c];
    out[1] = c;
    out[2] = r->next[c];
    return 1;
}

/* The most convex corner: when the projected polygon folds over (a twisted face), clipping it
 * still covers the face with n - 2 triangles, as a fan would. */
static uint32_t sharpest_corner(const Ring *r, uint32_t start, size_t remaining)
{
    uint32_t best = start;
    uint32_t c = start;
    for (size_t i = 0; i < remaining; i++, c = r->next[c])
        if (turn(r, c) > turn(r, best))
            best = c;
    return best;
}

/* The corner to remove next, by the first rule that finds one, looking around the ring from
 * start; *emit says whether it leaves a triangle behind. */
static uint32_t next_corner(const Ring *r, uint32_t start, size_t remaining, bool *emit)
{
    static const struct {
        bool (*applies)(const Ring *, uint32_t);
        bool emits;
    } rules[] = {
        {is_detour, false}, {is_strict_ear, true}, {is_touching_ear, true}, {is_straight, false}};
    for (size_t rule = 0; rule < sizeof rules / sizeof rules[0]; rule++) {
        uint32_t c = start;
        for (size_t i = 0; i < remaining; i++, c = r->next[c])
            if (rules[rule].applies(r, c)) {
                *emit = rules[rule].emits;
                return c;
            }
    }
    /* No ear at all: the projection folds over (a non-planar or self-crossing polygon). */
    uint32_t c = sharpest_corner(r, start, remaining);
    *emit = fabs(turn(r, c)) > r->collinear_eps;
    return c;
}

/* Removes corners until three remain; returns the triangles written. */
static size_t clip_ears(Ring *r, size_t n, uint32_t *out)
{
    size_t written = 0, remaining = n;
    uint32_t cursor = 0;
    for (; remaining > 3; remaining--) {
        bool emit;
        uint32_t c = next_corner(r, cursor, remaining, &emit);
        if (emit)
            written += emit_corner(r, c, out + 3 * written);
        cursor = r->prev[c]; /* the next ear is most likely next to this one */
        unlink_corner(r, c);
    }
    if (fabs(turn(r, cursor)) > r->collinear_eps)
        written += emit_corner(r, cursor, out + 3 * written);
    return written;
}

size_t triangulate_polygon(const float *points, size_t n, uint32_t *out)
{
    if (n < 3 || n > UINT32_MAX)
        return 0;
    if (n == 3) { /* a triangle is its own triangulation, degenerate or not */
        out[0] = 0;
        out[1] = 1;
        out[2] = 2;
        return 1;
    }
    Point2 stack_points[STACK_CORNERS];
    uint32_t stack_links[2 * STACK_CORNERS];
    Point2 *projected = stack_points;
    uint32_t *links = stack_links;
    if (n > STACK_CORNERS) {
        projected = malloc(n * sizeof *projected);
        links = malloc(2 * n * sizeof *links);
        if (!projected || !links) {
            free(projected);
            free(links);
            return 0;
        }
    }
    size_t written = 0;
    Ring ring = {.points = projected, .prev = links, .next = links + n};
    if (project_polygon(points, n, projected, &ring.orientation)) {
        ring.collinear_eps = collinear_tolerance(projected, n);
        for (size_t i = 0; i < n; i++) {
            ring.prev[i] = (uint32_t)((i + n - 1) % n);
            ring.next[i] = (uint32_t)((i + 1) % n);
        }
        written = clip_ears(&ring, n, out);
    }
    if (n > STACK_CORNERS) {
        free(projected);
        free(links);
    }
    return written;
}
