// SPDX-License-Identifier: MIT
/* The environment map's sampling on the device (tests/cl/env_test.cl): env_sample's directions
 * follow each texel's weight (how far the 3 x 3 neighbourhood's largest luminance rises above its
 * mean over the sphere, x sin theta: MIS compensation; computed here from the map, not from the
 * host's tables), the pdf integrates to one over the sphere, and the pdf is > 0 wherever the
 * bilinear radiance an escaped ray sees rises above the map's mean. */
#include "environment_maps.h"

/* The largest luminance of the texels bilinear filtering reads inside texel (i, j)'s cell (3 x 3,
 * wrapping in u, clamped in v). */
static double neighbourhood_max(const float *rgb, int w, int h, int i, int j)
{
    double best = 0.0;
    for (int dj = -1; dj <= 1; dj++)
        for (int di = -1; di <= 1; di++) {
            int jj = j + dj < 0 ? 0 : j + dj >= h ? h - 1 : j + dj, ii = (i + di + w) % w;
            const float *t = &rgb[3 * (jj * w + ii)];
            best = fmax(best, 0.2126 * t[0] + 0.7152 * t[1] + 0.0722 * t[2]);
        }
    return best;
}

/* Every texel's neighbourhood maximum (row-major). */
static double *neighbourhood_maxima(const float *rgb, int w, int h)
{
    double *m = malloc((size_t)w * h * sizeof *m);
    cr_assert(m);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++)
            m[j * w + i] = neighbourhood_max(rgb, w, h, i, j);
    return m;
}

/* The mean over the sphere of per-texel values: each x sin theta of its row, over W x the rows'
 * sin theta. */
static double sphere_mean(const double *v, int w, int h)
{
    double sum = 0.0, area = 0.0;
    for (int j = 0; j < h; j++) {
        double s = sin(ENV_PI * (j + 0.5) / h);
        for (int i = 0; i < w; i++)
            sum += v[j * w + i] * s, area += s;
    }
    return sum / area;
}

/* The neighbourhood maxima's mean over the sphere: what MIS compensation takes off. */
static double neighbourhood_mean(const float *rgb, int w, int h)
{
    double *m = neighbourhood_maxima(rgb, w, h), mean = sphere_mean(m, w, h);
    free(m);
    return mean;
}

/* Every texel's sampling weight, computed here from the map and not from the host's tables: the
 * neighbourhood maximum less its mean over the sphere (MIS compensation), clamped at 0, x sin theta
 * of the row; the uncompensated maximum x sin theta where no texel rises above the mean. */
static double *texel_weights(const float *rgb, int w, int h)
{
    double *weight = neighbourhood_maxima(rgb, w, h), mean = sphere_mean(weight, w, h), above = 0.0;
    for (int t = 0; t < w * h; t++)
        above += fmax(weight[t] - mean, 0.0);
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            double m = weight[j * w + i];
            weight[j * w + i] = (above > 0.0 ? fmax(m - mean, 0.0) : m) * sin(ENV_PI * (j + 0.5) / h);
        }
    return weight;
}

/* The width of interval k of a fixed-point CDF of n entries (environment.h: the end is 2^32). */
static double cdf_width(const uint32_t *cdf, size_t n, size_t k)
{
    return (k + 1 < n ? (double)cdf[k + 1] : 4294967296.0) - (double)cdf[k];
}

/* The two CDFs draw each texel with probability weight / total (within the fixed point's 2^-32 per
 * row and per texel), a texel of weight 0 never (its interval is empty); both start at 0 and never
 * decrease; texels[].w is that probability x W x H exactly as the integers imply it, so the pdf the
 * MIS weights use is the density env_sample draws from. A table off by one entry, built from
 * unsorted sums, or whose pdf forgets the row's share, fails. */
