// SPDX-License-Identifier: MIT
/* Media rendered (shared/DESIGN.md "Media"; cl/medium/), on scenes generated here, against closed
 * forms:
 *   - transmittance: an emitter seen through a slab of chromatic fog (an `interface` box) at
 *     max_depth 1 is Le exp(-sigma_t d) per channel: the tracking's weights (delta tracking when
 *     grey, spectral tracking when not) average to the transmittance;
 *   - shadow rays: a plane under a point light, seen and lit through an absorbing slab, is
 *     0.8 / pi I cos / r^2 times the two Beer-Lambert factors along the camera's and the light's
 *     paths through it (shadow rays pass the interface and take its medium's transmittance);
 *   - emission: an emitting slab seen at max_depth 1 is sigma_a Le (1 - exp(-sigma_t d)) / sigma_t;
 *   - white furnaces: a box of non-absorbing medium (grey and chromatic, forward-scattering) under
 *     a uniform sky, and a dielectric filled with such a medium, disappear: every pixel is the sky;
 *     principled subsurface with a white base too;
 *   - next-event estimation in media (phase function against light sampling, with MIS) adds up to
 *     what phase sampling alone finds (the same image within noise), on both path kernels.
 * Tolerances come from the images' own noise (standard errors of block means). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "media_fixtures.h"
#include "support.h"

static const double PI = 3.14159265358979323846;

/* A quad at z = z facing +z, half-size h. */
static const char *quad_z(const char *dir, const char *name, double z, double h)
{
    char text[256];
    snprintf(text, sizeof text, "v %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nf 1 2 3 4\n", -h,
             -h, z, h, -h, z, h, h, z, -h, h, z);
    return test_write_file(dir, name, text);
}

typedef struct {
    double mean[3], stderr_[3]; /* over the pixels, of per-pixel means */
} ImageStats;

/* Mean and standard error (from the spread of blocks of pixels) over the region x0..x1, y0..y1. */
static ImageStats region_stats(const float *rgb, int width, int x0, int y0, int x1, int y1)
{
    ImageStats s = {{0}, {0}};
    for (int c = 0; c < 3; c++) {
        double sum = 0.0, sum2 = 0.0;
        int n = 0;
        for (int y = y0; y < y1; y++)
            for (int x = x0; x < x1; x++) {
                double v = rgb[3 * (y * width + x) + c];
                sum += v, sum2 += v * v, n++;
            }
        double mean = sum / n, var = fmax(sum2 / n - mean * mean, 0.0);
        s.mean[c] = mean;
        s.stderr_[c] = sqrt(var / n);
    }
    return s;
}

static float *render_scene(const char *scene, int spp, int max_depth, unsigned seed, bool no_nee,
                           int path_kernel)
{
    RenderFixture f;
    render_fixture_open(&f, scene, 0, 0);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = spp, .max_depth = max_depth,
                                                            .seed = seed, .no_nee = no_nee,
                                                            .path_kernel = path_kernel},
                                       NULL);
    render_fixture_close(&f);
    return rgb;
}

/* Each channel's mean is within 4.5 standard errors (plus rel of the expected value) of expected. */
static void expect_mean(const char *what, ImageStats s, const double expected[3], double rel)
{
    for (int c = 0; c < 3; c++) {
        double tol = 4.5 * s.stderr_[c] + rel * fabs(expected[c]) + 1e-6;
        cr_expect(fabs(s.mean[c] - expected[c]) <= tol,
                  "%s, channel %d: mean %.6f, expected %.6f (tolerance %.2g, stderr %.2g)", what,
                  c, s.mean[c], expected[c], tol, s.stderr_[c]);
    }
}

/* ---- Transmittance ---------------------------------------------------------------------------- */

/* Camera on +z looking at a lamp quad at z = -3 through the box |x|, |y| <= 2, |z| <= 0.5 (an
 * interface filled with `medium_json`); narrow view (2 degrees): every ray crosses 1 unit of it. */
