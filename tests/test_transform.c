// SPDX-License-Identifier: MIT
/* host/base/transform.c: the order of composition, the rotation sense, the matrix layout, the
 * inverse, the T R S decomposition (mirrors and shears included), interpolation along the
 * shortest arc, and swept boxes that hold every position a moving box's corners pass through. */
#include <criterion/criterion.h>
#include <float.h>
#include <math.h>

#include "base/transform.h"
#include "xorshift.h"

#define PI 3.14159265358979323846

static void expect_point(const Affine *a, double x, double y, double z, double ex, double ey,
                         double ez, const char *what)
{
    double p[3] = {x, y, z};
    affine_point(a, p, p);
    cr_expect(fabs(p[0] - ex) < 1e-12 && fabs(p[1] - ey) < 1e-12 && fabs(p[2] - ez) < 1e-12,
              "%s: (%g, %g, %g) -> (%.15g, %.15g, %.15g), expected (%g, %g, %g)", what, x, y, z,
              p[0], p[1], p[2], ex, ey, ez);
}

static void expect_affine_near(const Affine *a, const Affine *b, double tolerance, const char *what)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            cr_expect(fabs(a->m[i][j] - b->m[i][j]) <= tolerance * (1.0 + fabs(b->m[i][j])),
                      "%s: m[%d][%d] = %.15g, expected %.15g", what, i, j, a->m[i][j], b->m[i][j]);
}

static double uniform(uint64_t *state, double lo, double hi)
{
    return lo + (hi - lo) * (xorshift_next(state) / 4294967296.0);
}

static Affine rotation(double x, double y, double z, double degrees)
{
    double axis[3] = {x, y, z};
    Affine r;
    cr_assert(affine_rotate(axis, degrees, &r));
    return r;
}

static Affine random_affine(uint64_t *state, double max_degrees)
{
    Affine r = rotation(uniform(state, -1, 1), uniform(state, -1, 1), uniform(state, -1, 1) + 1e-3,
                        uniform(state, -max_degrees, max_degrees));
    Affine s = affine_scale(uniform(state, 0.3, 3), uniform(state, 0.3, 3), uniform(state, 0.3, 3));
    Affine t = affine_translate(uniform(state, -5, 5), uniform(state, -5, 5), uniform(state, -5, 5));
    Affine rs = affine_mul(&r, &s);
    return affine_mul(&t, &rs);
}

Test(transform, mul_applies_the_right_factor_first)
{
    Affine s = affine_scale(2, 2, 2), t = affine_translate(1, 0, 0);
    Affine scale_then_translate = affine_mul(&t, &s), translate_then_scale = affine_mul(&s, &t);
    expect_point(&scale_then_translate, 1, 0, 0, 3, 0, 0, "scale 2, then translate 1");
    expect_point(&translate_then_scale, 1, 0, 0, 4, 0, 0, "translate 1, then scale 2");
}

/* Counter-clockwise looking down the axis toward the origin, i.e. the right-hand rule. */
Test(transform, rotation_is_counter_clockwise_seen_from_the_axis_tip)
{
    Affine z = rotation(0, 0, 1, 90), y = rotation(0, 1, 0, 90), x = rotation(1, 0, 0, 90);
    expect_point(&z, 1, 0, 0, 0, 1, 0, "+90 about +z takes +x");
    expect_point(&z, 0, 1, 0, -1, 0, 0, "+90 about +z takes +y");
    expect_point(&y, 0, 0, 1, 1, 0, 0, "+90 about +y takes +z");
    expect_point(&y, 1, 0, 0, 0, 0, -1, "+90 about +y takes +x");
    expect_point(&x, 0, 1, 0, 0, 0, 1, "+90 about +x takes +y");
    Affine minus = rotation(0, 0, -2, 90); /* a longer, reversed axis: the other way round */
    expect_point(&minus, 1, 0, 0, 0, -1, 0, "+90 about -z takes +x");
    Affine diagonal = rotation(1, 1, 1, 120); /* cycles the axes */
    expect_point(&diagonal, 1, 0, 0, 0, 1, 0, "+120 about (1,1,1) takes +x");
    expect_point(&diagonal, 0, 0, 1, 1, 0, 0, "+120 about (1,1,1) takes +z");
    Affine out;
    double zero[3] = {0, 0, 0}, nan_axis[3] = {NAN, 0, 1};
    cr_expect_not(affine_rotate(zero, 30, &out), "a zero axis is refused");
    cr_expect_not(affine_rotate(nan_axis, 30, &out), "a NaN axis is refused");
}