static void check_cdf_tables(const float *rgb, int w, int h)
{
    Environment env;
    Error err = {0};
    cr_assert(environment_build(&env, rgb, w, h, 1.0f, 0.0f, "map", &err), "%s", err.message);
    size_t n = (size_t)w * h;
    double *weight = texel_weights(rgb, w, h), total = 0.0;
    for (size_t t = 0; t < n; t++)
        total += weight[t];
    cr_expect_eq(env.cdf[0], 0u, "the rows' CDF starts at 0");
    int wrong_table = 0, wrong_pdf = 0, unsorted = 0;
    for (int j = 0; j < h; j++) {
        const uint32_t *row = env.cdf + h + (size_t)j * w;
        unsorted += row[0] != 0u || (j > 0 && env.cdf[j] < env.cdf[j - 1]);
        double row_p = cdf_width(env.cdf, (size_t)h, (size_t)j) / 4294967296.0;
        for (int i = 0; i < w; i++) {
            unsorted += i > 0 && row[i] < row[i - 1];
            size_t t = (size_t)j * w + i;
            double want = weight[t] / total * (double)n;
            double drawn = row_p * (cdf_width(row, (size_t)w, (size_t)i) / 4294967296.0) * (double)n;
            double pdf = env.texels[t].s[3];
            /* The fixed point rounds each interval's ends by 2^-33 (of the row or of the map). */
            double slack = 4.0 * (double)n / 4294967296.0 * (1.0 + want);
            if (!(fabs(drawn - want) <= 1e-6 * want + slack) || (want == 0.0 && drawn > slack))
                if (wrong_table++ < 3)
                    cr_log_error("texel (%d, %d): the CDFs draw it %.9g x uniform, its weight says %.9g",
                                 i, j, drawn, want);
            if (!(fabs(pdf - drawn) <= 1e-6 * drawn))
                if (wrong_pdf++ < 3)
                    cr_log_error("texel (%d, %d): texels[].w %.9g, the CDFs draw it %.9g x uniform", i, j,
                                 pdf, drawn);
        }
    }
    cr_expect_eq(unsorted, 0, "%dx%d: %d CDF entries out of order or not starting at 0", w, h, unsorted);
    /* Each guide entry is the interval holding its bucket's start, found here by brute force. */
    int wrong_guide = 0;
    for (int r = -1; r < h; r++) {
        size_t len = r < 0 ? (size_t)h : (size_t)w, at = r < 0 ? 0 : (size_t)h + (size_t)r * w;
        const uint32_t *cdf = env.cdf + at, *guide = env.cdf + h + n + at;
        for (size_t b = 0; b < len; b++) {
            uint64_t start = (((uint64_t)b << 32) + len - 1) / len;
            size_t k = len - 1;
            while (cdf[k] > start)
                k--;
            wrong_guide += guide[b] != k;
        }
    }
    cr_expect_eq(wrong_guide, 0, "%dx%d: %d guide entries wrong", w, h, wrong_guide);
    cr_expect_eq(wrong_table, 0, "%dx%d: %d texels drawn off their weight", w, h, wrong_table);
    cr_expect_eq(wrong_pdf, 0, "%dx%d: %d texels whose pdf is not the CDFs'", w, h, wrong_pdf);
    environment_free(&env);
    free(weight);
}

/* Maps from smooth to extreme: every texel's weight near the mean, a sun 10^5 x the sky (one
 * texel holds most of the mass, and the sky falls below the mean: only the sun is drawn), black
 * rows and single texels (many weights of 0), and a constant map (nothing above its mean: each
 * texel by sin theta). Compensating by a mean not over the sphere (each texel alike), or not at
 * all, fails. */