static const char *slab_scene(const char *dir, const char *medium_json, const char *lamp_emission,
                              const char *background)
{
    box_obj(dir, "box.obj", -2, -2, -0.5, 2, 2, 0.5);
    quad_z(dir, "lamp.obj", -3.0, 10.0);
    char text[4096];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, 0, 6], \"target\": [0, 0, 0], \"up\": [0, 1, 0], "
             "\"fov_y\": 2},\n \"film\": {\"width\": 16, \"height\": 16},\n"
             " \"media\": {\"fog\": %s},\n"
             " \"materials\": {\"lamp\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": %s},\n"
             "               \"boundary\": {\"type\": \"interface\"}},\n"
             " \"objects\": [{\"obj\": \"lamp.obj\", \"material\": \"lamp\"},\n"
             "             {\"obj\": \"box.obj\", \"material\": \"boundary\", \"interior\": \"fog\"}],\n"
             " \"background\": %s}\n",
             medium_json, lamp_emission, background);
    return test_write_file(dir, "scene.json", text);
}

static void check_transmittance(const double sa[3], const double ss[3], double g, int path_kernel)
{
    const char *dir = test_temp_dir();
    char medium[512];
    snprintf(medium, sizeof medium,
             "{\"type\": \"homogeneous\", \"sigma_a\": [%g, %g, %g], \"sigma_s\": [%g, %g, %g], "
             "\"g\": %g}",
             sa[0], sa[1], sa[2], ss[0], ss[1], ss[2], g);
    const char *scene = slab_scene(dir, medium, "[1, 1, 1]", "[0, 0, 0]");
    float *rgb = render_scene(scene, 512, 1, 5, false, path_kernel);
    ImageStats s = region_stats(rgb, 16, 0, 0, 16, 16);
    double expected[3];
    for (int c = 0; c < 3; c++)
        expected[c] = exp(-(sa[c] + ss[c]) * 1.0);
    char what[128];
    snprintf(what, sizeof what, "transmittance sigma_t (%g %g %g), kernel %d", sa[0] + ss[0],
             sa[1] + ss[1], sa[2] + ss[2], path_kernel);
    cr_log_info("%s: %.5f %.5f %.5f, expected %.5f %.5f %.5f", what, s.mean[0], s.mean[1],
                s.mean[2], expected[0], expected[1], expected[2]);
    expect_mean(what, s, expected, 0.002);
    free(rgb);
}

Test(media_render, transmittance_grey_and_chromatic, .timeout = 600)
{
    const double grey_a[3] = {0.4, 0.4, 0.4}, grey_s[3] = {0.8, 0.8, 0.8};
    const double chroma_a[3] = {0.2, 0.5, 1.0}, chroma_s[3] = {0.3, 0.1, 1.4};
    check_transmittance(grey_a, grey_s, 0.5, PATH_KERNEL_WAVEFRONT);
    check_transmittance(chroma_a, chroma_s, -0.3, PATH_KERNEL_WAVEFRONT);
    check_transmittance(chroma_a, chroma_s, 0.0, PATH_KERNEL_MEGAKERNEL);
}

/* ---- Emission --------------------------------------------------------------------------------- */

