// SPDX-License-Identifier: MIT
/* The film's exact sums: the same bits whatever the window, the pool, or the order in which
 * blocks of samples arrive; counts past 2^24; clamping and saturation at the documented edges. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/film.h"
#include "render/wavefront.h"
#include "support.h"
#include "xorshift.h"

#define SIZE 64
#define PIXELS (SIZE * SIZE)

static const RenderSettings cornell = {.spp = 32, .max_depth = 6, .seed = 5};

/* The film's raw words after rendering settings s (all of its spp) on f. */
static uint64_t *render_sums(RenderFixture *f, RenderSettings s)
{
    Error err = {0};
    Wavefront *w = wavefront_create(f->dev, &f->scene, &f->buffers, &s, &err);
    cr_assert(w, "%s", err.message);
    wavefront_advance(w, UINT64_MAX, s.spp);
    cr_assert_eq(wavefront_spp_done(w), s.spp);
    size_t n = (size_t)f->scene.desc.width * (size_t)f->scene.desc.height;
    uint64_t *sums = malloc(n * FILM_BYTES_PER_PIXEL);
    film_read_sums(wavefront_film(w), sums);
    wavefront_destroy(w);
    return sums;
}

/* Windows of 1, 4, 16 and 32 spp per pixel and a quarter of a sample, pools of 256 to 65536
 * slots: every split of the same samples gives the same bits. (A window holds at least the pool.) */
Test(film, windows_and_pools_do_not_change_the_bits, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", SIZE, SIZE);
    RenderStats ref_stats;
    float *ref = render_fixture_render(&f, cornell, &ref_stats);
    cr_assert_eq(ref_stats.windows, 1, "the reference is one window of 32 spp");
    const struct {
        uint32_t window, pool, windows;
    } splits[] = {
        {1 * PIXELS, 256, 32},   {1 * PIXELS, PIXELS, 32}, {4 * PIXELS, 256, 8},
        {16 * PIXELS, 65536, 2}, {32 * PIXELS, 256, 1},    {32 * PIXELS, 65536, 1},
        {PIXELS / 4, 256, 128},
    };
    for (size_t i = 0; i < sizeof splits / sizeof splits[0]; i++) {
        RenderSettings s = cornell;
        s.window_size = splits[i].window, s.pool_size = splits[i].pool;
        RenderStats stats;
        float *rgb = render_fixture_render(&f, s, &stats);
        cr_expect_eq(stats.windows, splits[i].windows, "window %u: %u windows", splits[i].window,
                     stats.windows);
        cr_expect_eq(stats.config.pool_size, splits[i].pool < splits[i].window ? splits[i].pool : splits[i].window);
        cr_expect(memcmp(rgb, ref, PIXELS * 3 * sizeof(float)) == 0,
                  "window %u, pool %u: the image differs from one window of 32 spp", splits[i].window,
                  splits[i].pool);
        free(rgb);
    }
    free(ref);
    render_fixture_close(&f);
}

/* Eight blocks of 4 spp (first_sample 0, 4, .. 28), rendered in a shuffled order and merged on the
 * host: the sums of one render of 32 spp, word for word. */
Test(film, sample_blocks_in_any_order_add_up_to_one_render, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", SIZE, SIZE);
    uint64_t *whole = render_sums(&f, cornell);
    int order[8] = {0, 1, 2, 3, 4, 5, 6, 7};
    uint64_t rng = 0x5eedf11dull | 1;
    for (int i = 7; i > 0; i--) { /* Fisher-Yates */
        int j = (int)(xorshift_next(&rng) % (uint32_t)(i + 1)), t = order[i];
        order[i] = order[j], order[j] = t;
    }
    uint64_t *merged = calloc(PIXELS * FILM_WORDS, sizeof *merged), *first_block = NULL;
    for (int b = 0; b < 8; b++) {
        RenderSettings s = cornell;
        s.spp = 4, s.first_sample = 4u * (uint32_t)order[b];
        s.window_size = PIXELS; /* one sample per window inside the block, too */
        uint64_t *block = render_sums(&f, s);
        film_sums_add(merged, block, PIXELS);
        if (order[b] == 0)
            first_block = block;
        else
            free(block);
    }
    cr_expect(memcmp(merged, whole, PIXELS * FILM_BYTES_PER_PIXEL) == 0,
              "blocks in the order %d %d %d %d %d %d %d %d do not add up to one render", order[0],
              order[1], order[2], order[3], order[4], order[5], order[6], order[7]);
    /* The blocks really are different samples: block 0 alone is not a quarter of the sums. */
    cr_assert(first_block);
    cr_expect_eq(first_block[3], 4, "4 samples in block 0");
    cr_expect(memcmp(first_block, whole, PIXELS * FILM_BYTES_PER_PIXEL) != 0);
    float *a = malloc(PIXELS * 3 * sizeof *a), *b = malloc(PIXELS * 3 * sizeof *b);
    film_sums_to_rgb(merged, PIXELS, a);
    film_sums_to_rgb(first_block, PIXELS, b);
    cr_expect(memcmp(a, b, PIXELS * 3 * sizeof *a) != 0, "block 0 alone gives the whole image");
    float *rendered = render_fixture_render(&f, cornell, NULL);
    cr_expect(memcmp(a, rendered, PIXELS * 3 * sizeof *a) == 0, "film_sums_to_rgb differs from the render");
    free(a), free(b), free(rendered), free(first_block), free(merged), free(whole);
    render_fixture_close(&f);
}

