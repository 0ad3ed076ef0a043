// SPDX-License-Identifier: MIT
/* The path tracer against analytic answers and against itself: white furnace, closed emitting
 * sphere (exercises NEE + MIS + Russian roulette), NEE vs BSDF-only on the Cornell box, compaction
 * on/off, determinism and independence from the pass split. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "scene/scene.h"
#include "render/scene_upload.h"
#include "support.h"
#include "render/wavefront.h"
#include "sphere_obj.h"


static const char *write_sphere_scene(const char *dir, const char *mtl, bool inward, const char *camera,
                                      const char *background)
{
    static char path[512];
    char file[512];
    snprintf(file, sizeof file, "%s/sphere.mtl", dir);
    FILE *f = fopen(file, "w");
    fprintf(f, "%s", mtl);
    fclose(f);
    snprintf(file, sizeof file, "%s/sphere.obj", dir);
    f = fopen(file, "w");
    fprintf(f, "mtllib sphere.mtl\nusemtl surface\n");
    write_sphere_obj(f, (float[3]){0, 0, 0}, 1.0f, 24, 48, inward);
    fclose(f);
    snprintf(path, sizeof path, "%s/scene.json", dir);
    f = fopen(path, "w");
    fprintf(f, "{\"camera\": %s, \"objects\": [{\"obj\": \"sphere.obj\"}], \"background\": %s}\n", camera,
            background);
    fclose(f);
    return path;
}

static double channel_mean(const float *rgb, size_t n, int c)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++)
        sum += rgb[3 * i + c];
    return sum / (double)n;
}

/* White furnace: a convex diffuse sphere of albedo 0.8 under a uniform sky of 1 reflects exactly
 * 0.8 (every bounce ray escapes); the sky around it is 1. Any self-intersection or energy error
 * shows as a deviation far above float rounding. */
Test(integrator, white_furnace_sphere, .timeout = 120)
{
    const char *dir = test_temp_dir();
    const char *scene = write_sphere_scene(dir, "newmtl surface\nKd 0.8 0.8 0.8\n", false,
                                           "{\"eye\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40}",
                                           "[1, 1, 1]");
    RenderFixture f;
    render_fixture_open(&f, scene, 48, 48);
    for (int nee = 0; nee < 2; nee++) {
        float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 8, .seed = 1, .no_nee = nee}, NULL);
        int on_sphere = 0, sky = 0;
        for (int y = 0; y < 48; y++)
            for (int x = 0; x < 48; x++) {
                /* Pixels well inside or well outside the sphere's silhouette (radius ~ 16.5 px). */
                double r = hypot(x + 0.5 - 24, y + 0.5 - 24);
                const float *px = &rgb[3 * (y * 48 + x)];
                for (int c = 0; c < 3; c++) {
                    if (r < 14) {
                        cr_expect(fabsf(px[c] - 0.8f) < 1e-3f, "pixel %d,%d = %f, expected 0.8", x, y, px[c]);
                    } else if (r > 19) {
                        cr_expect(fabsf(px[c] - 1.0f) < 1e-5f, "pixel %d,%d = %f, expected 1", x, y, px[c]);
                    }
                }
                on_sphere += r < 14, sky += r > 19;
            }
        cr_assert(on_sphere > 400 && sky > 400);
        free(rgb);
    }
    render_fixture_close(&f);
}

/* Inside a closed sphere whose inner wall has albedo a = 0.5 and emits Le = 0.5, radiance is
 * Le / (1 - a) = 1 in the limit; with max_depth D it is 1 - a^D. Exercises light sampling, the MIS
 * weights of both strategies (they must sum to one) and Russian roulette. */
Test(integrator, closed_emitting_sphere_converges_to_one, .timeout = 120)
{
    const char *dir = test_temp_dir();
    const char *scene = write_sphere_scene(dir, "newmtl surface\nKd 0.5 0.5 0.5\nKe 0.5 0.5 0.5\n", true,
                                           "{\"eye\": [0, 0, 0.3], \"target\": [0, 0, -1], \"fov_y\": 60}",
                                           "[0, 0, 0]");
    RenderFixture f;
    render_fixture_open(&f, scene, 32, 32);
    const int depth = 12;
    double expected = 1.0 - pow(0.5, depth);
    for (int nee = 0; nee < 2; nee++) {
        float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 64, .max_depth = depth, .seed = 7, .no_nee = !nee}, NULL);
        for (int c = 0; c < 3; c++) {
            double mean = channel_mean(rgb, 32 * 32, c);
            cr_expect(fabs(mean - expected) < 0.01, "%s: channel %d mean %f, expected %f",
                      nee ? "NEE+MIS" : "BSDF only", c, mean, expected);
        }
        free(rgb);
    }
    render_fixture_close(&f);
}

