// SPDX-License-Identifier: MIT
/* The Henyey-Greenstein phase function of media (cl/medium/phase.cl), run on the device: it
 * integrates to 1 over the sphere, matches the closed form (1 - g^2) / (4 pi (1 + g^2 - 2 g
 * cos)^1.5) with g > 0 forward, and phase_hg_sample's directions follow it: a chi-square test over
 * cos-theta bins (about the arriving direction, not an axis) against the exact bin probabilities,
 * a chi-square test of the azimuth around that direction, and the pdf it reports equals the phase
 * function at the direction it returns. A wrong sign of g, a cdf inverted for another density or a
 * frame that is not orthonormal fails these by far. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>

#include "bsdf_harness.h" /* chi_square_p_value */
#include "support.h"

#define COUNT (1u << 18)
#define BINS 64
#define PI 3.14159265358979323846

/* The cdf of cos theta under HG: P(cos <= x) in closed form (integral of 2 pi p over [-1, x]). */
static double hg_cdf(double g, double x)
{
    if (fabs(g) < 1e-6)
        return 0.5 * (x + 1.0);
    double a = 1.0 + g * g;
    /* d/dx (1 - g^2) / (2 g sqrt(a - 2 g x)) = (1 - g^2) / (2 (a - 2 g x)^1.5) = 2 pi p(x). */
    return (1.0 - g * g) / (2.0 * g) * (1.0 / sqrt(a - 2.0 * g * x) - 1.0 / (1.0 + g));
}

static double hg_closed_form(double g, double c)
{
    return (1.0 - g * g) / (4.0 * PI * pow(1.0 + g * g - 2.0 * g * c, 1.5));
}