Test(media_render, emitting_slab_matches_closed_form, .timeout = 600)
{
    const char *dir = test_temp_dir();
    const double sa[3] = {0.5, 1.0, 2.0}, ss[3] = {0.0, 0.6, 0.3}, le[3] = {1.0, 2.0, 0.5};
    char medium[512];
    snprintf(medium, sizeof medium,
             "{\"type\": \"homogeneous\", \"sigma_a\": [%g, %g, %g], \"sigma_s\": [%g, %g, %g], "
             "\"emission\": [%g, %g, %g]}",
             sa[0], sa[1], sa[2], ss[0], ss[1], ss[2], le[0], le[1], le[2]);
    /* The lamp is black: only the medium shines. */
    const char *scene = slab_scene(dir, medium, "[0, 0, 0]", "[0, 0, 0]");
    float *rgb = render_scene(scene, 512, 1, 9, false, PATH_KERNEL_WAVEFRONT);
    ImageStats s = region_stats(rgb, 16, 0, 0, 16, 16);
    double expected[3];
    /* Emitted along the camera segment until its first real scattering (max_depth 1 ends the
     * path there): integral of exp(-sigma_t t) sigma_a Le over the unit thickness. */
    for (int c = 0; c < 3; c++) {
        double st = sa[c] + ss[c];
        expected[c] = sa[c] * le[c] * (1.0 - exp(-st)) / st;
    }
    cr_log_info("emitting slab: %.5f %.5f %.5f, expected %.5f %.5f %.5f", s.mean[0], s.mean[1],
                s.mean[2], expected[0], expected[1], expected[2]);
    expect_mean("emitting slab", s, expected, 0.002);
    free(rgb);
}

/* ---- Shadow rays through an interface ---------------------------------------------------------- */

#define SHADOW_RES 24
static const double SLAB_SIGMA[3] = {0.3, 0.7, 1.2};

/* The plane point (x, 0, z) under a point light of intensity I at (0, H_LIGHT, 0), seen from
 * (0, H_CAM, 0), both through the absorbing slab 1 <= y <= 2: 0.8 / pi I cos / r^2 exp(-sigma
 * (r / h)) exp(-sigma (r_c / h_c)). */
#define H_LIGHT 4.0
#define H_CAM 6.0
#define INTENSITY 20.0
static double shadow_expected(double x, double z, int c)
{
    double r2 = x * x + z * z + H_LIGHT * H_LIGHT, r = sqrt(r2);
    double rc = sqrt(x * x + z * z + H_CAM * H_CAM);
    double e = INTENSITY * H_LIGHT / (r2 * r);
    return 0.8 / PI * e * exp(-SLAB_SIGMA[c] * r / H_LIGHT) * exp(-SLAB_SIGMA[c] * rc / H_CAM);
}

Test(media_render, shadow_rays_pass_interfaces_with_transmittance, .timeout = 600)
{
    const char *dir = test_temp_dir();
    box_obj(dir, "slab.obj", -30, 1, -30, 30, 2, 30);
    test_write_file(dir, "plane.obj", "v -20 0 -20\nv 20 0 -20\nv 20 0 20\nv -20 0 20\nf 1 4 3\nf 1 3 2\n");
    double tan_half = 0.25;
    char text[4096];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, %g, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], "
             "\"fov_y\": %.9g},\n \"film\": {\"width\": %d, \"height\": %d},\n"
             " \"media\": {\"tint\": {\"type\": \"homogeneous\", \"sigma_a\": [%g, %g, %g]}},\n"
             " \"materials\": {\"floor\": {\"type\": \"diffuse\", \"albedo\": 0.8},\n"
             "               \"boundary\": {\"type\": \"interface\"}},\n"
             " \"objects\": [{\"obj\": \"plane.obj\", \"material\": \"floor\"},\n"
             "             {\"obj\": \"slab.obj\", \"material\": \"boundary\", \"interior\": \"tint\"}],\n"
             " \"lights\": [{\"type\": \"point\", \"position\": [0, %g, 0], \"intensity\": [%g, %g, %g]}]}\n",
             H_CAM, 2.0 * atan(tan_half) * 180.0 / PI, SHADOW_RES, SHADOW_RES, SLAB_SIGMA[0],
             SLAB_SIGMA[1], SLAB_SIGMA[2], H_LIGHT, INTENSITY, INTENSITY, INTENSITY);
    const char *scene = test_write_file(dir, "scene.json", text);
    float *rgb = render_scene(scene, 64, 2, 3, false, PATH_KERNEL_WAVEFRONT);
    double worst = 0.0;
    for (int j = 0; j < SHADOW_RES; j++)
        for (int i = 0; i < SHADOW_RES; i++)
            for (int c = 0; c < 3; c++) {
                /* The pixel's footprint, 8 x 8 subsamples (the camera's box filter). */
                double sum = 0.0;
                for (int a = 0; a < 8; a++)
                    for (int b = 0; b < 8; b++) {
                        double sx = (2.0 * (i + (a + 0.5) / 8) / SHADOW_RES - 1.0) * tan_half;
                        double sy = (1.0 - 2.0 * (j + (b + 0.5) / 8) / SHADOW_RES) * tan_half;
                        sum += shadow_expected(sx * H_CAM, -sy * H_CAM, c);
                    }
                double expected = sum / 64.0, got = rgb[3 * (j * SHADOW_RES + i) + c];
                worst = fmax(worst, fabs(got / expected - 1.0));
            }
    cr_log_info("shadow rays through the slab: worst relative error %.4f", worst);
    cr_expect(worst < 0.02, "a pixel is %.3f off the closed form (relative)", worst);
    free(rgb);
}

