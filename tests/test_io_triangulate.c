// SPDX-License-Identifier: MIT
/* Ear clipping (host/io/triangulate.c): every polygon is given in 2-D, embedded in a tilted 3-D plane,
 * triangulated, and checked against the 2-D original: triangle count, total area, every triangle
 * inside the polygon (sample points inside, no edge crossing the boundary), same orientation as the
 * polygon, no degenerate triangle. Degenerate inputs must terminate and stay inside. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/triangulate.h"

#define MAX_CORNERS 512
#define GUARD 0xDEADBEEFu
#define PI 3.14159265358979323846

typedef struct {
    double x, y;
} P2;

typedef struct {
    P2 p[MAX_CORNERS];
    size_t n;
} Poly;

/* A frame for embedding 2-D polygons in 3-D: origin + two orthonormal axes. */
typedef struct {
    double origin[3], u[3], v[3];
} Plane;

static const Plane planes[] = {
    {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},                /* xy */
    {{1, 2, 3}, {0, 0, 1}, {1, 0, 0}},                /* zx */
    {{-5, 7, 2}, {0, 1, 0}, {0, 0, -1}},              /* yz, mirrored */
    {{10, -5, 3}, {0.6, 0.8, 0}, {-0.48, 0.36, 0.8}}, /* tilted */
    {{0.5, 0.5, -2},
     {0.5773502691896258, 0.5773502691896258, 0.5773502691896258},
     {0.7071067811865476, -0.7071067811865476, 0}}, /* along the diagonal */
};
#define NUM_PLANES (sizeof planes / sizeof planes[0])

static void embed(const Poly *poly, const Plane *plane, float *points)
{
    for (size_t i = 0; i < poly->n; i++)
        for (int k = 0; k < 3; k++)
            points[3 * i + k] =
                (float)(plane->origin[k] + poly->p[i].x * plane->u[k] + poly->p[i].y * plane->v[k]);
}

static double signed_area(const Poly *poly)
{
    double twice = 0;
    for (size_t i = 0; i < poly->n; i++) {
        P2 a = poly->p[i], b = poly->p[(i + 1) % poly->n];
        twice += a.x * b.y - b.x * a.y;
    }
    return twice / 2;
}

static double cross(P2 a, P2 b, P2 c)
{
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/* Crossing-number test; points on the boundary count as inside. */
static bool inside_polygon(const Poly *poly, P2 q)
{
    bool inside = false;
    for (size_t i = 0, j = poly->n - 1; i < poly->n; j = i++) {
        P2 a = poly->p[i], b = poly->p[j];
        double len = hypot(b.x - a.x, b.y - a.y);
        bool between = fmin(a.x, b.x) - 1e-9 <= q.x && q.x <= fmax(a.x, b.x) + 1e-9 &&
                       fmin(a.y, b.y) - 1e-9 <= q.y && q.y <= fmax(a.y, b.y) + 1e-9;
        if (between && fabs(cross(a, b, q)) <= 1e-9 * (len > 0 ? len : 1))
            return true;
        if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x)
            inside = !inside;
    }
    return inside;
}

