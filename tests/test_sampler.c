// SPDX-License-Identifier: MIT
/* The Sobol sampler (cl/core/sobol.cl, rng.cl's RNG_SOBOL keys): the stratification it promises,
 * the faster convergence it is for, and that it converges to the independent sampler's image. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define NET_POINTS 4096u /* 2^12 */

static void sobol_points(Device *dev, cl_kernel kernel, cl_mem out, cl_uint pixel, cl_uint seed,
                         cl_uint tuple, cl_uint first, cl_uint use_pair, cl_uint *points)
{
    cl_uint count = NET_POINTS;
    KERNEL_ARGS(kernel, 0, KARG(pixel), KARG(seed), KARG(tuple), KARG(first), KARG(count),
                KARG(use_pair), KARG(out));
    device_run(dev, kernel, NET_POINTS, 0, NULL);
    device_read(dev, out, 0, NET_POINTS * 2 * sizeof(cl_uint), points);
}

/* The top `bits` bits of x (0 for bits = 0, where x >> 32 would be undefined). */
static uint32_t top_bits(uint32_t x, unsigned bits) { return bits ? x >> (32u - bits) : 0u; }

/* Whether points[0 .. 2^k - 1] form a (0, k, 2)-net in base 2: for every split a + b = k, each
 * of the 2^a x 2^b elementary intervals holds exactly one point. */
static bool is_net(const cl_uint *points, unsigned k, unsigned *bad_a)
{
    static unsigned char seen[1u << 12];
    for (unsigned a = 0; a <= k; a++) {
        memset(seen, 0, (size_t)1 << k);
        for (uint32_t i = 0; i < (1u << k); i++) {
            uint32_t cell = top_bits(points[2 * i], a) << (k - a) | top_bits(points[2 * i + 1], k - a);
            if (seen[cell]++) {
                *bad_a = a;
                return false;
            }
        }
    }
    return true;
}

/* Every aligned block of 2^k samples of a pixel (the first 2^k among them: any prefix is a union
 * of such blocks, one per binary digit of its length) is a (0, k, 2)-net, for every tuple, pixel
 * and seed: what keeps adaptive sampling's and resumed renders' partial counts stratified. */
Test(sampler, sobol_aligned_blocks_are_nets, .timeout = 600)
{
    static const cl_uint pixels[] = {0u, 1u, 4099u, 262143u};
    static const cl_uint seeds[] = {0u, 7u};
    static const cl_uint tuples[] = {0u, 1u, 4u, 5u, 6u, 13u, 500u};
    Device *dev = test_device();
    Error err = {0};
    cl_mem out = device_buffer(dev, "points", CL_MEM_WRITE_ONLY, NET_POINTS * 2 * sizeof(cl_uint), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "rng_test_sobol_tuple");
    static cl_uint points[2 * NET_POINTS], other[2 * NET_POINTS];
    for (size_t p = 0; p < sizeof pixels / sizeof *pixels; p++)
        for (size_t s = 0; s < sizeof seeds / sizeof *seeds; s++)
            for (size_t t = 0; t < sizeof tuples / sizeof *tuples; t++)
                for (cl_uint first = 0; first <= 2 * NET_POINTS; first += 2 * NET_POINTS) {
                    sobol_points(dev, kernel, out, pixels[p], seeds[s], tuples[t], first, 1u, points);
                    for (cl_uint call = 0; call <= 2; call += 2) {
                        sobol_points(dev, kernel, out, pixels[p], seeds[s], tuples[t], first, call, other);
                        cr_assert(!memcmp(points, other, sizeof points), "pixel %u tuple %u: rng_bits2 and %s disagree",
                                  pixels[p], tuples[t], call ? "rng_bits4" : "rng_bits");
                    }
                    for (unsigned k = 0; k <= 12; k++)
                        for (uint32_t block = 0; block < NET_POINTS >> k; block++) {
                            unsigned a = 0;
                            cr_assert(is_net(points + 2 * (block << k), k, &a),
                                      "pixel %u seed %u tuple %u: samples %u .. %u are no (0, %u, 2)-net "
                                      "(two points in one 2^-%u x 2^-%u interval)",
                                      pixels[p], seeds[s], tuples[t], first + (block << k),
                                      first + ((block + 1) << k) - 1, k, a, k - a);
                        }
                }
    clReleaseKernel(kernel);
    clReleaseMemObject(out);
    test_device_release(dev);
}