/* A scene that shows only the background (one triangle behind the camera). */
static const char *write_sky_scene(const char *background)
{
    static char path[512];
    const char *dir = test_temp_dir();
    char file[512];
    snprintf(file, sizeof file, "%s/behind.obj", dir);
    FILE *out = fopen(file, "w");
    cr_assert(out);
    fprintf(out, "v -1 -1 5\nv 1 -1 5\nv 0 1 5\nf 1 2 3\n");
    fclose(out);
    snprintf(path, sizeof path, "%s/scene.json", dir);
    out = fopen(path, "w");
    cr_assert(out);
    fprintf(out, "{\"camera\": {\"eye\": [0, 0, 0], \"target\": [0, 0, -1], \"fov_y\": 40},\n"
                 " \"objects\": [{\"obj\": \"behind.obj\"}], \"background\": %s}\n", background);
    fclose(out);
    return path;
}

/* Every sample is the background: r above FILM_SAMPLE_MAX is clamped to it, g = 1.5 is exact,
 * b = 0.1 is rounded to the nearest step 2^-FILM_FRACTION_BITS. */
Test(film, samples_are_clamped_and_rounded_to_the_documented_steps, .timeout = 120)
{
    RenderFixture f;
    render_fixture_open(&f, write_sky_scene("[3000000, 1.5, 0.1]"), 4, 4);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 3, .max_depth = 2}, NULL);
    float b = (float)(1677722.0 / 16777216.0); /* round(0.1f * 2^24) / 2^24 */
    for (int i = 0; i < 16; i++) {
        cr_expect_eq(rgb[3 * i + 0], FILM_SAMPLE_MAX, "pixel %d: r = %f", i, rgb[3 * i + 0]);
        cr_expect_eq(rgb[3 * i + 1], 1.5f, "pixel %d: g = %f", i, rgb[3 * i + 1]);
        cr_expect_eq(rgb[3 * i + 2], b, "pixel %d: b = %.9g, expected %.9g", i, rgb[3 * i + 2], b);
    }
    free(rgb);
    render_fixture_close(&f);
}

/* A film preset to 2^24 samples takes one more (a float count would stay at 2^24), and a sum at
 * the edge saturates instead of wrapping. */
Test(film, the_count_grows_past_2_24_and_sums_saturate, .timeout = 120)
{
    RenderFixture f;
    render_fixture_open(&f, write_sky_scene("[2, 1.5, 0.25]"), 4, 4);
    RenderSettings s = {.spp = 1, .max_depth = 2};
    Error err = {0};
    Wavefront *w = wavefront_create(f.dev, &f.scene, &f.buffers, &s, &err);
    cr_assert(w, "%s", err.message);
    const uint64_t one = 1ull << FILM_FRACTION_BITS, before = 1ull << 24;
    uint64_t sums[16 * FILM_WORDS];
    for (int i = 0; i < 16; i++) {
        sums[FILM_WORDS * i + 0] = UINT64_MAX - one; /* one sample of 2 from the edge */
        sums[FILM_WORDS * i + 1] = before * (one + one / 2);
        sums[FILM_WORDS * i + 2] = before * (one / 4);
        sums[FILM_WORDS * i + 3] = before;
    }
    film_write_sums(wavefront_film(w), sums);
    wavefront_advance(w, UINT64_MAX, 1);
    film_read_sums(wavefront_film(w), sums);
    float rgb[16 * 3];
    film_sums_to_rgb(sums, 16, rgb);
    for (int i = 0; i < 16; i++) {
        const uint64_t *px = &sums[FILM_WORDS * i];
        cr_expect_eq(px[3], before + 1, "pixel %d: %llu samples", i, (unsigned long long)px[3]);
        cr_expect_eq(px[0], UINT64_MAX, "pixel %d: r did not saturate", i);
        cr_expect_eq(px[1], (before + 1) * (one + one / 2));
        cr_expect_eq(px[2], (before + 1) * (one / 4));
        cr_expect_eq(rgb[3 * i + 1], 1.5f);
        cr_expect_eq(rgb[3 * i + 2], 0.25f);
    }
    wavefront_destroy(w);
    /* The host merge saturates the same way and adds counts exactly. */
    uint64_t a[FILM_WORDS] = {UINT64_MAX - 1, 5, 0, before}, b[FILM_WORDS] = {7, 6, 0, 1};
    film_sums_add(a, b, 1);
    cr_expect(a[0] == UINT64_MAX && a[1] == 11 && a[2] == 0 && a[3] == before + 1);
    render_fixture_close(&f);
}

