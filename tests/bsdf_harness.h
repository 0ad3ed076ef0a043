// SPDX-License-Identifier: MIT
/* bsdf_harness.h: what tests/test_bsdf_*.c share: running the kernels of tests/cl/bsdf_test.cl
 * (bsdf_sample and bsdf_eval of one material in the local shading frame) and a chi-square test of
 * the sampled directions against the pdf that eval reports, integrated numerically over a
 * (theta, phi) grid of the whole sphere. Header-only (static functions) so that each test binary
 * builds from its own .c alone. */
#ifndef PT_TESTS_BSDF_HARNESS_H
#define PT_TESTS_BSDF_HARNESS_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define BSDF_PI 3.14159265358979323846
/* BsdfSample.flags, as cl/material/bsdf_common.cl defines them (kernel-only). */
#define SAMPLE_REFLECTION 1u
#define SAMPLE_TRANSMISSION 2u
#define SAMPLE_DELTA 4u

typedef struct {
    Device *dev;
    cl_kernel sample, eval;
} BsdfHarness;

static inline void bsdf_harness_open(BsdfHarness *h)
{
    h->dev = test_device();
    h->sample = device_kernel(h->dev, "bsdf_test_sample");
    h->eval = device_kernel(h->dev, "bsdf_test_eval");
}

static inline void bsdf_harness_close(BsdfHarness *h)
{
    clReleaseKernel(h->sample);
    clReleaseKernel(h->eval);
    test_device_release(h->dev);
}

static inline Material bsdf_material(cl_uint type)
{
    Material m;
    memset(&m, 0, sizeof m);
    m.type = type;
    for (int t = 0; t < MATERIAL_TEX_COUNT; t++)
        m.tex[t] = NO_TEXTURE;
    m.base = (float4){{1, 1, 1, 0}};
    m.specular_color = (float4){{1, 1, 1, 0}};
    m.ior = 1.5f;
    m.specular = 1.0f;
    m.opacity = 1.0f;
    return m;
}

/* A gold-like conductor (eta, k at roughly 650/550/450 nm), or Fresnel 1. */
static inline Material bsdf_conductor(float roughness, float anisotropy, int fresnel_one)
{
    Material m = bsdf_material(MATERIAL_CONDUCTOR);
    m.roughness = roughness;
    m.anisotropy = anisotropy;
    if (fresnel_one)
        m.flags = MATERIAL_FLAG_FRESNEL_ONE;
    m.eta = (float4){{0.17f, 0.42f, 1.37f, 0}};
    m.k = (float4){{3.5f, 2.35f, 1.77f, 0}};
    return m;
}

static inline Material bsdf_dielectric(float ior, float roughness, float anisotropy)
{
    Material m = bsdf_material(MATERIAL_DIELECTRIC);
    m.ior = ior;
    m.roughness = roughness;
    m.anisotropy = anisotropy;
    return m;
}

static inline Material bsdf_principled(float metallic, float roughness, float anisotropy)
{
    Material m = bsdf_material(MATERIAL_PRINCIPLED);
    m.base = (float4){{0.9f, 0.6f, 0.3f, 0}};
    m.metallic = metallic;
    m.roughness = roughness;
    m.anisotropy = anisotropy;
    return m;
}

/* The direction at polar angle theta, azimuth phi (degrees); w = front (1) or not (0). */
static inline cl_float4 bsdf_dir(double theta_deg, double phi_deg, int front)
{
    double t = theta_deg * BSDF_PI / 180.0, p = phi_deg * BSDF_PI / 180.0;
    return (cl_float4){{(float)(sin(t) * cos(p)), (float)(sin(t) * sin(p)), (float)cos(t),
                        front ? 1.0f : 0.0f}};
}