/* ---- Convergence on an analytic integral --------------------------------------------------- */

#define SIDE 32
#define EYE_HEIGHT 0.9 /* below the lamp */
#define TAN_HALF 0.2679491924311227 /* tan(15 degrees): fov_y 30 */
#define ALBEDO 0.5
#define LAMP_HALF 0.5 /* a 1 x 1 lamp ... */
#define LAMP_HEIGHT 1.0 /* ... this high above the floor, facing down, radiance 1 */

/* Seen from straight above: a grey floor lit by a square lamp facing it (out of view), direct
 * light only (max depth 2). Every pixel sees the floor. */
static const char *write_lit_floor(void)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "floor.mtl", "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0 0 0\nKe 1 1 1\n");
    test_write_file(dir, "floor.obj",
                    "mtllib floor.mtl\n"
                    "v -2 0 2\nv 2 0 2\nv 2 0 -2\nv -2 0 -2\n"
                    "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
                    "usemtl floor\nf 1 2 3 4\nusemtl lamp\nf 5 6 7 8\n");
    char json[512];
    snprintf(json, sizeof json,
             "{\"camera\": {\"eye\": [0, %g, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], \"fov_y\": 30},\n"
             " \"film\": {\"width\": %d, \"height\": %d}, \"render\": {\"max_depth\": 2},\n"
             " \"objects\": [{\"obj\": \"floor.obj\"}], \"background\": [0, 0, 0]}\n",
             EYE_HEIGHT, SIDE, SIDE);
    return test_write_file(dir, "floor.json", json);
}

/* Irradiance at floor point (x, 0, z) from the lamp (radiance 1): Lambert's polygon formula,
 * E = 1/2 sum over edges of the angle they subtend times the normal's share of their plane's. */
static double lamp_irradiance(double x, double z)
{
    static const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    double sum = 0.0;
    for (int i = 0; i < 4; i++) {
        const double *a = corners[i], *b = corners[(i + 1) % 4];
        double va[3] = {LAMP_HALF * a[0] - x, LAMP_HEIGHT, LAMP_HALF * a[1] - z};
        double vb[3] = {LAMP_HALF * b[0] - x, LAMP_HEIGHT, LAMP_HALF * b[1] - z};
        double la = sqrt(va[0] * va[0] + va[1] * va[1] + va[2] * va[2]);
        double lb = sqrt(vb[0] * vb[0] + vb[1] * vb[1] + vb[2] * vb[2]);
        double c[3] = {va[1] * vb[2] - va[2] * vb[1], va[2] * vb[0] - va[0] * vb[2],
                       va[0] * vb[1] - va[1] * vb[0]};
        double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double angle = acos(fmin(1.0, fmax(-1.0, (va[0] * vb[0] + va[1] * vb[1] + va[2] * vb[2]) / (la * lb))));
        sum += angle * c[1] / lc; /* the floor's normal is +y */
    }
    return 0.5 * fabs(sum);
}

/* Each pixel's exact value: radiance albedo / pi E averaged over its footprint on the floor (the
 * box filter), by a 16 x 16 midpoint rule (its error is far below the errors measured). */
static void exact_floor(double *exact)
{
    double half_width = EYE_HEIGHT * TAN_HALF, pixel = 2.0 * half_width / SIDE;
    for (int y = 0; y < SIDE; y++)
        for (int x = 0; x < SIDE; x++) {
            double sum = 0.0;
            for (int j = 0; j < 16; j++)
                for (int i = 0; i < 16; i++)
                    sum += lamp_irradiance(-half_width + (x + (i + 0.5) / 16.0) * pixel,
                                           -half_width + (y + (j + 0.5) / 16.0) * pixel);
            exact[y * SIDE + x] = ALBEDO / 3.14159265358979323846 * sum / 256.0;
        }
}

/* Root-mean-square relative error of the film against the exact values, over SEEDS renders. */
#define SEEDS 4
static double rms_error(RenderFixture *f, const double *exact, int sampler, int spp)
{
    double sum = 0.0;
    for (unsigned s = 0; s < SEEDS; s++) {
        float *rgb = render_fixture_render(f, (RenderSettings){.spp = spp, .max_depth = 2, .seed = 11u + 7u * s,
                                                               .sampler = sampler}, NULL);
        for (int i = 0; i < SIDE * SIDE; i++) {
            double e = (rgb[3 * i + 1] - exact[i]) / exact[i];
            sum += e * e;
        }
        free(rgb);
    }
    return sqrt(sum / (SEEDS * SIDE * SIDE));
}