static void run_eval(Device *dev, float g, const float *cos_theta, cl_uint count, float *out)
{
    Error err = {0};
    cl_mem a = device_buffer(dev, "cos", CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                             count * sizeof(float), (void *)cos_theta, &err);
    cl_mem b = device_buffer(dev, "out", CL_MEM_WRITE_ONLY, count * sizeof(float), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel k = device_kernel(dev, "phase_test_eval");
    cl_uint arg = 0;
    KERNEL_ARG(k, arg++, g);
    KERNEL_ARG(k, arg++, a);
    KERNEL_ARG(k, arg++, count);
    KERNEL_ARG(k, arg++, b);
    device_run(dev, k, count, 0, NULL);
    device_read(dev, b, 0, count * sizeof(float), out);
    clReleaseKernel(k);
    clReleaseMemObject(a);
    clReleaseMemObject(b);
}

static void run_sample(Device *dev, float g, cl_float4 d, const float *u, float *out)
{
    Error err = {0};
    cl_mem a = device_buffer(dev, "u", CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                             2 * COUNT * sizeof(float), (void *)u, &err);
    cl_mem b = device_buffer(dev, "out", CL_MEM_WRITE_ONLY, 4 * COUNT * sizeof(float), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel k = device_kernel(dev, "phase_test_sample");
    cl_uint count = COUNT, arg = 0;
    KERNEL_ARG(k, arg++, g);
    KERNEL_ARG(k, arg++, d);
    KERNEL_ARG(k, arg++, a);
    KERNEL_ARG(k, arg++, count);
    KERNEL_ARG(k, arg++, b);
    device_run(dev, k, COUNT, 0, NULL);
    device_read(dev, b, 0, 4 * COUNT * sizeof(float), out);
    clReleaseKernel(k);
    clReleaseMemObject(a);
    clReleaseMemObject(b);
}

static const float G_VALUES[] = {-0.9f, -0.5f, 0.0f, 0.3f, 0.7f, 0.95f};
#define G_COUNT (sizeof G_VALUES / sizeof G_VALUES[0])

Test(medium_phase, integrates_to_one_and_matches_the_closed_form)
{
    Device *dev = test_device();
    enum { N = 1 << 16 };
    float *c = malloc(N * sizeof *c), *p = malloc(N * sizeof *p);
    cr_assert(c && p);
    for (int i = 0; i < N; i++)
        c[i] = (float)(-1.0 + 2.0 * (i + 0.5) / N); /* midpoints */
    for (size_t gi = 0; gi < G_COUNT; gi++) {
        double g = G_VALUES[gi];
        run_eval(dev, G_VALUES[gi], c, N, p);
        double integral = 0.0, worst = 0.0;
        for (int i = 0; i < N; i++) {
            integral += 2.0 * PI * p[i] * (2.0 / N);
            worst = fmax(worst, fabs(p[i] / hg_closed_form(g, c[i]) - 1.0));
        }
        cr_expect(fabs(integral - 1.0) < 2e-3, "g %g: the phase integrates to %.6f", g, integral);
        cr_expect(worst < 1e-4, "g %g: off the closed form by %.3g (relative)", g, worst);
    }
    /* Forward scattering: g > 0 puts more density ahead (cos 1) than behind. */
    float ends[2] = {1.0f, -1.0f}, at[2];
    run_eval(dev, 0.5f, ends, 2, at);
    cr_expect(at[0] > 10.0f * at[1], "g 0.5: p(forward) %g, p(back) %g", at[0], at[1]);
    free(c);
    free(p);
    test_device_release(dev);
}

Test(medium_phase, samples_follow_the_phase_function)
{
    Device *dev = test_device();
    float *u = malloc(2 * COUNT * sizeof *u), *out = malloc(4 * COUNT * sizeof *out);
    cr_assert(u && out);
    srand(11);
    for (uint32_t i = 0; i < 2 * COUNT; i++)
        u[i] = (float)((double)rand() / ((double)RAND_MAX + 1.0));
    /* An arriving direction along no axis. */
    double dn = sqrt(0.3 * 0.3 + 0.5 * 0.5 + 0.81 * 0.81);
    cl_float4 d = {{(float)(0.3 / dn), (float)(-0.5 / dn), (float)(0.81 / dn), 0.0f}};
    for (size_t gi = 0; gi < G_COUNT; gi++) {
        double g = G_VALUES[gi];
        run_sample(dev, G_VALUES[gi], d, u, out);
        /* cos theta about d, and the azimuth in a frame of our own around d. */
        double t[3], b[3], dd[3] = {d.s[0], d.s[1], d.s[2]};
        double ref[3] = {0, 1, 0};
        t[0] = ref[1] * dd[2] - ref[2] * dd[1], t[1] = ref[2] * dd[0] - ref[0] * dd[2];
        t[2] = ref[0] * dd[1] - ref[1] * dd[0];
        double tn = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        for (int k = 0; k < 3; k++)
            t[k] /= tn;
        b[0] = dd[1] * t[2] - dd[2] * t[1], b[1] = dd[2] * t[0] - dd[0] * t[2];
        b[2] = dd[0] * t[1] - dd[1] * t[0];
        double counts[BINS] = {0}, phi_counts[BINS] = {0}, worst_pdf = 0.0, worst_len = 0.0;
        for (uint32_t i = 0; i < COUNT; i++) {
            const float *w = &out[4 * i];
            double len = sqrt((double)w[0] * w[0] + (double)w[1] * w[1] + (double)w[2] * w[2]);
            worst_len = fmax(worst_len, fabs(len - 1.0));
            double c = (w[0] * dd[0] + w[1] * dd[1] + w[2] * dd[2]) / len;
            int bin = (int)((c + 1.0) * 0.5 * BINS);
            counts[bin < 0 ? 0 : bin >= BINS ? BINS - 1 : bin]++;
            double phi = atan2(w[0] * b[0] + w[1] * b[1] + w[2] * b[2],
                               w[0] * t[0] + w[1] * t[1] + w[2] * t[2]) + PI;
            int pb = (int)(phi / (2.0 * PI) * BINS);
            phi_counts[pb < 0 ? 0 : pb >= BINS ? BINS - 1 : pb]++;
            worst_pdf = fmax(worst_pdf, fabs(w[3] / hg_closed_form(g, fmax(-1.0, fmin(1.0, c))) - 1.0));
        }
        double chi = 0.0, chi_phi = 0.0;
        int dof = -1;
        double pooled_expected = 0.0, pooled_count = 0.0;
        for (int k = 0; k < BINS; k++) {
            double lo = -1.0 + 2.0 * k / BINS, hi = -1.0 + 2.0 * (k + 1) / BINS;
            double expected = COUNT * (hg_cdf(g, hi) - hg_cdf(g, lo));
            pooled_expected += expected, pooled_count += counts[k];
            if (pooled_expected >= 5.0) { /* cells expecting fewer than 5 are pooled */
                chi += (pooled_count - pooled_expected) * (pooled_count - pooled_expected) /
                       pooled_expected;
                dof++;
                pooled_expected = pooled_count = 0.0;
            }
            double e_phi = (double)COUNT / BINS;
            chi_phi += (phi_counts[k] - e_phi) * (phi_counts[k] - e_phi) / e_phi;
        }
        double p_cos = chi_square_p_value(chi, dof), p_phi = chi_square_p_value(chi_phi, BINS - 1);
        cr_log_info("g %5.2f: cos chi2 %.1f (%d dof, p %.3g), azimuth chi2 %.1f (p %.3g)", g, chi,
                    dof, p_cos, chi_phi, p_phi);
        cr_expect(p_cos > 1e-4, "g %g: cos theta chi-square %.1f over %d dof, p %.3g", g, chi, dof,
                  p_cos);
        cr_expect(p_phi > 1e-4, "g %g: azimuth chi-square %.1f, p %.3g", g, chi_phi, p_phi);
        cr_expect(worst_pdf < 1e-3, "g %g: reported pdf off the phase by %.3g", g, worst_pdf);
        cr_expect(worst_len < 1e-5, "g %g: |wi| off 1 by %.3g", g, worst_len);
    }
    free(u);
    free(out);
    test_device_release(dev);
}