Test(transform, rows16_are_row_major_with_translation_in_the_fourth_column)
{
    double rows[16] = {0, -1, 0, 1,  1, 0, 0, 2,  0, 0, 1, 3,  0, 0, 0, 1};
    Affine a;
    cr_assert(affine_from_rows16(rows, &a));
    expect_point(&a, 0, 0, 0, 1, 2, 3, "the origin goes to the fourth column");
    expect_point(&a, 1, 0, 0, 1, 3, 3, "x goes to the first column plus translation");
    double vec[3] = {1, 0, 0};
    affine_vector(&a, vec, vec);
    cr_expect(vec[0] == 0 && vec[1] == 1 && vec[2] == 0, "vectors ignore the translation");
    rows[14] = 0.5;
    cr_expect_not(affine_from_rows16(rows, &a), "a projective last row is refused");
}

Test(transform, inverse_undoes_and_singular_is_refused)
{
    uint64_t state = 0x1234567ull;
    for (int n = 0; n < 100; n++) {
        Affine a = random_affine(&state, 360), inverse;
        cr_assert(affine_invert(&a, &inverse));
        Affine product = affine_mul(&inverse, &a), id = affine_identity();
        expect_affine_near(&product, &id, 1e-12, "inverse * a");
        double n_obj[3] = {0.3, -0.5, 0.8}, tangent[3] = {0.5, 0.3, 0}, nw[3], tw[3];
        affine_normal(&inverse, n_obj, nw);
        affine_vector(&a, tangent, tw);
        cr_expect(fabs(nw[0] * tw[0] + nw[1] * tw[1] + nw[2] * tw[2]) < 1e-12,
                  "a transformed normal stays perpendicular to a transformed tangent");
    }
    Affine flat = affine_scale(1, 0, 1), inverse;
    cr_expect_not(affine_invert(&flat, &inverse), "a zero scale is singular");
    double rows[16] = {1, 2, 3, 0,  2, 4, 6, 0,  0, 0, 1, 0,  0, 0, 0, 1};
    Affine rank2;
    cr_assert(affine_from_rows16(rows, &rank2));
    cr_expect_not(affine_invert(&rank2, &inverse), "dependent rows are singular");
    Affine tiny = affine_scale(1e-9, 1e-9, 1e-9);
    cr_expect(affine_invert(&tiny, &inverse), "a small but regular scale inverts");
}

static void expect_round_trip(const Affine *a, const char *what)
{
    Trs trs;
    cr_assert(trs_decompose(a, &trs), "%s: decomposes", what);
    double qlen = sqrt(trs.q[0] * trs.q[0] + trs.q[1] * trs.q[1] + trs.q[2] * trs.q[2] +
                       trs.q[3] * trs.q[3]);
    cr_expect(fabs(qlen - 1.0) < 1e-12, "%s: unit quaternion (%g)", what, qlen);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            cr_expect(fabs(trs.s[i][j] - trs.s[j][i]) < 1e-12, "%s: S symmetric", what);
    Affine s = affine_identity();
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            s.m[i][j] = trs.s[i][j];
    cr_expect((affine_det(&s) < 0) == (affine_det(a) < 0), "%s: S keeps the mirror (det S %g, det M %g)",
              what, affine_det(&s), affine_det(a));
    Affine back = trs_compose(&trs);
    expect_affine_near(&back, a, 1e-10, what);
}