/* From 16 to 256 spp the independent sampler's error falls as 1/sqrt(N) (4x); Sobol's faster
 * (the lamp's and the BSDF's 2D tuples are each stratified; what is left at the rate of random
 * numbers is their interaction with the pixel's jitter, a padded sampler's limit). With 4 x 1024
 * pixels the measured ratios are within a few percent of their expectation. */
Test(sampler, sobol_error_falls_faster_than_independent, .timeout = 600)
{
    static double exact[SIDE * SIDE];
    exact_floor(exact);
    RenderFixture f;
    render_fixture_open(&f, write_lit_floor(), SIDE, SIDE);
    double ind16 = rms_error(&f, exact, SAMPLER_INDEPENDENT, 16);
    double ind256 = rms_error(&f, exact, SAMPLER_INDEPENDENT, 256);
    double sob16 = rms_error(&f, exact, SAMPLER_SOBOL, 16);
    double sob256 = rms_error(&f, exact, SAMPLER_SOBOL, 256);
    cr_log_info("relative RMS error: independent %.3g at 16 spp, %.3g at 256 (ratio %.2f); "
                "sobol %.3g, %.3g (ratio %.2f)", ind16, ind256, ind16 / ind256, sob16, sob256,
                sob16 / sob256);
    fprintf(stderr, "independent %.4g %.4g ratio %.2f; sobol %.4g %.4g ratio %.2f\n", ind16, ind256,
            ind16 / ind256, sob16, sob256, sob16 / sob256);
    cr_expect(ind16 / ind256 > 3.4 && ind16 / ind256 < 4.7,
              "independent: error ratio %.2f from 16 to 256 spp, 4 expected", ind16 / ind256);
    cr_expect(sob16 / sob256 > 6.0, "sobol: error ratio %.2f from 16 to 256 spp, not above 1/sqrt(N)'s 4",
              sob16 / sob256);
    cr_expect(sob256 < 0.5 * ind256, "sobol's error %.3g at 256 spp, independent's %.3g", sob256, ind256);
    render_fixture_close(&f);
}

/* ---- Sobol and independent numbers converge to the same image ------------------------------ */

#define Z_RENDERS 8
#define Z_SIDE 24
#define Z_BLOCK 4 /* pixels a side */
#define Z_BLOCKS ((Z_SIDE / Z_BLOCK) * (Z_SIDE / Z_BLOCK) * 3)

/* Per block of Z_BLOCK x Z_BLOCK pixels and channel: the mean over Z_RENDERS renders (seeds) of
 * the block's average, and that mean's variance. */
static void block_means(RenderFixture *f, int sampler, int spp, double *mean, double *variance)
{
    static double sum[Z_BLOCKS], sum2[Z_BLOCKS];
    memset(sum, 0, sizeof sum), memset(sum2, 0, sizeof sum2);
    for (unsigned k = 0; k < Z_RENDERS; k++) {
        float *rgb = render_fixture_render(
            f, (RenderSettings){.spp = spp, .max_depth = f->scene.desc.max_depth, .seed = 1000u + 17u * k,
                                .sampler = sampler}, NULL);
        double block[Z_BLOCKS] = {0};
        for (int y = 0; y < Z_SIDE; y++)
            for (int x = 0; x < Z_SIDE; x++)
                for (int c = 0; c < 3; c++)
                    block[((y / Z_BLOCK) * (Z_SIDE / Z_BLOCK) + x / Z_BLOCK) * 3 + c] +=
                        rgb[(y * Z_SIDE + x) * 3 + c] / (double)(Z_BLOCK * Z_BLOCK);
        for (int b = 0; b < Z_BLOCKS; b++)
            sum[b] += block[b], sum2[b] += block[b] * block[b];
        free(rgb);
    }
    for (int b = 0; b < Z_BLOCKS; b++) {
        mean[b] = sum[b] / Z_RENDERS;
        variance[b] = fmax(sum2[b] - Z_RENDERS * mean[b] * mean[b], 0.0) / (Z_RENDERS - 1) / Z_RENDERS;
    }
}