/* ---- White furnaces ---------------------------------------------------------------------------- */

/* A box |x|, |y|, |z| <= 1 of `material` (interior: `medium_json` when not NULL) under a uniform
 * sky of 0.5, seen whole: the image is the sky everywhere when nothing absorbs; with `absorbs`
 * (the control: the same box with a medium that absorbs a little) every channel is darker, which
 * shows that the paths do enter the medium (a box they passed by would be a furnace too). */
static void check_furnace_or_darker(const char *what, const char *material_json,
                                    const char *medium_json, int path_kernel, bool absorbs)
{
    const char *dir = test_temp_dir();
    box_obj(dir, "box.obj", -1, -1, -1, 1, 1, 1);
    char text[4096];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [2.5, 2, 4], \"target\": [0, 0, 0], \"up\": [0, 1, 0], "
             "\"fov_y\": 40},\n \"film\": {\"width\": 16, \"height\": 16},\n"
             " %s%s%s"
             " \"materials\": {\"m\": %s},\n"
             " \"objects\": [{\"obj\": \"box.obj\", \"material\": \"m\"%s}],\n"
             " \"background\": [0.5, 0.5, 0.5]}\n",
             medium_json ? "\"media\": {\"inside\": " : "", medium_json ? medium_json : "",
             medium_json ? "},\n" : "", material_json,
             medium_json ? ", \"interior\": \"inside\"" : "");
    const char *scene = test_write_file(dir, "scene.json", text);
    float *rgb = render_scene(scene, 256, 1000, 21, false, path_kernel);
    ImageStats s = region_stats(rgb, 16, 0, 0, 16, 16);
    const double expected[3] = {0.5, 0.5, 0.5};
    cr_log_info("furnace %s: %.5f %.5f %.5f (+- %.5f %.5f %.5f)", what, s.mean[0], s.mean[1],
                s.mean[2], s.stderr_[0], s.stderr_[1], s.stderr_[2]);
    if (!absorbs)
        expect_mean(what, s, expected, 0.0);
    for (int c = 0; absorbs && c < 3; c++)
        cr_expect(s.mean[c] < 0.5 - 4.5 * s.stderr_[c], "%s, channel %d: mean %.5f, not darker", what,
                  c, s.mean[c]);
    free(rgb);
}

static void check_furnace(const char *what, const char *material_json, const char *medium_json,
                          int path_kernel)
{
    check_furnace_or_darker(what, material_json, medium_json, path_kernel, false);
}

