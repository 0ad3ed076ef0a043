// SPDX-License-Identifier: MIT
/* The BSDF lobes (cl/material/) sample the directions their pdf says: chi-square goodness of fit
 * of 2^20 bsdf_sample directions against bsdf_eval's pdf integrated over a (theta, phi) grid of
 * the sphere, with the sampler's lost samples (below the horizon, on the wrong side) as one more
 * cell expecting 1 - the pdf's integral. Rough conductors (with anisotropy, near-normal and grazing
 * views), rough glass from outside and inside, principled at metallic 0, 0.5, 1. A pdf without
 * the G1(wo) of the visible-normal density, or alpha_x and alpha_y swapped in the sampler, fails. */
#include "bsdf_harness.h"

#define SAMPLES (1u << 20)
/* Fixed seed: the outcome is deterministic; the threshold says how unlikely a failure of a correct
 * sampler would be. */
#define P_VALUE_LIMIT 1e-3

typedef struct {
    const char *name;
    Material m;
    cl_float4 wo;
} SamplingCase;

static void check_cases(const SamplingCase *cases, int count)
{
    BsdfHarness h;
    bsdf_harness_open(&h);
    for (int i = 0; i < count; i++) {
        ChiSquareResult r = bsdf_chi_square(&h, &cases[i].m, cases[i].wo, SAMPLES, 17u + (cl_uint)i);
        cr_log_info("%-40s chi2 %9.1f dof %4d p %.3g  pdf integral %.4f kept %.4f", cases[i].name,
                    r.chi_square, r.dof, r.p_value, r.pdf_integral, r.kept);
        cr_expect(r.p_value > P_VALUE_LIMIT, "%s: chi-square %.1f over %d dof, p = %.3g",
                  cases[i].name, r.chi_square, r.dof, r.p_value);
        /* The pdf never integrates above 1, and the mass it misses is what the sampler loses. */
        cr_expect(r.pdf_integral < 1.003, "%s: pdf integrates to %.4f", cases[i].name, r.pdf_integral);
        cr_expect(fabs(r.pdf_integral - r.kept) < 0.004, "%s: pdf integrates to %.4f, sampler keeps %.4f",
                  cases[i].name, r.pdf_integral, r.kept);
    }
    bsdf_harness_close(&h);
}

Test(bsdf_sampling, conductor, .timeout = 120)
{
    SamplingCase cases[] = {
        {"conductor r 0.2 normal", bsdf_conductor(0.2f, 0.0f, 0), bsdf_dir(5, 30, 1)},
        {"conductor r 0.2 grazing", bsdf_conductor(0.2f, 0.0f, 0), bsdf_dir(80, 30, 1)},
        {"conductor r 0.5 normal", bsdf_conductor(0.5f, 0.0f, 0), bsdf_dir(5, 30, 1)},
        {"conductor r 0.5 grazing", bsdf_conductor(0.5f, 0.0f, 0), bsdf_dir(80, 30, 1)},
        {"conductor r 1 normal", bsdf_conductor(1.0f, 0.0f, 0), bsdf_dir(5, 30, 1)},
        {"conductor r 1 grazing", bsdf_conductor(1.0f, 0.0f, 0), bsdf_dir(80, 30, 1)},
        {"conductor r 0.3 aniso 0.8 normal", bsdf_conductor(0.3f, 0.8f, 0), bsdf_dir(5, 30, 1)},
        {"conductor r 0.3 aniso 0.8 oblique", bsdf_conductor(0.3f, 0.8f, 0), bsdf_dir(50, 40, 1)},
        {"conductor r 0.7 aniso 0.8 grazing", bsdf_conductor(0.7f, 0.8f, 0), bsdf_dir(80, 60, 1)},
    };
    check_cases(cases, (int)(sizeof cases / sizeof cases[0]));
}