/* z of every block's difference: few beyond 3.5 (a t with 7 degrees of freedom is beyond 3.5 for
 * about 1% of blocks; caustic paths make it heavier-tailed, hence the 8% allowance), and the mean
 * of z^2 near 1 (a bias over a part of the image raises it). */
static void same_image(const char *name, int spp)
{
    char path[256];
    snprintf(path, sizeof path, "tests/scenes/%s/scene.json", name);
    RenderFixture f;
    render_fixture_open(&f, path, Z_SIDE, Z_SIDE);
    static double ms[Z_BLOCKS], vs[Z_BLOCKS], mi[Z_BLOCKS], vi[Z_BLOCKS];
    block_means(&f, SAMPLER_SOBOL, spp, ms, vs);
    block_means(&f, SAMPLER_INDEPENDENT, spp, mi, vi);
    int beyond = 0;
    double z2_sum = 0.0, sobol_var = 0.0, independent_var = 0.0;
    for (int b = 0; b < Z_BLOCKS; b++) {
        double var = vs[b] + vi[b] + pow(1e-4 * fmax(fabs(mi[b]), 1e-2), 2);
        double z2 = (ms[b] - mi[b]) * (ms[b] - mi[b]) / var;
        beyond += z2 > 3.5 * 3.5;
        z2_sum += z2;
        sobol_var += vs[b], independent_var += vi[b];
    }
    cr_log_info("%s: %d of %d blocks beyond |z| 3.5, mean z^2 %.2f; variance sobol / independent %.2f",
                name, beyond, Z_BLOCKS, z2_sum / Z_BLOCKS, sobol_var / independent_var);
    fprintf(stderr, "%s: %d of %d blocks beyond |z| 3.5, mean z^2 %.2f; variance sobol / independent %.2f\n",
            name, beyond, Z_BLOCKS, z2_sum / Z_BLOCKS, sobol_var / independent_var);
    cr_expect(beyond <= Z_BLOCKS * 8 / 100, "%s: %d of %d blocks differ beyond |z| 3.5", name, beyond, Z_BLOCKS);
    cr_expect(z2_sum / Z_BLOCKS < 2.0, "%s: mean z^2 %.2f over %d blocks (1 expected)", name,
              z2_sum / Z_BLOCKS, Z_BLOCKS);
    render_fixture_close(&f);
}

Test(sampler, sobol_and_independent_agree_cornell_glass_mirror, .timeout = 600) { same_image("cornell-sphere", 128); }
Test(sampler, sobol_and_independent_agree_environment_map, .timeout = 600) { same_image("envmap", 128); }

/* render.sampler chooses the sampler when the settings do not (settings 0), and the settings'
 * choice wins over it: the same bits as the named sampler's render. */
Test(sampler, scene_sampler_is_the_default_and_settings_override_it, .timeout = 300)
{
    char dir[512];
    snprintf(dir, sizeof dir, "%s", write_lit_floor());
    *strrchr(dir, '/') = '\0'; /* the folder of floor.json and floor.obj */
    const char *path = test_write_file(dir, "floor-independent.json",
        "{\"camera\": {\"eye\": [0, 0.9, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], \"fov_y\": 30},\n"
        " \"film\": {\"width\": 32, \"height\": 32}, \"render\": {\"max_depth\": 2, \"sampler\": \"independent\"},\n"
        " \"objects\": [{\"obj\": \"floor.obj\"}], \"background\": [0, 0, 0]}\n");
    RenderFixture f;
    render_fixture_open(&f, path, SIDE, SIDE);
    size_t bytes = SIDE * SIDE * 3 * sizeof(float);
    float *scene = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 2, .seed = 3}, NULL);
    float *ind = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 2, .seed = 3,
                                                            .sampler = SAMPLER_INDEPENDENT}, NULL);
    float *sob = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 2, .seed = 3,
                                                            .sampler = SAMPLER_SOBOL}, NULL);
    cr_expect(!memcmp(scene, ind, bytes), "render.sampler \"independent\" was not used");
    cr_expect(memcmp(sob, ind, bytes), "--sampler sobol did not override render.sampler");
    free(scene), free(ind), free(sob);
    render_fixture_close(&f);
}