/* True when segments ab and cd cross at a point interior to both. */
static bool proper_crossing(P2 a, P2 b, P2 c, P2 d)
{
    double d1 = cross(a, b, c), d2 = cross(a, b, d), d3 = cross(c, d, a), d4 = cross(c, d, b);
    return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/* Every triangle lies in the polygon: sample points inside and no edge crossing the boundary. */
static void expect_triangle_inside(const Poly *poly, const uint32_t *t, const char *what)
{
    P2 a = poly->p[t[0]], b = poly->p[t[1]], c = poly->p[t[2]];
    static const double weights[][3] = {
        {1. / 3, 1. / 3, 1. / 3}, {0.6, 0.2, 0.2}, {0.2, 0.6, 0.2}, {0.2, 0.2, 0.6}};
    for (size_t s = 0; s < sizeof weights / sizeof weights[0]; s++) {
        P2 q = {weights[s][0] * a.x + weights[s][1] * b.x + weights[s][2] * c.x,
                weights[s][0] * a.y + weights[s][1] * b.y + weights[s][2] * c.y};
        cr_expect(inside_polygon(poly, q), "%s: triangle (%u %u %u) sample %zu outside", what, t[0],
                  t[1], t[2], s);
    }
    P2 corners[3] = {a, b, c};
    for (int e = 0; e < 3; e++)
        for (size_t i = 0; i < poly->n; i++)
            cr_expect(!proper_crossing(corners[e], corners[(e + 1) % 3], poly->p[i],
                                       poly->p[(i + 1) % poly->n]),
                      "%s: triangle (%u %u %u) edge crosses polygon edge %zu", what, t[0], t[1],
                      t[2], i);
}

/* Runs the triangulator; checks indices and that it wrote nothing past n - 2 triangles. */
static size_t run(const Poly *poly, const Plane *plane, uint32_t *out, const char *what)
{
    static float points[3 * MAX_CORNERS];
    embed(poly, plane, points);
    size_t capacity = poly->n >= 3 ? 3 * (poly->n - 2) : 0;
    for (size_t i = 0; i < capacity + 3; i++)
        out[i] = GUARD;
    size_t count = triangulate_polygon(points, poly->n, out);
    cr_assert(count <= (poly->n >= 3 ? poly->n - 2 : 0), "%s: %zu triangles for %zu corners", what,
              count, poly->n);
    for (size_t i = capacity; i < capacity + 3; i++)
        cr_assert_eq(out[i], GUARD, "%s: wrote past n - 2 triangles", what);
    for (size_t i = 0; i < 3 * count; i++)
        cr_assert(out[i] < poly->n, "%s: index %u out of range", what, out[i]);
    return count;
}

/* The full contract for a simple polygon, on every plane and in both windings. */
static void check_simple(const Poly *original, const char *name)
{
    static uint32_t out[3 * MAX_CORNERS + 3];
    for (int winding = 0; winding < 2; winding++) {
        Poly poly = *original;
        if (winding)
            for (size_t i = 0; i < poly.n; i++)
                poly.p[i] = original->p[poly.n - 1 - i];
        double area = signed_area(&poly);
        for (size_t k = 0; k < NUM_PLANES; k++) {
            char what[128];
            snprintf(what, sizeof what, "%s (%s winding, plane %zu)", name,
                     winding ? "reversed" : "original", k);
            size_t count = run(&poly, &planes[k], out, what);
            cr_expect_eq(count, poly.n - 2, "%s: %zu triangles, want %zu", what, count, poly.n - 2);
            double total = 0;
            for (size_t t = 0; t < count; t++) {
                const uint32_t *tri = out + 3 * t;
                double tri_area = cross(poly.p[tri[0]], poly.p[tri[1]], poly.p[tri[2]]) / 2;
                cr_expect(tri_area * area > 0, "%s: triangle %zu flips the orientation", what, t);
                cr_expect(fabs(tri_area) > 1e-9 * fabs(area), "%s: triangle %zu degenerate", what,
                          t);
                expect_triangle_inside(&poly, tri, what);
                total += fabs(tri_area);
            }
            cr_expect(fabs(total - fabs(area)) <= 1e-4 * fabs(area),
                      "%s: triangles cover %g, polygon %g", what, total, fabs(area));
        }
    }
}

static Poly from_points(const double *xy, size_t n)
{
    Poly poly = {.n = n};
    for (size_t i = 0; i < n; i++)
        poly.p[i] = (P2){xy[2 * i], xy[2 * i + 1]};
    return poly;
}

/* The same polygon starting at corner `shift`. */
static Poly rotated(const Poly *poly, size_t shift)
{
    Poly out = {.n = poly->n};
    for (size_t i = 0; i < poly->n; i++)
        out.p[i] = poly->p[(i + shift) % poly->n];
    return out;
}

static void check_every_start(const double *xy, size_t n, const char *name)
{
    Poly poly = from_points(xy, n);
    for (size_t shift = 0; shift < n; shift++) {
        char what[96];
        snprintf(what, sizeof what, "%s from corner %zu", name, shift);
        Poly start = rotated(&poly, shift);
        check_simple(&start, what);
    }
}

Test(triangulate, regular_polygons_3_to_12)
{
    for (size_t n = 3; n <= 12; n++) {
        Poly poly = {.n = n};
        for (size_t i = 0; i < n; i++)
            poly.p[i] = (P2){2 * cos(2 * PI * i / n), 2 * sin(2 * PI * i / n)};
        char name[32];
        snprintf(name, sizeof name, "regular %zu-gon", n);
        check_simple(&poly, name);
    }
}

Test(triangulate, arrowhead_quad_uses_the_inner_diagonal)
{
    /* Reflex corner at (1, 2): the only valid diagonal joins it to the tip (4, 2). */
    const double dart[] = {0, 0, 4, 2, 0, 4, 1, 2};
    check_every_start(dart, 4, "arrowhead");
}

Test(triangulate, concave_shapes)
{
    const double l_shape[] = {0, 0, 3, 0, 3, 1, 1, 1, 1, 3, 0, 3};
    check_every_start(l_shape, 6, "L");
    const double u_shape[] = {0, 0, 3, 0, 3, 3, 2, 3, 2, 1, 1, 1, 1, 3, 0, 3};
    check_every_start(u_shape, 8, "U");
    const double comb[] = {0, 0, 7, 0, 7, 3, 6, 3, 6, 1, 5, 1, 5, 3, 4, 3,
                           4, 1, 3, 1, 3, 3, 2, 3, 2, 1, 1, 1, 1, 3, 0, 3};
    check_every_start(comb, 16, "comb");
    double star[20];
    for (int i = 0; i < 10; i++) {
        double radius = i % 2 ? 0.8 : 2.0, angle = PI / 2 + 2 * PI * i / 10;
        star[2 * i] = radius * cos(angle);
        star[2 * i + 1] = radius * sin(angle);
    }
    check_every_start(star, 10, "star");
    /* A spiral: long reflex chains where a wrong ear is easy to take. */
    const double spiral[] = {0, 0, 6, 0, 6, 6, 1, 6, 1, 2, 4, 2, 4, 4,
                             3, 4, 3, 3, 2, 3, 2, 5, 5, 5, 5, 1, 0, 1};
    check_every_start(spiral, 14, "spiral");
}

Test(triangulate, collinear_corners_on_edges_still_give_n_minus_2)
{
    const double square_with_midpoints[] = {0, 0, 1, 0, 2, 0, 2, 1, 2, 2, 1, 2, 0, 2, 0, 1};
    check_every_start(square_with_midpoints, 8, "square with midpoints");
}

/* Deterministic pseudo-random numbers in [0, 1). */
static double next_random(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return (*state >> 8) / 16777216.0;
}

Test(triangulate, random_star_shaped_polygons)
{
    uint32_t state = 12345;
    size_t sizes[] = {4, 5, 7, 16, 40, 65, 200}; /* 65 and 200 pass the stack limit */
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++)
        for (int trial = 0; trial < 4; trial++) {
            Poly poly = {.n = sizes[s]};
            for (size_t i = 0; i < poly.n; i++) {
                double angle = 2 * PI * (i + 0.8 * next_random(&state)) / poly.n;
                double radius = 0.2 + 3 * next_random(&state);
                poly.p[i] = (P2){radius * cos(angle), radius * sin(angle)};
            }
            char name[64];
            snprintf(name, sizeof name, "random star %zu #%d", poly.n, trial);
            check_simple(&poly, name);
        }
}