/* A panel glowing with radiance 3 on black, its edges across pixels: every sample is 0 or 3. */
static const char *write_panel_scene(void)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "panel.mtl", "newmtl panel\nKd 0 0 0\nKe 3 3 3\n");
    test_write_file(dir, "panel.obj", "mtllib panel.mtl\nusemtl panel\n"
                                      "v -0.37 -0.41 0\nv 0.53 -0.41 0\nv 0.53 0.29 0\nv -0.37 0.29 0\n"
                                      "f 1 2 3 4\n");
    return test_write_file(dir, "scene.json",
                           "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0], \"fov_y\": 40},\n"
                           " \"objects\": [{\"obj\": \"panel.obj\"}], \"background\": [0, 0, 0]}\n");
}

/* The moments: a pixel whose samples are all equal has variance exactly 0; one whose samples take
 * the two values 0 and a has mean m and sample variance n / (n - 1) m (a - m), so the variance of
 * its mean is m (a - m) / (n - 1). And keeping them leaves the film's bits as they were. */
Test(film, the_variance_of_constant_and_two_valued_pixels, .timeout = 120)
{
    RenderFixture f;
    render_fixture_open(&f, write_panel_scene(), 8, 8);
    RenderSettings s = {.spp = 64, .max_depth = 2, .seed = 9, .moments = true};
    Error err = {0};
    Wavefront *w = wavefront_create(f.dev, &f.scene, &f.buffers, &s, &err);
    cr_assert(w, "%s", err.message);
    wavefront_advance(w, UINT64_MAX, s.spp);
    float rgb[64 * 3], variance[64 * 3], spp[64];
    wavefront_read_film(w, rgb);
    cr_assert(wavefront_read_variance(w, variance));
    wavefront_read_spp(w, spp);
    wavefront_destroy(w);
    int constant = 0, two_valued = 0;
    for (int i = 0; i < 64; i++) {
        cr_expect_eq(spp[i], 64.0f);
        double m = rgb[3 * i], expected = m * (3.0 - m) / 63.0;
        if (m == 0.0 || m == 3.0)
            constant++;
        else
            two_valued++;
        for (int c = 0; c < 3; c++)
            cr_expect(fabs(variance[3 * i + c] - expected) <= 1e-6 * expected,
                      "pixel %d: mean %g, variance of the mean %.9g, expected %.9g", i, m,
                      variance[3 * i + c], expected);
    }
    cr_expect(constant > 10 && two_valued > 10, "%d constant and %d two-valued pixels", constant,
              two_valued);
    s.moments = false;
    float *plain = render_fixture_render(&f, s, NULL);
    cr_expect(memcmp(plain, rgb, sizeof rgb) == 0, "the moments changed the image");
    free(plain);
    /* Without moments there is no variance to read. */
    w = wavefront_create(f.dev, &f.scene, &f.buffers, &s, &err);
    cr_assert(w, "%s", err.message);
    cr_expect(!wavefront_read_variance(w, variance));
    wavefront_destroy(w);
    render_fixture_close(&f);
}

/* Where the pool comes from (render/pool_size.h): RenderSettings.pool_size, else PT_POOL_SIZE,
 * else the device's default (clamped to the render's samples); the default window is
 * WINDOW_PER_POOL pools, and PT_WINDOW_POOLS changes it. tests/test_pool_size.c checks the choice
 * itself; this checks that the wavefront passes it what the user set. */
Test(film, the_pool_comes_from_the_settings_then_the_environment, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open(&f, "scenes/cornell-box/scene.json", SIZE, SIZE);
    RenderSettings s = cornell; /* 32 spp of 64 x 64: 131072 samples */
    RenderStats stats;
    free(render_fixture_render(&f, s, &stats));
    cr_expect_eq(stats.config.pool_size, POOL_SIZE_CPU, "the CPU's default pool");
    cr_expect_eq(stats.config.window_size, WINDOW_PER_POOL * POOL_SIZE_CPU > 32u * PIXELS
                                               ? 32u * PIXELS : WINDOW_PER_POOL * POOL_SIZE_CPU);
    setenv("PT_POOL_SIZE", "2048", 1);
    free(render_fixture_render(&f, s, &stats));
    cr_expect_eq(stats.config.pool_size, 2048u, "PT_POOL_SIZE");
    cr_expect_eq(stats.config.window_size, WINDOW_PER_POOL * 2048u);
    setenv("PT_WINDOW_POOLS", "3", 1);
    free(render_fixture_render(&f, s, &stats));
    cr_expect_eq(stats.config.window_size, 3u * 2048u, "PT_WINDOW_POOLS");
    unsetenv("PT_WINDOW_POOLS");
    s.pool_size = 1024;
    free(render_fixture_render(&f, s, &stats));
    cr_expect_eq(stats.config.pool_size, 1024u, "the settings' pool wins over PT_POOL_SIZE");
    unsetenv("PT_POOL_SIZE");
    render_fixture_close(&f);
}
