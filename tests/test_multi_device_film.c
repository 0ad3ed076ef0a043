// SPDX-License-Identifier: MIT
/* Work units through the wavefront API, in this process: a render split into runs of units
 * (wavefront_render_block) in shuffled order, on one device or spread over two, is the same bits
 * as one wavefront_render of the whole; and what is promised across devices that differ (README,
 * "Several devices": equal within float rounding). PoCL stands in for a GPU by opening the CPU
 * again with a GPU's BVH layout (PT_BVH_WIDTH=2: another tree, visited in another order) and, for
 * a GPU's other float rounding (NVIDIA's compiler contracts a * b + c into FMAs and has its own
 * division, square root and transcendentals), with -cl-unsafe-math-optimizations (PT_CL_OPTIONS).
 *
 * The criterion: the mean of |a - b| over every channel below 1e-4 of the image's mean value, and
 * under 1% of the pixels differing by more than 1% (of the larger of the value and the image mean).
 * Why statistical: most paths only round differently (measured: worst 2.4e-5 relative, mean 8e-8),
 * but a path whose hit point moves by an ulp across an edge, or whose Russian-roulette or lobe
 * choice flips on a rounded value, takes another branch and its sample becomes an unrelated value
 * (as large as the pixel's mean times spp at a light): rare, so it stays below the pixel share. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/film.h"
#include "render/session.h"
#include "dist/unit_film.h"
#include "render/wavefront.h"
#include "dist/work_units.h"
#include "scene/scene.h"
#include "support.h"

#define SCENE "tests/scenes/cornell-sphere"
#define WIDTH 48
#define HEIGHT 40
#define SPP 24

/* The scene on contexts of the CPU device: twice as it is (two devices computing the same values);
 * with the 2-wide BVH (the layout a GPU walks); with the 2-wide BVH and unsafe maths (a GPU's
 * rounding, as far as PoCL can show it). */
enum { DEV_CPU, DEV_CPU_AGAIN, DEV_TWO_WIDE, DEV_GPU_LIKE, NUM_DEVICES };

typedef struct {
    Scene scene;
    SessionDevice dev[NUM_DEVICES];
    int count;
} Devices;

static void open_scene(Scene *scene)
{
    Error err = {0};
    cr_assert(scene_load_with(SCENE, INSTANCING_AUTO, scene, &err), "%s", err.message);
    scene->desc.width = WIDTH, scene->desc.height = HEIGHT;
    scene_add_default_light(scene);
}

/* The first `count` devices. program.c reads PT_BVH_WIDTH and PT_CL_OPTIONS when a device is
 * opened, so each is set around one session_device_open. */
static void open_devices(Devices *t, int count)
{
    static const struct {
        const char *bvh_width, *cl_options;
    } env[NUM_DEVICES] = {{NULL, NULL},
                          {NULL, NULL},
                          {"2", NULL},
                          {"2", "-cl-mad-enable -cl-no-signed-zeros "
                                "-cl-unsafe-math-optimizations"}};
    memset(t, 0, sizeof *t);
    open_scene(&t->scene);
    for (int i = 0; i < count; i++) {
        Error err = {0};
        if (env[i].bvh_width)
            setenv("PT_BVH_WIDTH", env[i].bvh_width, 1);
        if (env[i].cl_options)
            setenv("PT_CL_OPTIONS", env[i].cl_options, 1);
        bool ok = session_device_open(&t->dev[i], &t->scene, "cpu", false, &err);
        unsetenv("PT_BVH_WIDTH");
        unsetenv("PT_CL_OPTIONS");
        cr_assert(ok, "%s", err.message);
        t->count++;
    }
    if (count > DEV_TWO_WIDE)
        cr_assert_eq(t->dev[DEV_TWO_WIDE].dev.bvh_width, 2);
}

static void close_devices(Devices *t)
{
    for (int i = t->count; i-- > 0;)
        session_device_close(&t->dev[i]);
    scene_free(&t->scene);
}

static RenderSettings settings(const Scene *scene)
{
    return (RenderSettings){.spp = SPP, .max_depth = scene->desc.max_depth, .seed = 3};
}