Test(environment_sampling, cdfs_draw_each_texel_by_its_weight)
{
    float *axis = axis_map(64, 32), *contrast = contrast_map(64, 32), *one = one_texel_map(32, 16, 0, 5);
    check_cdf_tables(axis, 64, 32);
    check_cdf_tables(contrast, 64, 32);
    check_cdf_tables(one, 32, 16);
    float *flat = malloc(48 * 24 * 3 * sizeof *flat);
    for (int t = 0; t < 48 * 24 * 3; t++)
        flat[t] = 0.75f;
    check_cdf_tables(flat, 48, 24);
    free(flat);
    int w = 512, h = 256;
    float *sun = malloc((size_t)w * h * 3 * sizeof *sun);
    uint64_t state = 11;
    for (int t = 0; t < w * h; t++)
        for (int c = 0; c < 3; c++)
            sun[3 * t + c] = 0.1f + mesh_rng_float(&state);
    for (int c = 0; c < 3; c++)
        sun[3 * (100 * w + 200) + c] = 1e5f;
    check_cdf_tables(sun, w, h);
    free(axis), free(contrast), free(one), free(sun);
}

/* The contrast map (environment_maps.h) built, turned by rotation degrees. */
static Environment contrast_environment(int w, int h, float rotation)
{
    float *rgb = contrast_map(w, h);
    Environment env;
    Error err = {0};
    cr_assert(environment_build(&env, rgb, w, h, 1.0f, rotation, "contrast", &err), "%s", err.message);
    free(rgb);
    return env;
}

/* The first 2^k Sobol samples of a pixel stay stratified through env_sample (issue 34): the
 * number that land in each row is within 2 of its expectation (the rows are intervals of the
 * net's second coordinate, which holds one point per 2^-k), for several pixels, bounces and k,
 * and the texel counts' squared deviations are far below independent sampling's (whose mean is
 * about the expectation itself). An alias table (pt's sampler before) scatters neighbouring
 * numbers over unrelated texels: its rows deviate by about the square root of their count. */