/* Degenerate input: must return, write only in-range indices, and add no area outside. */
static void check_degenerate(const double *xy, size_t n, const Poly *region, double region_area,
                             const char *name)
{
    static uint32_t out[3 * MAX_CORNERS + 3];
    Poly poly = from_points(xy, n);
    for (size_t k = 0; k < NUM_PLANES; k++) {
        char what[96];
        snprintf(what, sizeof what, "%s (plane %zu)", name, k);
        size_t count = run(&poly, &planes[k], out, what);
        double total = 0;
        for (size_t t = 0; t < count; t++) {
            const uint32_t *tri = out + 3 * t;
            double tri_area = fabs(cross(poly.p[tri[0]], poly.p[tri[1]], poly.p[tri[2]])) / 2;
            total += tri_area;
            if (region && tri_area > 0)
                expect_triangle_inside(region, tri, what);
        }
        /* Slack for corners rounded to float off their line in tilted planes. */
        cr_expect(total <= region_area * (1 + 1e-6) + 1e-5, "%s: triangles cover %g > %g", what,
                  total, region_area);
        if (region_area > 0)
            cr_expect(fabs(total - region_area) <= 1e-4 * region_area,
                      "%s: triangles cover %g, polygon %g", what, total, region_area);
    }
}

Test(triangulate, degenerate_inputs_terminate_and_stay_inside)
{
    const double collinear[] = {0, 0, 1, 0, 2, 0, 3, 0, 4, 0};
    check_degenerate(collinear, 5, NULL, 0, "all collinear");
    const double back_and_forth[] = {0, 0, 2, 0, 1, 0, 3, 0};
    check_degenerate(back_and_forth, 4, NULL, 0, "collinear back and forth");
    const double same_point[] = {1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
    check_degenerate(same_point, 5, NULL, 0, "one point repeated");
    const double two_points[] = {0, 0, 1, 1, 0, 0, 1, 1};
    check_degenerate(two_points, 4, NULL, 0, "two points repeated");

    /* The repeated corners and the zero-width spike must not change the covered square. */
    const double square_xy[] = {0, 0, 2, 0, 2, 2, 0, 2};
    Poly square = from_points(square_xy, 4);
    const double repeated[] = {0, 0, 0, 0, 2, 0, 2, 2, 2, 2, 0, 2};
    check_degenerate(repeated, 6, &square, 4, "square with repeated corners");
    const double spike[] = {0, 0, 2, 0, 2, 2, 1, 2, 1, 3, 1, 2, 0, 2};
    check_degenerate(spike, 7, &square, 4, "square with a zero-width spike");
    const double needle[] = {0, 0, 2, 0, 2, 2, 1, 2, 1, 1, 1, 2, 0, 2};
    check_degenerate(needle, 7, &square, 4, "square with an inward needle");
}

Test(triangulate, fewer_than_three_corners_and_nan_give_nothing)
{
    uint32_t out[16];
    const float points[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    cr_expect_eq(triangulate_polygon(points, 0, out), 0);
    cr_expect_eq(triangulate_polygon(points, 1, out), 0);
    cr_expect_eq(triangulate_polygon(points, 2, out), 0);
    const float with_nan[] = {0, 0, 0, 1, 0, 0, NAN, 1, 0, 0, 1, 0};
    size_t count = triangulate_polygon(with_nan, 4, out);
    cr_expect(count <= 2);
    for (size_t i = 0; i < 3 * count; i++)
        cr_expect(out[i] < 4);
}

Test(triangulate, twisted_quad_still_gives_two_triangles)
{
    /* A non-planar quad whose projection folds over (from Spot's control mesh): both triangles
     * are kept, and together they keep the quad's vector area (Newell normal). */
    const float quad[] = {0.210205f, 0.758202f, -0.246046f, 0.169506f, 0.796441f, -0.370178f,
                          0.17047f,  0.793819f, -0.366116f, 0.211178f, 0.765424f, -0.239481f};
    uint32_t out[6];
    cr_assert_eq(triangulate_polygon(quad, 4, out), 2);
    double newell[3] = {0, 0, 0}, sum[3] = {0, 0, 0};
    for (int i = 0; i < 4; i++) {
        const float *a = quad + 3 * i, *b = quad + 3 * ((i + 1) % 4);
        newell[0] += ((double)a[1] - b[1]) * ((double)a[2] + b[2]);
        newell[1] += ((double)a[2] - b[2]) * ((double)a[0] + b[0]);
        newell[2] += ((double)a[0] - b[0]) * ((double)a[1] + b[1]);
    }
    for (int t = 0; t < 2; t++) {
        const float *a = quad + 3 * out[3 * t], *b = quad + 3 * out[3 * t + 1],
                    *c = quad + 3 * out[3 * t + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        sum[0] += e1[1] * e2[2] - e1[2] * e2[1];
        sum[1] += e1[2] * e2[0] - e1[0] * e2[2];
        sum[2] += e1[0] * e2[1] - e1[1] * e2[0];
    }
    double norm = sqrt(newell[0] * newell[0] + newell[1] * newell[1] + newell[2] * newell[2]);
    for (int k = 0; k < 3; k++)
        cr_expect(fabs(sum[k] - newell[k]) <= 1e-4 * norm, "axis %d: %g vs %g", k, sum[k],
                  newell[k]);
}