static float *render_whole(SessionDevice *d, const Scene *scene)
{
    float *rgb = malloc((size_t)WIDTH * HEIGHT * 3 * sizeof *rgb);
    RenderSettings s = settings(scene);
    RenderStats stats;
    Error err = {0};
    cr_assert(wavefront_render(&d->dev, scene, &d->buffers, &s, rgb, &stats, &err), "%s",
              err.message);
    return rgb;
}

/* The grid's runs (random lengths within a tile) in shuffled order, rendered in turn by the
 * devices which[0 .. num_devices - 1] (run i by which[i % num_devices]) into their films, merged
 * into one host film. */
static float *render_units(Devices *t, const int *which, int num_devices, uint32_t unit_spp,
                           uint32_t unit_rows, uint64_t seed)
{
    UnitGrid g;
    Error err = {0};
    cr_assert(unit_grid_init(&g, WIDTH, HEIGHT, SPP, unit_spp, unit_rows, &err), "%s", err.message);
    UnitRun *runs = malloc(g.count * sizeof *runs);
    uint32_t n = 0;
    for (uint32_t u = 0; u < g.count; n++) {
        uint32_t tile_end = (u / g.blocks + 1) * g.blocks;
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        uint32_t count = 1 + (uint32_t)(seed >> 33) % 3u;
        runs[n] = (UnitRun){u, count < tile_end - u ? count : tile_end - u};
        u += runs[n].count;
    }
    for (uint32_t i = n; i > 1; i--) { /* Fisher-Yates */
        seed = seed * 6364136223846793005ull + 1442695040888963407ull;
        uint32_t j = (uint32_t)(seed >> 33) % i;
        UnitRun swap = runs[i - 1];
        runs[i - 1] = runs[j], runs[j] = swap;
    }
    RenderSettings s = settings(&t->scene);
    Wavefront *w[2] = {NULL, NULL};
    uint8_t *done[2];
    for (int d = 0; d < num_devices; d++) {
        SessionDevice *sd = &t->dev[which[d]];
        w[d] = wavefront_create(&sd->dev, &t->scene, &sd->buffers, &s, &err);
        cr_assert(w[d], "%s", err.message);
        done[d] = calloc(unit_bitmap_bytes(g.count), 1);
    }
    for (uint32_t i = 0; i < n; i++) {
        int d = (int)(i % (uint32_t)num_devices);
        PixelBlock b = unit_run_block(&g, runs[i]);
        wavefront_render_block(w[d], &b);
        for (uint32_t u = runs[i].first; u < runs[i].first + runs[i].count; u++)
            unit_bitmap_set(done[d], u);
    }
    UnitFilm film;
    cr_assert(unit_film_init(&film, &g, &err));
    uint64_t *sums = malloc(film.num_pixels * FILM_BYTES_PER_PIXEL);
    for (int d = 0; d < num_devices; d++) {
        film_read_sums(wavefront_film(w[d]), sums);
        cr_assert(unit_film_merge(&film, sums, done[d], &err), "%s", err.message);
        wavefront_destroy(w[d]);
        free(done[d]);
    }
    cr_assert(unit_film_complete(&film));
    cr_assert_eq(unit_film_spp_done(&film), SPP);
    float *rgb = malloc(film.num_pixels * 3 * sizeof *rgb);
    film_sums_to_rgb(film.sums, film.num_pixels, rgb);
    unit_film_free(&film);
    free(sums);
    free(runs);
    return rgb;
}

static void expect_same_bits(const float *a, const float *b, const char *what)
{
    size_t n = (size_t)WIDTH * HEIGHT * 3, differ = 0, first = 0;
    for (size_t i = 0; i < n; i++)
        if (memcmp(&a[i], &b[i], sizeof a[i]) != 0 && differ++ == 0)
            first = i;
    cr_expect_eq(differ, 0, "%s: %zu of %zu values differ, the first at pixel %zu (%.9g vs %.9g)",
                 what, differ, n, first / 3, differ ? a[first] : 0.0, differ ? b[first] : 0.0);
}