Test(transform, decompose_compose_round_trip)
{
    uint64_t state = 0xabcdefull;
    for (int n = 0; n < 200; n++) {
        Affine a = random_affine(&state, 360);
        expect_round_trip(&a, "rotate scale translate");
        Affine mirror = affine_scale(-1, 1, 1), mirrored = affine_mul(&a, &mirror);
        expect_round_trip(&mirrored, "mirrored");
        Affine shear = affine_identity();
        shear.m[0][1] = uniform(&state, -2, 2), shear.m[1][2] = uniform(&state, -2, 2);
        Affine sheared = affine_mul(&a, &shear);
        expect_round_trip(&sheared, "sheared");
        Affine both = affine_mul(&sheared, &mirror);
        expect_round_trip(&both, "sheared and mirrored");
    }
    /* Without shear, R is the rotation itself. */
    Affine r = rotation(0, 0, 1, 90), s = affine_scale(2, 3, 4), rs = affine_mul(&r, &s);
    Trs trs;
    cr_assert(trs_decompose(&rs, &trs));
    double h = sqrt(0.5);
    cr_expect(fabs(fabs(trs.q[2]) - h) < 1e-12 && fabs(fabs(trs.q[3]) - h) < 1e-12,
              "q = (0, 0, sin 45, cos 45): (%g, %g, %g, %g)", trs.q[0], trs.q[1], trs.q[2], trs.q[3]);
    cr_expect(fabs(trs.s[0][0] - 2) < 1e-12 && fabs(trs.s[1][1] - 3) < 1e-12 &&
              fabs(trs.s[2][2] - 4) < 1e-12, "S = diag(2, 3, 4)");
    Affine flat = affine_scale(1, 1, 0);
    cr_expect_not(trs_decompose(&flat, &trs), "a singular matrix does not decompose");
}

static Trs decompose(const Affine *a)
{
    Trs trs;
    cr_assert(trs_decompose(a, &trs));
    return trs;
}

Test(transform, interpolation_endpoints_and_midpoint)
{
    Affine a = affine_translate(0, 0, 0);
    Affine r = rotation(0, 0, 1, 90), t = affine_translate(2, 4, 0), s = affine_scale(3, 3, 3);
    Affine rs = affine_mul(&r, &s), b = affine_mul(&t, &rs);
    Trs ta = decompose(&a), tb = decompose(&b);
    Trs at0 = trs_interpolate(&ta, &tb, 0.0), at1 = trs_interpolate(&ta, &tb, 1.0);
    Affine m0 = trs_compose(&at0), m1 = trs_compose(&at1);
    expect_affine_near(&m0, &a, 1e-12, "f = 0");
    expect_affine_near(&m1, &b, 1e-12, "f = 1");
    Trs mid = trs_interpolate(&ta, &tb, 0.5);
    Affine m = trs_compose(&mid);
    double c = cos(PI / 4) * 2, sn = sin(PI / 4) * 2; /* rotated 45, scaled 2, moved (1, 2, 0) */
    expect_point(&m, 1, 0, 0, 1 + c, 2 + sn, 0, "midpoint of a 90 degree turn is 45 degrees");
}

Test(transform, interpolation_takes_the_shortest_arc)
{
    Affine a = affine_identity(), b = rotation(0, 0, 1, 350); /* = -10 degrees */
    Trs ta = decompose(&a), tb = decompose(&b), tb_negated = tb;
    for (int k = 0; k < 4; k++)
        tb_negated.q[k] = -tb.q[k];
    for (int variant = 0; variant < 2; variant++) {
        Trs mid = trs_interpolate(&ta, variant ? &tb_negated : &tb, 0.5);
        Affine m = trs_compose(&mid);
        expect_point(&m, 1, 0, 0, cos(-5 * PI / 180), sin(-5 * PI / 180), 0,
                     variant ? "with -q: -5 degrees" : "with q: -5 degrees, not 175");
    }
    Trs aligned = tb;
    trs_align(&ta, &aligned);
    double d = 0;
    for (int k = 0; k < 4; k++)
        d += ta.q[k] * aligned.q[k];
    cr_expect(d >= 0, "aligned quaternions have a non-negative dot product (%g)", d);
    Affine same = trs_compose(&aligned);
    expect_affine_near(&same, &b, 1e-12, "q and -q are the same rotation");
}

/* Every corner's path, sampled densely, lies in the swept box, and the box is not much larger
 * than the sampled one. */