Test(media_render, white_furnace_media, .timeout = 900)
{
    check_furnace("grey fog g 0.6", "{\"type\": \"interface\"}",
                  "{\"type\": \"homogeneous\", \"sigma_s\": 3, \"g\": 0.6}", PATH_KERNEL_WAVEFRONT);
    check_furnace("chromatic fog g -0.4", "{\"type\": \"interface\"}",
                  "{\"type\": \"homogeneous\", \"sigma_s\": [1, 3, 6], \"g\": -0.4}",
                  PATH_KERNEL_MEGAKERNEL);
    check_furnace("glass of milk", "{\"type\": \"dielectric\", \"ior\": 1.4}",
                  "{\"type\": \"homogeneous\", \"sigma_s\": [4, 2, 1], \"g\": 0.3}",
                  PATH_KERNEL_WAVEFRONT);
    /* The controls: 10% absorption in the same media must show. */
    check_furnace_or_darker("grey fog, albedo 0.9", "{\"type\": \"interface\"}",
                            "{\"type\": \"homogeneous\", \"sigma_s\": 2.7, \"sigma_a\": 0.3, "
                            "\"g\": 0.6}", PATH_KERNEL_WAVEFRONT, true);
    check_furnace_or_darker("glass of milk, albedo 0.9", "{\"type\": \"dielectric\", \"ior\": 1.4}",
                            "{\"type\": \"homogeneous\", \"sigma_s\": [3.6, 1.8, 0.9], "
                            "\"sigma_a\": [0.4, 0.2, 0.1], \"g\": 0.3}", PATH_KERNEL_MEGAKERNEL, true);
    /* specular 0: the coat, whose Schlick weights are not exactly energy-conserving (principled.cl),
     * is out of the way; what does not reflect diffusely enters and walks without loss. */
    check_furnace("principled subsurface, white",
                  "{\"type\": \"principled\", \"base_color\": 1, \"specular\": 0, "
                  "\"subsurface\": 0.7, \"subsurface_radius\": [0.5, 0.3, 0.2]}",
                  NULL, PATH_KERNEL_MEGAKERNEL);
}

/* ---- Next-event estimation in media ------------------------------------------------------------ */

/* Two 16 x 16 renders that estimate the same value per pixel (NEE + MIS and BSDF or phase sampling
 * alone): their difference has mean 0 in every pixel, and its spread over a block of pixels gives
 * the standard error of its mean. The largest |z| over the 4 blocks of 8 x 8, the whole image
 * (where a bias spread over many pixels shows best) and the 3 channels. */
static double worst_block_z(const float *a, const float *b)
{
    float *diff = malloc(16 * 16 * 3 * sizeof *diff);
    cr_assert(diff);
    for (int i = 0; i < 16 * 16 * 3; i++)
        diff[i] = a[i] - b[i];
    double worst = 0.0;
    for (int block = 0; block < 5; block++) {
        int bx = block % 2, by = block / 2;
        ImageStats d = block < 4 ? region_stats(diff, 16, 8 * bx, 8 * by, 8 * bx + 8, 8 * by + 8)
                                 : region_stats(diff, 16, 0, 0, 16, 16);
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fabs(d.mean[c]) / fmax(d.stderr_[c], 1e-9));
    }
    free(diff);
    return worst;
}

/* On the wavefront and the megakernel: scene rendered with NEE + MIS (1024 spp, seed) and with
 * `alone` (BSDF or phase sampling only, alone_spp, seed + 1), max depth `depth`, agree per block
 * (worst_block_z); the NEE render's mean (green) exceeds min_mean, so that a black image does not
 * pass. */
static void expect_nee_agrees(const char *scene, int alone_spp, int depth, unsigned seed,
                              const char *alone, double min_mean)
{
    for (int kernel = PATH_KERNEL_WAVEFRONT; kernel <= PATH_KERNEL_MEGAKERNEL; kernel++) {
        float *nee = render_scene(scene, 1024, depth, seed, false, kernel);
        float *only = render_scene(scene, alone_spp, depth, seed + 1, true, kernel);
        double worst = worst_block_z(nee, only);
        ImageStats a = region_stats(nee, 16, 0, 0, 16, 16), b = region_stats(only, 16, 0, 0, 16, 16);
        cr_log_info("kernel %d: NEE %.4f %.4f %.4f, %s only %.4f %.4f %.4f, worst block z %.2f",
                    kernel, a.mean[0], a.mean[1], a.mean[2], alone, b.mean[0], b.mean[1], b.mean[2],
                    worst);
        cr_expect(a.mean[1] > min_mean, "kernel %d: the image is dark (%.4f)", kernel, a.mean[1]);
        /* 15 z-values: 4.5 is passed by chance once in about 10^4 seeds. */
        cr_expect(worst < 4.5, "kernel %d: NEE + MIS and %s differ (block z %.2f)", kernel, alone,
                  worst);
        free(nee);
        free(only);
    }
}