Test(environment_sampling, sobol_samples_stay_stratified_over_the_map, .timeout = 300)
{
    int w = 32, h = 16;
    Environment env = contrast_environment(w, h, 0.0f);
    Error err = {0};
    Device *dev = test_device();
    cl_kernel k = device_kernel(dev, "env_test_sobol_texels");
    EnvBuffers b;
    cl_uint a0 = env_args(dev, k, &env, &b);
    const cl_uint n_max = 4096;
    cl_mem out = device_buffer(dev, "texel_of", CL_MEM_READ_WRITE, n_max * sizeof(cl_uint), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_uint *texel_of = malloc(n_max * sizeof *texel_of);
    double *row_count = malloc((size_t)h * sizeof *row_count), *count = malloc((size_t)w * h * sizeof *count);
    const cl_uint pixels[] = {0, 77, 4242}, bounces[] = {0, 3};
    for (size_t pi = 0; pi < 3; pi++)
        for (size_t bi = 0; bi < 2; bi++)
            for (cl_uint n = 256; n <= n_max; n *= 4) {
                cl_uint a = a0, seed = 9;
                KERNEL_ARG(k, a++, pixels[pi]);
                KERNEL_ARG(k, a++, bounces[bi]);
                KERNEL_ARG(k, a++, seed);
                KERNEL_ARG(k, a++, n);
                KERNEL_ARG(k, a++, out);
                device_run(dev, k, n, 0, NULL);
                device_read(dev, out, 0, n * sizeof *texel_of, texel_of);
                memset(row_count, 0, (size_t)h * sizeof *row_count);
                memset(count, 0, (size_t)w * h * sizeof *count);
                for (cl_uint s = 0; s < n; s++) {
                    row_count[texel_of[s] / (cl_uint)w] += 1.0;
                    count[texel_of[s]] += 1.0;
                }
                double worst = 0.0, sq = 0.0, expected_sq = 0.0;
                for (int j = 0; j < h; j++) {
                    double e = 0.0;
                    for (int i = 0; i < w; i++) {
                        double p = env.texels[j * w + i].s[3] / ((double)w * h), et = p * n;
                        e += et;
                        sq += (count[j * w + i] - et) * (count[j * w + i] - et);
                        expected_sq += et * (1.0 - p); /* independent sampling's variance */
                    }
                    worst = fmax(worst, fabs(row_count[j] - e));
                }
                cr_log_info("pixel %u bounce %u, %u samples: worst row %.2f, texel deviations %.3f of "
                            "independent's", pixels[pi], bounces[bi], n, worst, sq / expected_sq);
                /* A direction on a row's edge may round into the next row (env_texel_of): one more. */
                cr_expect(worst <= 3.0, "pixel %u bounce %u, %u samples: a row is off by %.1f", pixels[pi],
                          bounces[bi], n, worst);
                cr_expect(sq < 0.35 * expected_sq,
                          "pixel %u bounce %u, %u samples: texel deviations %.0f, independent's %.0f",
                          pixels[pi], bounces[bi], n, sq, expected_sq);
            }
    clReleaseMemObject(out);
    env_buffers_release(&b);
    clReleaseKernel(k);
    test_device_release(dev);
    environment_free(&env);
    free(texel_of), free(row_count), free(count);
}

/* Samples of env_sample counted per texel pass a chi-square test against the texel weights (a
 * black texel whose neighbours are black too is not sampled); each sample's pdf and radiance
 * equal what an escaped ray in its direction sees (env_lookup). */
static void check_samples_follow_the_weights(const float *rgb, int w, int h)
{
    Environment env;
    Error err = {0};
    cr_assert(environment_build(&env, rgb, w, h, 1.0f, 37.0f, "map", &err), "%s", err.message);
    double *expected = texel_weights(rgb, w, h), total = 0.0;
    for (int t = 0; t < w * h; t++)
        total += expected[t];
    Device *dev = test_device();
    cl_kernel k = device_kernel(dev, "env_test_sample");
    EnvBuffers b;
    cl_uint a = env_args(dev, k, &env, &b);
    cl_uint items = 4096, per_item = 1024, seed = 5;
    cl_uint *counts = calloc((size_t)w * h, sizeof *counts), zero = 0;
    cl_mem counts_buf = device_buffer(dev, "counts", CL_MEM_READ_WRITE, (size_t)w * h * sizeof *counts, counts, &err);
    cl_mem mismatch_buf = device_buffer(dev, "mismatches", CL_MEM_READ_WRITE, sizeof zero, &zero, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    KERNEL_ARG(k, a++, per_item);
    KERNEL_ARG(k, a++, seed);
    KERNEL_ARG(k, a++, counts_buf);
    KERNEL_ARG(k, a++, mismatch_buf);
    device_run(dev, k, items, 0, NULL);
    device_read(dev, counts_buf, 0, (size_t)w * h * sizeof *counts, counts);
    cl_uint mismatches;
    device_read(dev, mismatch_buf, 0, sizeof mismatches, &mismatches);
    cr_expect_eq(mismatches, 0, "%u samples whose pdf or radiance differ from env_lookup's", mismatches);

    double n = (double)items * per_item, chi = 0.0, pooled_e = 0.0, pooled_o = 0.0, stray = 0.0;
    int bins = 0;
    for (int t = 0; t < w * h; t++) {
        double e = n * expected[t] / total;
        if (e == 0.0) {
            stray += counts[t];
        } else if (e < 20.0) {
            pooled_e += e, pooled_o += counts[t];
        } else {
            chi += (counts[t] - e) * (counts[t] - e) / e, bins++;
        }
    }
    /* A direction drawn on a cell's edge may round into a neighbour of weight 0: env_lookup gives
     * it that neighbour's pdf, 0, and next-event estimation drops it: a few in 10^6 on PoCL, 9 in
     * 4.2 10^6 on the H200 (NVIDIA's atan2/acos differ by an ulp or two). A bias of that order;
     * an unwidened table puts most of the map's samples here. */
    cr_expect(stray <= 1e-5 * n, "%.0f samples in texels of weight 0", stray);
    if (pooled_e > 0.0)
        chi += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e, bins++;
    /* Wilson-Hilferty quantile at p = 1e-6 (z = 4.75) for bins - 1 degrees of freedom. */
    double dof = bins - 1, q = 1.0 - 2.0 / (9.0 * dof) + 4.75 * sqrt(2.0 / (9.0 * dof));
    double limit = dof * q * q * q;
    cr_log_info("chi-square %.1f over %d bins (limit %.1f)", chi, bins, limit);
    cr_expect(chi < limit, "chi-square %.1f over %d bins, limit %.1f", chi, bins, limit);
    clReleaseMemObject(counts_buf), clReleaseMemObject(mismatch_buf);
    env_buffers_release(&b);
    clReleaseKernel(k);
    test_device_release(dev);
    environment_free(&env);
    free(expected), free(counts);
}

Test(environment_sampling, samples_follow_the_texel_weights, .timeout = 300)
{
    int w = 32, h = 16;
    float *rgb = contrast_map(w, h);
    check_samples_follow_the_weights(rgb, w, h);
    free(rgb);
}

/* One bright texel on the u = 0 seam: only its 3 x 3 neighbourhood (wrapped) is ever sampled. */
Test(environment_sampling, one_bright_texel_samples_its_neighbourhood, .timeout = 300)
{
    int w = 32, h = 16;
    float *rgb = one_texel_map(w, h, 0, 5);
    check_samples_follow_the_weights(rgb, w, h);
    free(rgb);
}

/* env_lookup at n directions: rgb radiance, w pdf. */
static float4 *lookup(const Environment *env, const float4 *dirs, cl_uint n)
{
    Error err = {0};
    Device *dev = test_device();
    cl_kernel k = device_kernel(dev, "env_test_lookup");
    EnvBuffers b;
    cl_uint a = env_args(dev, k, env, &b);
    cl_mem dirs_buf = device_buffer(dev, "dirs", CL_MEM_READ_ONLY, n * sizeof *dirs, (void *)dirs, &err);
    cl_mem out_buf = device_buffer(dev, "out", CL_MEM_WRITE_ONLY, n * sizeof(float4), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    KERNEL_ARG(k, a++, dirs_buf);
    KERNEL_ARG(k, a++, n);
    KERNEL_ARG(k, a++, out_buf);
    device_run(dev, k, n, 0, NULL);
    float4 *out = malloc(n * sizeof *out);
    device_read(dev, out_buf, 0, n * sizeof *out, out);
    clReleaseMemObject(dirs_buf), clReleaseMemObject(out_buf);
    env_buffers_release(&b);
    clReleaseKernel(k);
    test_device_release(dev);
    return out;
}

/* The solid-angle pdf integrates to 1: midpoint rule on a grid 8x finer than the texels. */
Test(environment_sampling, pdf_integrates_to_one, .timeout = 120)
{
    int w = 32, h = 16;
    Environment env = contrast_environment(w, h, 37.0f);
    cl_uint nt = 8 * (cl_uint)h, np = 8 * (cl_uint)w, nd = nt * np;
    float4 *dirs = malloc(nd * sizeof *dirs);
    for (cl_uint j = 0; j < nt; j++)
        for (cl_uint i = 0; i < np; i++) {
            double th = ENV_PI * (j + 0.5) / nt, ph = 2.0 * ENV_PI * (i + 0.5) / np;
            dirs[j * np + i] = (float4){{(float)(sin(th) * cos(ph)), (float)cos(th), (float)(sin(th) * sin(ph)), 0}};
        }
    float4 *out = lookup(&env, dirs, nd);
    double integral = 0.0;
    for (cl_uint j = 0; j < nt; j++)
        for (cl_uint i = 0; i < np; i++)
            integral += out[j * np + i].s[3] * sin(ENV_PI * (j + 0.5) / nt) * (ENV_PI / nt) * (2.0 * ENV_PI / np);
    cr_expect(fabs(integral - 1.0) < 2e-3, "the pdf integrates to %.5f over the sphere", integral);
    environment_free(&env);
    free(dirs), free(out);
}

/* Wherever an escaped ray sees light above the map's mean, next-event estimation can sample it
 * (below it, the BSDF's samples alone cover the light, with MIS weight 1): for random directions
 * and a grid around a single bright texel (bilinear filtering spreads it over the cells around it,
 * across the u seam and at the top row), radiance > 0 implies pdf > 0 on a black map, and radiance
 * above the mean implies pdf > 0 on a grey ramp in u (texels from well below to well above the
 * mean). A sampler weighting each texel by its own luminance only (not its neighbourhood's) leaves
 * a pdf of 0 in the half-cells around the bright one and fails; so does one taking twice the mean
 * off (the ramp's texels just above the mean). */
Test(environment_sampling, pdf_is_positive_wherever_radiance_is, .timeout = 120)
{
    static const int bright[][2] = {{0, 5}, {13, 0}, {20, 9}};
    int w = 32, h = 16;
    for (size_t m = 0; m < 2 * sizeof bright / sizeof bright[0]; m++) {
        bool ramp = m >= sizeof bright / sizeof bright[0];
        const int *b = bright[m % (sizeof bright / sizeof bright[0])];
        float *rgb = one_texel_map(w, h, b[0], b[1]);
        for (int t = 0; ramp && t < w * h; t++)
            for (int c = 0; c < 3; c++)
                rgb[3 * t + c] += 0.5f + 10.0f * (float)(t % w) / (float)w;
        float threshold = ramp ? (float)neighbourhood_mean(rgb, w, h) : 0.0f;
        Environment env;
        Error err = {0};
        cr_assert(environment_build(&env, rgb, w, h, 1.0f, 0.0f, ramp ? "one texel on a ramp" : "one texel", &err), "%s", err.message);
        enum { RANDOM = 1 << 16, GRID = 64 };
        cl_uint n = RANDOM + GRID * GRID;
        float4 *dirs = malloc(n * sizeof *dirs);
        uint64_t state = 3 + m;
        for (cl_uint i = 0; i < RANDOM; i++) {
            double z = 2.0 * mesh_rng_float(&state) - 1.0, ph = 2.0 * ENV_PI * mesh_rng_float(&state);
            double r = sqrt(fmax(0.0, 1.0 - z * z));
            dirs[i] = (float4){{(float)(r * cos(ph)), (float)z, (float)(r * sin(ph)), 0}};
        }
        /* A grid over the 3 x 3 texels around the bright one, through texel_direction's mapping. */
        for (int gj = 0; gj < GRID; gj++)
            for (int gi = 0; gi < GRID; gi++) {
                double fi = b[0] - 1.5 + 3.0 * (gi + 0.5) / GRID, fj = b[1] - 1.5 + 3.0 * (gj + 0.5) / GRID;
                double phi = 2.0 * ENV_PI * (fi / w - 0.5), theta = ENV_PI * fj / h;
                if (theta < 0.0)
                    theta = -theta, phi += ENV_PI;
                dirs[RANDOM + gj * GRID + gi] = (float4){{(float)(sin(theta) * sin(phi)), (float)cos(theta),
                                                          (float)(-sin(theta) * cos(phi)), 0}};
            }
        float4 *out = lookup(&env, dirs, n);
        cl_uint lit = 0, unsampled = 0;
        for (cl_uint i = 0; i < n; i++) {
            float lum = 0.2126f * out[i].s[0] + 0.7152f * out[i].s[1] + 0.0722f * out[i].s[2];
            if (lum > threshold && fabsf(dirs[i].s[1]) < 0.99999f) { /* the poles have sin theta = 0 */
                lit++;
                if (!(out[i].s[3] > 0.0f) && unsampled++ < 3)
                    cr_log_error("bright texel (%d, %d): direction (%g, %g, %g) sees %g but has pdf %g",
                                 b[0], b[1], dirs[i].s[0], dirs[i].s[1], dirs[i].s[2], lum,
                                 out[i].s[3]);
            }
        }
        cr_expect(lit > GRID * GRID / 4, "bright texel (%d, %d): only %u lit directions", b[0],
                  b[1], lit);
        cr_expect_eq(unsampled, 0, "bright texel (%d, %d): %u of %u lit directions have pdf 0",
                     b[0], b[1], unsampled, lit);
        environment_free(&env);
        free(rgb), free(dirs), free(out);
    }
}