/* Transmission's support ends where the generalised half vector reaches the horizon, wi.z =
 * -wo.z / eta: the view angles keep that edge off the grid's cell boundaries (at wo 75 degrees it
 * falls 0.07 degrees inside a cell, narrower than the refined integration grid). */
Test(bsdf_sampling, dielectric, .timeout = 120)
{
    SamplingCase cases[] = {
        {"glass 1.5 r 0.3 outside 30", bsdf_dielectric(1.5f, 0.3f, 0.0f), bsdf_dir(30, 20, 1)},
        {"glass 1.5 r 0.3 inside 30", bsdf_dielectric(1.5f, 0.3f, 0.0f), bsdf_dir(30, 20, 0)},
        {"glass 1.5 r 0.6 outside 70", bsdf_dielectric(1.5f, 0.6f, 0.0f), bsdf_dir(70, 20, 1)},
        {"glass 1.5 r 0.6 inside 75 (TIR)", bsdf_dielectric(1.5f, 0.6f, 0.0f), bsdf_dir(75, 20, 0)},
        {"water 1.33 r 0.4 outside 5", bsdf_dielectric(1.33f, 0.4f, 0.0f), bsdf_dir(5, 20, 1)},
        {"water 1.33 r 0.4 inside 40", bsdf_dielectric(1.33f, 0.4f, 0.0f), bsdf_dir(40, 20, 0)},
        {"glass 1.5 r 0.5 aniso 0.8 outside", bsdf_dielectric(1.5f, 0.5f, 0.8f), bsdf_dir(45, 50, 1)},
    };
    check_cases(cases, (int)(sizeof cases / sizeof cases[0]));
}

Test(bsdf_sampling, principled, .timeout = 120)
{
    SamplingCase cases[] = {
        {"principled metallic 0 r 0.3", bsdf_principled(0.0f, 0.3f, 0.0f), bsdf_dir(30, 10, 1)},
        {"principled metallic 0 r 0.3 grazing", bsdf_principled(0.0f, 0.3f, 0.0f), bsdf_dir(80, 10, 1)},
        {"principled metallic 0.5 r 0.5", bsdf_principled(0.5f, 0.5f, 0.0f), bsdf_dir(45, 10, 1)},
        {"principled metallic 1 r 0.4", bsdf_principled(1.0f, 0.4f, 0.0f), bsdf_dir(20, 10, 1)},
        {"principled metallic 1 r 0.8 grazing", bsdf_principled(1.0f, 0.8f, 0.0f), bsdf_dir(80, 10, 1)},
        {"principled metallic 0.5 r 0.4 aniso 0.8", bsdf_principled(0.5f, 0.4f, 0.8f), bsdf_dir(40, 70, 1)},
    };
    check_cases(cases, (int)(sizeof cases / sizeof cases[0]));
}

/* Principled with subsurface scattering (DESIGN "Media"): from outside, the entering lobe below
 * the surface beside the specular and diffuse ones; from inside (a walk reaching the surface), the
 * Lambertian exit. */
static Material principled_subsurface(float metallic, float roughness, float subsurface)
{
    Material m = bsdf_principled(metallic, roughness, 0.0f);
    m.subsurface = subsurface;
    return m;
}

Test(bsdf_sampling, principled_subsurface, .timeout = 120)
{
    SamplingCase cases[] = {
        {"principled subsurface 0.6 r 0.3", principled_subsurface(0.0f, 0.3f, 0.6f), bsdf_dir(30, 10, 1)},
        {"principled subsurface 1 r 0.5 grazing", principled_subsurface(0.0f, 0.5f, 1.0f), bsdf_dir(75, 10, 1)},
        {"principled subsurface 0.5 metallic 0.4", principled_subsurface(0.4f, 0.4f, 0.5f), bsdf_dir(40, 10, 1)},
        {"principled subsurface exit", principled_subsurface(0.0f, 0.3f, 0.5f), bsdf_dir(40, 10, 0)},
    };
    check_cases(cases, (int)(sizeof cases / sizeof cases[0]));
}