Test(media_render, light_sampling_agrees_with_phase_sampling, .timeout = 900)
{
    const char *dir = test_temp_dir();
    box_obj(dir, "box.obj", -1, -1, -1, 1, 1, 1);
    test_write_file(dir, "lamp.obj", "v -0.9 0.9 -0.9\nv 0.9 0.9 -0.9\nv 0.9 0.9 0.9\nv -0.9 0.9 0.9\nf 1 2 3 4\n");
    const char *scene = test_write_file(
        dir, "scene.json",
        "{\"camera\": {\"eye\": [0, 0, 4], \"target\": [0, 0, 0], \"up\": [0, 1, 0], \"fov_y\": 35},\n"
        " \"film\": {\"width\": 16, \"height\": 16},\n"
        " \"media\": {\"fog\": {\"type\": \"homogeneous\", \"sigma_a\": 0.2, \"sigma_s\": [0.6, 1.0, 1.6], \"g\": 0.5}},\n"
        " \"materials\": {\"lamp\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": [2, 2, 2]},\n"
        "               \"boundary\": {\"type\": \"interface\"}},\n"
        " \"objects\": [{\"obj\": \"lamp.obj\", \"material\": \"lamp\"},\n"
        "             {\"obj\": \"box.obj\", \"material\": \"boundary\", \"interior\": \"fog\"}]}\n");
    expect_nee_agrees(scene, 4096, 12, 31, "phase sampling", 0.01);
}

/* An area light seen through an `interface` surface: a BSDF-sampled ray that crosses it and hits
 * the lamp weighs itself against light sampling with the light's density as seen from the vertex
 * it left, over the whole distance (crossings are no vertices), not from the crossing. The lamp
 * hangs inside an interface box over a floor; direct light only (max depth 2), so the NEE + MIS
 * render and the BSDF-only render estimate the same image. With the density from the crossing the
 * BSDF side's weight was too large and the floor too bright under the box. */
Test(media_render, mis_across_interfaces, .timeout = 900)
{
    const char *dir = test_temp_dir();
    box_obj(dir, "box.obj", -1, 0.6, -1, 1, 1.8, 1);
    test_write_file(dir, "floor.obj", "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\nf 1 4 3\nf 1 3 2\n");
    /* Facing down (-y), inside the box. */
    test_write_file(dir, "lamp.obj", "v -0.6 1.2 -0.6\nv 0.6 1.2 -0.6\nv 0.6 1.2 0.6\nv -0.6 1.2 0.6\nf 1 2 3 4\n");
    const char *scene = test_write_file(
        dir, "scene.json",
        "{\"camera\": {\"eye\": [0, 3, 4], \"target\": [0, 0, 0.5], \"up\": [0, 1, 0], \"fov_y\": 40},\n"
        " \"film\": {\"width\": 16, \"height\": 16},\n"
        " \"media\": {\"clear\": {\"type\": \"homogeneous\", \"sigma_a\": 0.001}},\n"
        " \"materials\": {\"lamp\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": [3, 3, 3]},\n"
        "               \"floor\": {\"type\": \"diffuse\", \"albedo\": 0.8},\n"
        "               \"boundary\": {\"type\": \"interface\"}},\n"
        " \"objects\": [{\"obj\": \"lamp.obj\", \"material\": \"lamp\"},\n"
        "             {\"obj\": \"floor.obj\", \"material\": \"floor\"},\n"
        "             {\"obj\": \"box.obj\", \"material\": \"boundary\", \"interior\": \"clear\"}]}\n");
    expect_nee_agrees(scene, 8192, 2, 41, "BSDF sampling", 0.05);
}
