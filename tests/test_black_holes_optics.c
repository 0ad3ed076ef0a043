// SPDX-License-Identifier: MIT
/* The geodesic integrator of cl/stages/integrate_geodesic.cl (geodesic_step, run by the test
 * kernel tests/cl/geodesic_test.cl) against the optics it must reproduce: the deflection of a
 * high-accuracy double-precision integration of the same ODE (itself checked against the
 * weak-field series), conservation of h = |x x dx/dl|, and capture exactly below the critical
 * impact parameter 3 sqrt(3) M. */
#include <criterion/criterion.h>
#include <math.h>

#include "support.h"

#define PI 3.14159265358979323846

/* The host's reference: d^2x/dl^2 = -3 M h^2 x / |x|^5 in the plane (x, y), classic RK4 in double
 * with steps of 0.001 r (the device takes 0.08 r in float), from (x0, b) along +x until r > R or
 * r <= 2M (1 + eps). Returns the angle of the final direction, or NAN when captured. */
static double reference_deflection(double M, double b, double x0, double R, double eps)
{
    double s[4] = {x0, b, 1.0, 0.0}; /* x, y, vx, vy */
    double h2 = b * b;               /* conserved: the exact value, not the integrated one */
    for (long step = 0; step < 100000000L; step++) {
        double r = hypot(s[0], s[1]);
        if (r <= 2.0 * M * (1.0 + eps))
            return NAN;
        if (r > R && step > 0)
            return atan2(s[3], s[2]);
        double dl = 1e-3 * r / hypot(s[2], s[3]), k[4][4], t[4];
        for (int stage = 0; stage < 4; stage++) {
            const double c = stage == 0 ? 0.0 : stage == 3 ? 1.0 : 0.5;
            for (int j = 0; j < 4; j++)
                t[j] = s[j] + (stage ? c * dl * k[stage - 1][j] : 0.0);
            double rr = hypot(t[0], t[1]), a = -3.0 * M * h2 / pow(rr, 5.0);
            k[stage][0] = t[2], k[stage][1] = t[3], k[stage][2] = a * t[0], k[stage][3] = a * t[1];
        }
        for (int j = 0; j < 4; j++)
            s[j] += dl / 6.0 * (k[0][j] + 2.0 * k[1][j] + 2.0 * k[2][j] + k[3][j]);
    }
    return NAN;
}

/* The device's runs of geodesic_test_trace over impact parameters b[0..n) for one hole of mass M
 * at the origin with influence radius R. */