Test(multi_device_film, shuffled_runs_on_one_or_two_devices_are_the_same_bits, .timeout = 600)
{
    Devices t;
    open_devices(&t, DEV_CPU_AGAIN + 1);
    float *whole = render_whole(&t.dev[DEV_CPU], &t.scene);
    double sum = 0.0;
    for (size_t i = 0; i < (size_t)WIDTH * HEIGHT * 3; i++)
        sum += whole[i];
    cr_assert_gt(sum, 0.0, "the image is black");
    const struct {
        uint32_t unit_spp, unit_rows;
        int devices;
    } splits[] = {{1, 0, 1}, {7, 5, 1}, {1, 7, 2}, {7, 0, 2}, {64, 1, 2}};
    for (size_t i = 0; i < sizeof splits / sizeof splits[0]; i++) {
        float *units = render_units(&t, (const int[]){DEV_CPU, DEV_CPU_AGAIN}, splits[i].devices,
                                    splits[i].unit_spp, splits[i].unit_rows, 1000 + i);
        char what[128];
        snprintf(what, sizeof what, "units of %u spp x %u rows on %d devices", splits[i].unit_spp,
                 splits[i].unit_rows, splits[i].devices);
        expect_same_bits(whole, units, what);
        free(units);
    }
    free(whole);
    close_devices(&t);
}

/* The criterion of the file's comment. */
static void expect_within_rounding(const float *a, const float *b, const char *what)
{
    size_t pixels = (size_t)WIDTH * HEIGHT, values_differ = 0, far = 0;
    double sum = 0.0, diff = 0.0;
    for (size_t i = 0; i < pixels * 3; i++) {
        sum += a[i], diff += fabs((double)a[i] - b[i]);
        values_differ += a[i] != b[i];
    }
    double mean = sum / (double)(pixels * 3);
    cr_assert_gt(mean, 0.0, "%s: the image is black", what);
    for (size_t p = 0; p < pixels; p++)
        for (int c = 0; c < 3; c++)
            if (fabs((double)a[3 * p + c] - b[3 * p + c]) >
                0.01 * fmax(fabs((double)a[3 * p + c]), mean)) {
                far++;
                break;
            }
    double relative = diff / (double)(pixels * 3) / mean, share = (double)far / (double)pixels;
    cr_log_info("%s: %zu of %zu values differ, mean |difference| %.3g of the mean, %.3g%% of "
                "pixels beyond 1%%", what, values_differ, pixels * 3, relative, 100.0 * share);
    cr_expect_lt(relative, 1e-4, "%s: mean |difference| %.3g of the mean", what, relative);
    cr_expect_lt(share, 0.01, "%s: %.3g%% of pixels differ by more than 1%%", what, 100.0 * share);
}

Test(multi_device_film, other_layout_and_rounding_agree_within_float_rounding, .timeout = 900)
{
    Devices t;
    open_devices(&t, NUM_DEVICES);
    float *cpu = render_whole(&t.dev[DEV_CPU], &t.scene);
    float *two_wide = render_whole(&t.dev[DEV_TWO_WIDE], &t.scene);
    float *gpu_like = render_whole(&t.dev[DEV_GPU_LIKE], &t.scene);
    expect_within_rounding(cpu, two_wide, "2-wide vs 8-wide BVH");
    expect_within_rounding(cpu, gpu_like, "2-wide BVH and unsafe maths vs the CPU's build");
    /* Sharing the units: close to either device alone. */
    float *mixed = render_units(&t, (const int[]){DEV_CPU, DEV_GPU_LIKE}, 2, 1, 0, 77);
    expect_within_rounding(cpu, mixed, "the CPU and the GPU-like build sharing the units");
    expect_within_rounding(gpu_like, mixed, "sharing the units vs the GPU-like build alone");
    /* Each build alone is still exactly its own image through units. */
    float *gpu_like_units = render_units(&t, (const int[]){DEV_GPU_LIKE}, 1, 3, 4, 78);
    expect_same_bits(gpu_like, gpu_like_units, "the GPU-like build through units");
    free(cpu), free(two_wide), free(gpu_like), free(mixed), free(gpu_like_units);
    close_devices(&t);
}