Test(transform, swept_box_holds_sampled_corners)
{
    uint64_t state = 0x5eedull;
    for (int n = 0; n < 200; n++) {
        Affine a = random_affine(&state, 180), b = random_affine(&state, 180);
        if (n % 4 == 1) { /* mirrored at both ends */
            Affine mirror = affine_scale(1, -1, 1);
            a = affine_mul(&a, &mirror), b = affine_mul(&b, &mirror);
        }
        Trs ta = decompose(&a), tb = decompose(&b);
        float lo[3], hi[3];
        for (int k = 0; k < 3; k++)
            lo[k] = (float)uniform(&state, -2, 1), hi[k] = lo[k] + (float)uniform(&state, 0.1, 3);
        float box_lo[3], box_hi[3];
        trs_swept_box(&ta, &tb, lo, hi, box_lo, box_hi);
        double seen_lo[3] = {INFINITY, INFINITY, INFINITY}, seen_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int step = 0; step <= 2000; step++) {
            Trs at = trs_interpolate(&ta, &tb, step / 2000.0);
            Affine m = trs_compose(&at);
            for (int corner = 0; corner < 8; corner++) {
                double p[3] = {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1],
                               corner & 4 ? hi[2] : lo[2]};
                affine_point(&m, p, p);
                for (int k = 0; k < 3; k++) {
                    seen_lo[k] = fmin(seen_lo[k], p[k]), seen_hi[k] = fmax(seen_hi[k], p[k]);
                    cr_assert(p[k] >= box_lo[k] && p[k] <= box_hi[k],
                              "case %d, f = %g, corner %d: axis %d at %.9g outside [%.9g, %.9g]", n,
                              step / 2000.0, corner, k, p[k], box_lo[k], box_hi[k]);
                }
            }
        }
        for (int k = 0; k < 3; k++) {
            double extent = seen_hi[k] - seen_lo[k], box = (double)box_hi[k] - box_lo[k];
            cr_expect(box <= 2.0 * extent, "case %d axis %d: swept box %g vs sampled extent %g", n,
                      k, box, extent);
        }
    }
}

/* affine_points_box (the TLAS's box of a turned instance, render/scene_upload.c) holds every point
 * transformed in double, is no larger than affine_box of the points' bounds, and is tight: each
 * face touches a point within a few float ulps. */
Test(transform, points_box_holds_every_point_and_is_tight)
{
    uint64_t state = 41;
    enum { N = 200 };
    float4 points[N];
    for (int trial = 0; trial < 50; trial++) {
        Affine a = random_affine(&state, 180.0);
        float plo[3] = {INFINITY, INFINITY, INFINITY}, phi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int i = 0; i < N; i++)
            for (int k = 0; k < 4; k++) {
                points[i].s[k] = k < 3 ? (float)uniform(&state, -2, 2) : 0.0f;
                if (k < 3)
                    plo[k] = fminf(plo[k], points[i].s[k]), phi[k] = fmaxf(phi[k], points[i].s[k]);
            }
        float lo[3], hi[3], clo[3], chi[3];
        affine_points_box(&a, points, N, lo, hi);
        affine_box(&a, plo, phi, clo, chi);
        double reach_lo[3] = {INFINITY, INFINITY, INFINITY}, reach_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int i = 0; i < N; i++) {
            double p[3] = {points[i].s[0], points[i].s[1], points[i].s[2]};
            affine_point(&a, p, p);
            for (int k = 0; k < 3; k++) {
                cr_expect(lo[k] <= p[k] && p[k] <= hi[k], "trial %d point %d axis %d outside", trial,
                          i, k);
                reach_lo[k] = fmin(reach_lo[k], p[k]), reach_hi[k] = fmax(reach_hi[k], p[k]);
            }
        }
        for (int k = 0; k < 3; k++) {
            cr_expect(clo[k] <= lo[k] && hi[k] <= chi[k], "trial %d axis %d: larger than the corners'", trial, k);
            double ulps = 4.0 * FLT_EPSILON * (1.0 + fabs(reach_lo[k]) + fabs(reach_hi[k]));
            cr_expect(reach_lo[k] - lo[k] <= ulps && hi[k] - reach_hi[k] <= ulps,
                      "trial %d axis %d: not tight", trial, k);
        }
    }
}