/* n samples from wo: wi_pdf[i] = (wi, pdf), weight_flags[i] = (weight, flags). */
static inline void bsdf_harness_sample(BsdfHarness *h, const Material *m, cl_float4 wo, cl_uint seed,
                                       cl_uint n, cl_float4 *wi_pdf, cl_float4 *weight_flags)
{
    Error err = {0};
    cl_mem mat = device_buffer(h->dev, "material", CL_MEM_READ_ONLY, sizeof *m, m, &err);
    cl_mem a = device_buffer(h->dev, "wi_pdf", CL_MEM_WRITE_ONLY, n * sizeof(cl_float4), NULL, &err);
    cl_mem b = device_buffer(h->dev, "weight_flags", CL_MEM_WRITE_ONLY, n * sizeof(cl_float4), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    KERNEL_ARGS(h->sample, 0, KARG(mat), KARG(wo), KARG(seed), KARG(n), KARG(a), KARG(b));
    device_run(h->dev, h->sample, n, 0, NULL);
    device_read(h->dev, a, 0, n * sizeof(cl_float4), wi_pdf);
    device_read(h->dev, b, 0, n * sizeof(cl_float4), weight_flags);
    clReleaseMemObject(mat);
    clReleaseMemObject(a);
    clReleaseMemObject(b);
}

/* out[i] = (f(wo[i], wi[i]) |cos wi|, pdf); wo[i].w != 0: front. */
static inline void bsdf_harness_eval(BsdfHarness *h, const Material *m, const cl_float4 *wo,
                                     const cl_float4 *wi, cl_uint n, cl_float4 *out)
{
    Error err = {0};
    size_t size = n * sizeof(cl_float4);
    cl_mem mat = device_buffer(h->dev, "material", CL_MEM_READ_ONLY, sizeof *m, m, &err);
    cl_mem a = device_buffer(h->dev, "wo", CL_MEM_READ_ONLY, size, (void *)wo, &err);
    cl_mem b = device_buffer(h->dev, "wi", CL_MEM_READ_ONLY, size, (void *)wi, &err);
    cl_mem c = device_buffer(h->dev, "out", CL_MEM_WRITE_ONLY, size, NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    KERNEL_ARGS(h->eval, 0, KARG(mat), KARG(a), KARG(b), KARG(n), KARG(c));
    device_run(h->dev, h->eval, n, 0, NULL);
    device_read(h->dev, c, 0, size, out);
    clReleaseMemObject(mat);
    clReleaseMemObject(a);
    clReleaseMemObject(b);
    clReleaseMemObject(c);
}

/* Chi-square over a grid of THETA x PHI cells covering the sphere, plus one cell for the samples
 * the sampler loses (flags 0), whose expected share is 1 - the integral of the pdf. The pdf is
 * integrated by the midpoint rule on SUB x SUB points per cell, SUB_FINE x SUB_FINE where it
 * varies by more than a factor 2 within the cell. */
#define BSDF_CHI_THETA 36
#define BSDF_CHI_PHI 72
#define BSDF_CHI_SUB 8
#define BSDF_CHI_SUB_FINE 32 /* for cells where the pdf varies by more than 2x */
#define BSDF_CHI_CELLS (BSDF_CHI_THETA * BSDF_CHI_PHI)

typedef struct {
    double chi_square, p_value;
    int dof;
    double pdf_integral; /* of the pdf over the sphere */
    double kept;         /* fraction of samples not lost */
} ChiSquareResult;

/* Upper tail of the chi-square distribution with k degrees of freedom (Wilson-Hilferty: the cube
 * root of chi2 / k is nearly normal; good to a few percent of the p-value for k >= 10). */
static inline double chi_square_p_value(double chi2, int k)
{
    if (k < 1)
        return 1.0;
    double v = 2.0 / (9.0 * k);
    double z = (cbrt(chi2 / k) - (1.0 - v)) / sqrt(v);
    return 0.5 * erfc(z / sqrt(2.0));
}

static inline int bsdf_cell_of(cl_float4 w)
{
    double z = fmax(-1.0, fmin(1.0, w.s[2]));
    double theta = acos(z), phi = atan2(w.s[1], w.s[0]);
    if (phi < 0.0)
        phi += 2.0 * BSDF_PI;
    int t = (int)(theta / BSDF_PI * BSDF_CHI_THETA), p = (int)(phi / (2.0 * BSDF_PI) * BSDF_CHI_PHI);
    t = t < 0 ? 0 : t >= BSDF_CHI_THETA ? BSDF_CHI_THETA - 1 : t;
    p = p < 0 ? 0 : p >= BSDF_CHI_PHI ? BSDF_CHI_PHI - 1 : p;
    return t * BSDF_CHI_PHI + p;
}

/* The pdf integrated over each of cells[0 .. count) (midpoint rule on sub x sub points), and its
 * least and greatest value there. */
static inline void bsdf_integrate_cells(BsdfHarness *h, const Material *m, cl_float4 wo,
                                        const int *cells, int count, int sub, double *integral,
                                        double *low, double *high)
{
    const cl_uint per_cell = (cl_uint)(sub * sub), points = (cl_uint)count * per_cell;
    cl_float4 *wos = malloc(points * sizeof *wos), *wis = malloc(points * sizeof *wis);
    cl_float4 *out = malloc(points * sizeof *out);
    double *weight = malloc(points * sizeof *weight);
    double dt = BSDF_PI / BSDF_CHI_THETA / sub, dp = 2.0 * BSDF_PI / BSDF_CHI_PHI / sub;
    for (cl_uint k = 0, i = 0; k < (cl_uint)count; k++)
        for (cl_uint s = 0; s < per_cell; s++, i++) {
            cl_uint c = (cl_uint)cells[k];
            double theta = ((c / BSDF_CHI_PHI) * sub + s / sub + 0.5) * dt;
            double phi = ((c % BSDF_CHI_PHI) * sub + s % sub + 0.5) * dp;
            wos[i] = wo;
            wis[i] = (cl_float4){{(float)(sin(theta) * cos(phi)), (float)(sin(theta) * sin(phi)),
                                  (float)cos(theta), 0.0f}};
            weight[i] = sin(theta) * dt * dp;
        }
    bsdf_harness_eval(h, m, wos, wis, points, out);
    for (cl_uint k = 0, i = 0; k < (cl_uint)count; k++) {
        integral[k] = 0.0;
        low[k] = INFINITY;
        high[k] = 0.0;
        for (cl_uint s = 0; s < per_cell; s++, i++) {
            integral[k] += out[i].s[3] * weight[i];
            low[k] = fmin(low[k], out[i].s[3]);
            high[k] = fmax(high[k], out[i].s[3]);
        }
    }
    free(wos);
    free(wis);
    free(out);
    free(weight);
}

static inline ChiSquareResult bsdf_chi_square(BsdfHarness *h, const Material *m, cl_float4 wo,
                                              cl_uint n, cl_uint seed)
{
    /* Expected: the pdf integrated per cell; cells where it varies a lot (a lobe's peak, the edge
     * of its support) again on a finer grid. */
    double expected[BSDF_CHI_CELLS + 1] = {0}, observed[BSDF_CHI_CELLS + 1] = {0}, integral = 0.0;
    double low[BSDF_CHI_CELLS], high[BSDF_CHI_CELLS];
    int all[BSDF_CHI_CELLS], refine[BSDF_CHI_CELLS], refined = 0;
    for (int c = 0; c < BSDF_CHI_CELLS; c++)
        all[c] = c;
    bsdf_integrate_cells(h, m, wo, all, BSDF_CHI_CELLS, BSDF_CHI_SUB, expected, low, high);
    for (int c = 0; c < BSDF_CHI_CELLS; c++)
        if (high[c] > 2.0 * low[c])
            refine[refined++] = c;
    if (refined > 0) {
        double *fine = malloc(refined * sizeof *fine), *l = malloc(refined * sizeof *l);
        double *hi = malloc(refined * sizeof *hi);
        bsdf_integrate_cells(h, m, wo, refine, refined, BSDF_CHI_SUB_FINE, fine, l, hi);
        for (int i = 0; i < refined; i++)
            expected[refine[i]] = fine[i];
        free(fine);
        free(l);
        free(hi);
    }
    for (int c = 0; c < BSDF_CHI_CELLS; c++)
        integral += expected[c];

    cl_float4 *wi_pdf = malloc(n * sizeof *wi_pdf), *weight_flags = malloc(n * sizeof *weight_flags);
    bsdf_harness_sample(h, m, wo, seed, n, wi_pdf, weight_flags);
    double lost = 0.0;
    for (cl_uint i = 0; i < n; i++) {
        if (weight_flags[i].s[3] == 0.0f)
            lost += 1.0;
        else
            observed[bsdf_cell_of(wi_pdf[i])] += 1.0;
    }
    free(wi_pdf);
    free(weight_flags);
    for (int c = 0; c < BSDF_CHI_CELLS; c++)
        expected[c] *= n;
    expected[BSDF_CHI_CELLS] = fmax(0.0, 1.0 - integral) * n;
    observed[BSDF_CHI_CELLS] = lost;

    /* Cells expecting fewer than 5 samples are pooled (as Mitsuba's chi2 test does). */
    ChiSquareResult r = {0};
    double pool_e = 0.0, pool_o = 0.0;
    int cells = 0;
    for (int c = 0; c <= BSDF_CHI_CELLS; c++) {
        if (expected[c] < 5.0) {
            if (getenv("BSDF_CHI_DEBUG") && observed[c] > 10.0)
                cr_log_info("low cell theta %d phi %d: observed %.0f expected %.1f", c / BSDF_CHI_PHI,
                            c % BSDF_CHI_PHI, observed[c], expected[c]);
            pool_e += expected[c];
            pool_o += observed[c];
            continue;
        }
        double d = observed[c] - expected[c];
        r.chi_square += d * d / expected[c];
        if (getenv("BSDF_CHI_DEBUG") && d * d / expected[c] > 20.0)
            cr_log_info("cell theta %d phi %d: observed %.0f expected %.1f", c / BSDF_CHI_PHI,
                        c % BSDF_CHI_PHI, observed[c], expected[c]);
        cells++;
    }
    if (pool_e > 0.0) {
        double d = pool_o - pool_e;
        r.chi_square += d * d / fmax(pool_e, 5.0);
        if (getenv("BSDF_CHI_DEBUG"))
            cr_log_info("pooled cells: observed %.0f expected %.1f", pool_o, pool_e);
        cells++;
    }
    r.dof = cells - 1;
    r.p_value = chi_square_p_value(r.chi_square, r.dof);
    r.pdf_integral = integral;
    r.kept = 1.0 - lost / n;
    return r;
}

#endif