static void device_trace(double M, double R, const float *b, int n, cl_float4 *dir, cl_float4 *info)
{
    Device *dev = test_device();
    BlackHole hole = {.centre = {{0, 0, 0, (float)M}}, .normal = {{0, 1, 0, (float)R}},
                      .tangent = {{1, 0, 0, 0}}};
    Error err = {0};
    cl_mem hole_buf = device_buffer(dev, "hole", CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof hole, &hole, &err);
    cl_mem b_buf = device_buffer(dev, "b", CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof *b, b, &err);
    cl_mem dir_buf = device_buffer(dev, "dir", CL_MEM_WRITE_ONLY, n * sizeof *dir, NULL, &err);
    cl_mem info_buf = device_buffer(dev, "info", CL_MEM_WRITE_ONLY, n * sizeof *info, NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel k = device_kernel(dev, "geodesic_test_trace");
    cl_uint count = (cl_uint)n;
    KERNEL_ARGS(k, 0, KARG(hole_buf), KARG(b_buf), KARG(count), KARG(dir_buf), KARG(info_buf));
    device_run(dev, k, (size_t)n, 0, NULL);
    device_read(dev, dir_buf, 0, n * sizeof *dir, dir);
    device_read(dev, info_buf, 0, n * sizeof *info, info);
    clReleaseKernel(k);
    clReleaseMemObject(hole_buf), clReleaseMemObject(b_buf), clReleaseMemObject(dir_buf),
        clReleaseMemObject(info_buf);
    test_device_release(dev);
}

/* Impact parameters from just outside the photon sphere's to the weak field. */
static const float impact[] = {5.25f, 5.3f, 5.5f, 6.0f, 7.0f, 8.0f, 10.0f, 15.0f, 20.0f, 30.0f,
                               50.0f, 100.0f, 200.0f, 400.0f, 700.0f, 1000.0f};
#define N_IMPACT ((int)(sizeof impact / sizeof impact[0]))
#define INFLUENCE 2000.0 /* the default for M = 1 (scene/black_holes.h) */

/* The reference integrator itself: started and ended far out (R = 10^6 M), it gives the
 * weak-field series 4M/b + 15 pi M^2 / (4 b^2) + 128 M^3 / (3 b^3) + 3465 pi M^4 / (64 b^4)
 * (Keeton & Petters 2005) to 1e-7 rad. (The ODE's force falls as 1/r^4: what lies beyond R bends
 * a ray by about M b^3 / R^4, nothing here.) */
Test(black_holes_optics, reference_matches_weak_field_series)
{
    const double bs[] = {100.0, 300.0, 1000.0};
    for (int i = 0; i < 3; i++) {
        double b = bs[i], R = 1e6;
        double got = -reference_deflection(1.0, b, -sqrt(R * R - b * b), R, 0.01);
        double expected = 4.0 / b + 15.0 * PI / (4.0 * b * b) + 128.0 / (3.0 * b * b * b) +
                          3465.0 * PI / (64.0 * b * b * b * b);
        cr_expect(fabs(got - expected) < 1e-7, "b = %g: reference %.9f, series %.9f", b, got, expected);
    }
}

/* Weak field to strong field: the device's deflection within 1e-4 rad of the reference, over the
 * same path (in at R, out at R). */
Test(black_holes_optics, deflection_matches_reference)
{
    cl_float4 dir[N_IMPACT], info[N_IMPACT];
    device_trace(1.0, INFLUENCE, impact, N_IMPACT, dir, info);
    for (int i = 0; i < N_IMPACT; i++) {
        double b = impact[i];
        double x0 = -sqrt(INFLUENCE * INFLUENCE - b * b) * (1.0 - 1e-6);
        double ref = reference_deflection(1.0, b, (double)(float)x0, INFLUENCE, 0.01);
        double got = atan2(dir[i].s[1], dir[i].s[0]);
        /* Strong-field rays turn by more than pi: compare angles modulo 2 pi. */
        double diff = remainder(got - ref, 2.0 * PI);
        cr_log_info("b = %6.1f M: deflection %.6f rad (reference %.6f), error %.2e, %g steps", b,
                    -got, -ref, diff, info[i].s[1]);
        cr_expect(info[i].s[2] == 0.0f, "b = %g M was captured", b);
        cr_expect(fabs(diff) < 1e-4, "b = %g M: deflection error %.3e rad (got %.7f, reference %.7f)",
                  b, diff, -got, -ref);
    }
}

/* h = |x x v| is a constant of the motion: along every traced ray it stays within 1e-4 of its start
 * (captured rays included, up to capture). */
Test(black_holes_optics, h_is_conserved)
{
    const float more[] = {3.0f, 5.0f, 5.15f, 5.2f};
    float b[N_IMPACT + 4];
    memcpy(b, impact, sizeof impact);
    memcpy(b + N_IMPACT, more, sizeof more);
    cl_float4 dir[N_IMPACT + 4], info[N_IMPACT + 4];
    device_trace(1.0, INFLUENCE, b, N_IMPACT + 4, dir, info);
    for (int i = 0; i < N_IMPACT + 4; i++)
        cr_expect(info[i].s[0] < 1e-4f, "b = %g M: h drifted by %.3e relative", b[i], info[i].s[0]);
}

/* Capture exactly below b_c = 3 sqrt(3) M = 5.196 M: rays at 0.5% either side, at two masses. */
Test(black_holes_optics, capture_at_critical_impact_parameter)
{
    const double masses[] = {1.0, 0.25};
    for (int m = 0; m < 2; m++) {
        double M = masses[m], bc = 3.0 * sqrt(3.0) * M;
        float b[] = {(float)(0.5 * bc), (float)(0.995 * bc), (float)(1.005 * bc), (float)(1.5 * bc)};
        cl_float4 dir[4], info[4];
        device_trace(M, 2000.0 * M, b, 4, dir, info);
        for (int i = 0; i < 4; i++) {
            bool expect = b[i] < bc;
            cr_expect_eq(info[i].s[2] != 0.0f, expect, "M = %g, b = %g (b_c = %g): captured %g", M,
                         b[i], bc, info[i].s[2]);
        }
    }
}