/* Per-channel image means and their standard errors from K independent renders (seeds). */
typedef struct {
    double mean[3], se[3];
    float *image; /* mean image over the K renders */
} Estimate;

static Estimate estimate(RenderFixture *f, RenderSettings s, int renders)
{
    size_t n = (size_t)f->scene.desc.width * (size_t)f->scene.desc.height;
    Estimate e = {.image = calloc(n * 3, sizeof(float))};
    double sums[3] = {0}, sums2[3] = {0};
    for (int k = 0; k < renders; k++) {
        s.seed = 1000u + (unsigned)k * 7919u;
        float *rgb = render_fixture_render(f, s, NULL);
        for (int c = 0; c < 3; c++) {
            double m = channel_mean(rgb, n, c);
            sums[c] += m, sums2[c] += m * m;
        }
        for (size_t i = 0; i < 3 * n; i++)
            e.image[i] += rgb[i] / renders;
        free(rgb);
    }
    for (int c = 0; c < 3; c++) {
        e.mean[c] = sums[c] / renders;
        double var = (sums2[c] - renders * e.mean[c] * e.mean[c]) / (renders - 1);
        e.se[c] = sqrt(fmax(var, 0.0) / renders);
    }
    return e;
}

/* NEE+MIS and BSDF sampling alone estimate the same integral: their image means must agree
 * within the measured noise (z < 4.5), and their per-pixel difference must be noise-sized. */
Test(integrator, nee_and_bsdf_sampling_converge_to_the_same_image, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", 32, 32);
    const int renders = 6;
    Estimate nee = estimate(&f, (RenderSettings){.spp = 64, .max_depth = 5}, renders);
    Estimate bsdf = estimate(&f, (RenderSettings){.spp = 256, .max_depth = 5, .no_nee = true}, renders);
    for (int c = 0; c < 3; c++) {
        double z = fabs(nee.mean[c] - bsdf.mean[c]) / sqrt(nee.se[c] * nee.se[c] + bsdf.se[c] * bsdf.se[c]);
        cr_expect(z < 4.5, "channel %d: NEE %f +- %f vs BSDF %f +- %f (z = %.2f)", c, nee.mean[c],
                  nee.se[c], bsdf.mean[c], bsdf.se[c], z);
        cr_expect(nee.mean[c] > 0.01, "channel %d: the image is not black (mean %f)", c, nee.mean[c]);
    }
    free(nee.image);
    free(bsdf.image);
    render_fixture_close(&f);
}

Test(integrator, compaction_does_not_change_the_image, .timeout = 120)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", 32, 32);
    RenderStats with, without, refilled;
    /* The wavefront's own mechanics (compaction, refills, the shadow queue) are under test here:
     * pinned to it, since CPUs otherwise get the megakernel (test_megakernel.c). */
    float *a = render_fixture_render(&f, (RenderSettings){.spp = 8, .max_depth = 8, .seed = 3, .path_kernel = PATH_KERNEL_WAVEFRONT}, &with);
    float *b = render_fixture_render(&f, (RenderSettings){.spp = 8, .max_depth = 8, .seed = 3, .no_compaction = true}, &without);
    cr_expect(memcmp(a, b, 32 * 32 * 3 * sizeof(float)) == 0, "images differ");
    /* Compaction really removed paths: fewer extension rays than without. */
    cr_expect(with.live_per_step[4] < with.live_per_step[0]);
    /* 256 slots tracing the same one window of 8192 samples: slots are refilled as paths end (so
     * there are more steps than bounces), and the image keeps every bit. */
    float *c = render_fixture_render(&f, (RenderSettings){.spp = 8, .max_depth = 8, .seed = 3, .pool_size = 256, .window_size = 8192, .path_kernel = PATH_KERNEL_WAVEFRONT}, &refilled);
    cr_expect_eq(refilled.windows, 1);
    cr_expect_eq(refilled.config.pool_size, 256);
    cr_expect(refilled.live_per_step[40] == 256, "the pool is not kept full: %llu paths at step 40",
              (unsigned long long)refilled.live_per_step[40]);
    cr_expect_eq(refilled.extension_rays, with.extension_rays);
    cr_expect(memcmp(a, c, 32 * 32 * 3 * sizeof(float)) == 0, "refilling slots changed the image");
    /* Shadow rays by a flag per active path instead of the queue: the same rays, the same bits. */
    RenderStats queued;
    float *q = render_fixture_render(&f, (RenderSettings){.spp = 8, .max_depth = 8, .seed = 3, .pool_size = 256, .window_size = 8192, .shadow_flags = true, .path_kernel = PATH_KERNEL_WAVEFRONT}, &queued);
    cr_expect_eq(queued.shadow_rays, with.shadow_rays);
    cr_expect(memcmp(a, q, 32 * 32 * 3 * sizeof(float)) == 0, "shadow flags changed the image");
    /* Shading the paths grouped by material: the same bits. */
    float *sorted = render_fixture_render(&f, (RenderSettings){.spp = 8, .max_depth = 8, .seed = 3, .pool_size = 256, .window_size = 8192, .sort_materials = true}, NULL);
    cr_expect(memcmp(a, sorted, 32 * 32 * 3 * sizeof(float)) == 0, "sorting by material changed the image");
    /* Every ray against every triangle instead of the BVH (the benchmark's ablation): the same
     * hits, so the same rays and the same bits. */
    RenderStats brute;
    float *bf = render_fixture_render(&f, (RenderSettings){.spp = 8, .max_depth = 8, .seed = 3, .brute_force = true}, &brute);
    cr_expect_eq(brute.extension_rays, with.extension_rays);
    cr_expect_eq(brute.shadow_rays, with.shadow_rays);
    cr_expect(memcmp(a, bf, 32 * 32 * 3 * sizeof(float)) == 0, "brute force changed the image");
    free(a), free(b), free(c), free(q), free(sorted), free(bf);
    render_fixture_close(&f);
}

/* Passing an `interface` surface takes a step but is no bounce: without compaction (every step
 * over the whole window) the paths that cross one still run to their ends, as with it. */
Test(integrator, no_compaction_with_interfaces, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open(&f, "tests/scenes/fog-room/scene.json", 24, 24);
    RenderStats with, without;
    RenderSettings s = {.spp = 4, .max_depth = 6, .seed = 3, .path_kernel = PATH_KERNEL_WAVEFRONT};
    float *a = render_fixture_render(&f, s, &with);
    s.no_compaction = true;
    float *b = render_fixture_render(&f, s, &without);
    cr_expect_eq(without.extension_rays, with.extension_rays, "%llu extension rays, %llu with compaction",
                 (unsigned long long)without.extension_rays, (unsigned long long)with.extension_rays);
    cr_expect(memcmp(a, b, 24 * 24 * 3 * sizeof(float)) == 0, "images differ");
    free(a), free(b);
    render_fixture_close(&f);
}

Test(integrator, same_seed_same_bits_and_window_split_independent, .timeout = 120)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", 32, 32);
    size_t n = 32 * 32 * 3;
    float *a = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 6, .seed = 11}, NULL);
    float *b = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 6, .seed = 11}, NULL);
    cr_expect(memcmp(a, b, n * sizeof(float)) == 0, "same seed, different bits");
    /* Windows of 4 spp, and of half a film (traced by 128 refilled slots): the same samples in
     * other sums, and the film's fixed-point sums are exact, so the same bits. */
    RenderStats stats;
    float *c = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 6, .seed = 11, .pool_size = 4 * 32 * 32, .window_size = 4 * 32 * 32}, &stats);
    cr_expect_eq(stats.windows, 4);
    float *d = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 6, .seed = 11, .pool_size = 128, .window_size = 512}, &stats);
    cr_expect_eq(stats.windows, 32);
    cr_expect(memcmp(a, c, n * sizeof(float)) == 0, "4 windows changed the image");
    cr_expect(memcmp(a, d, n * sizeof(float)) == 0, "32 windows changed the image");
    /* A different seed changes the image. */
    float *e = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 6, .seed = 12}, NULL);
    cr_expect(memcmp(a, e, n * sizeof(float)) != 0);
    free(a), free(b), free(c), free(d), free(e);
    render_fixture_close(&f);
}
