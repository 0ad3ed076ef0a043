// SPDX-License-Identifier: MIT
/* render/bloom.h on the test device (PoCL): the kernel sums to 1 (a single bright pixel's light
 * is all there after the stage, also at a corner), its profile is the Gaussian of sigma = R / 3,
 * strength 0 and images below the threshold come back bit for bit, bad values are refused; and
 * `pt render --bloom` changes the PNG but not the EXR beside it. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "io/image_io.h"
#include "render/bloom.h"
#include "support.h"

static Device *dev;
static void open_device(void) { dev = test_device(); }
static void close_device(void) { test_device_release(dev); }

TestSuite(bloom, .init = open_device, .fini = close_device);

static float *image(int width, int height)
{
    float *rgb = calloc((size_t)width * (size_t)height * 3, sizeof(float));
    cr_assert(rgb);
    return rgb;
}

static void channel_sums(const float *rgb, int width, int height, double sums[3])
{
    sums[0] = sums[1] = sums[2] = 0.0;
    for (size_t i = 0; i < (size_t)width * (size_t)height; i++)
        for (int c = 0; c < 3; c++)
            sums[c] += rgb[3 * i + (size_t)c];
}

/* Blooms rgb in place and expects each channel's total unchanged (to float rounding). */
static void bloom_keeping_the_totals(float *rgb, int width, int height, float strength,
                                     float radius)
{
    double before[3], after[3];
    channel_sums(rgb, width, height, before);
    Error err = {0};
    cr_assert(bloom_apply(dev, rgb, width, height, strength, radius, &err), "%s", err.message);
    channel_sums(rgb, width, height, after);
    for (int c = 0; c < 3; c++)
        cr_expect(fabs(after[c] - before[c]) <= 1e-5 * before[c],
                  "channel %d: %.7g before, %.7g after", c, before[c], after[c]);
}

/* The bright part as bloom.h defines it, in double. */
static void bright(const float c[3], double out[3])
{
    double luminance = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    for (int k = 0; k < 3; k++)
        out[k] = luminance > BLOOM_THRESHOLD ? c[k] * (luminance - BLOOM_THRESHOLD) / luminance
                                             : 0.0;
}

/* A point of light in the middle: the output is the input less strength x its bright part, plus
 * that light spread as g(dx) g(dy), g the normalised Gaussian of sigma = radius / 3 over
 * |k| <= ceil(radius), computed here from its definition. The totals are unchanged. */
Test(bloom, a_point_spreads_as_the_gaussian_and_keeps_its_light)
{
    const int width = 61, height = 41, cx = 30, cy = 20;
    const float radius = 6.0f, strength = 0.6f, point[3] = {100.0f, 50.0f, 25.0f};
    float *rgb = image(width, height);
    memcpy(rgb + 3 * (cy * width + cx), point, sizeof point);
    bloom_keeping_the_totals(rgb, width, height, strength, radius);
    double b[3], g[7], norm = 0.0;
    for (int k = -6; k <= 6; k++)
        norm += exp(-0.5 * (k / 2.0) * (k / 2.0));
    for (int k = 0; k <= 6; k++)
        g[k] = exp(-0.5 * (k / 2.0) * (k / 2.0)) / norm;
    bright(point, b);
    double worst = 0.0;
    for (int y = 0; y < height; y++)
        for (int x = 0; x < width; x++) {
            int dx = abs(x - cx), dy = abs(y - cy);
            double spread = dx <= 6 && dy <= 6 ? g[dx] * g[dy] : 0.0;
            for (int c = 0; c < 3; c++) {
                double expected = strength * b[c] * spread;
                if (dx == 0 && dy == 0)
                    expected += point[c] - strength * b[c];
                double got = rgb[3 * (y * width + x) + c];
                worst = fmax(worst, fabs(got - expected));
                cr_assert(fabs(got - expected) <= 1e-5 * point[c],
                          "(%d, %d)[%d] = %.9g, expected %.9g", x, y, c, got, expected);
            }
        }
    cr_log_info("largest difference from the Gaussian: %g", worst);
    free(rgb);
}

/* A point in a corner: the mirrored borders keep all of its light in the image. */
Test(bloom, a_point_in_the_corner_keeps_its_light)
{
    const int width = 37, height = 23;
    float *rgb = image(width, height);
    rgb[0] = rgb[1] = rgb[2] = 40.0f;
    rgb[3 * (size_t)(width * height - 1)] = 30.0f; /* the opposite corner, red only */
    bloom_keeping_the_totals(rgb, width, height, 1.0f, 15.0f);
    cr_expect(rgb[0] < 40.0f && rgb[3 * 5] > 0.0f, "the light spread: %g, %g", rgb[0], rgb[15]);
    free(rgb);
}

static float *random_image(int width, int height, float scale)
{
    float *rgb = image(width, height);
    unsigned state = 12345u;
    for (size_t i = 0; i < (size_t)width * (size_t)height * 3; i++) {
        state = state * 1664525u + 1013904223u;
        float u = (float)(state >> 8) / 16777216.0f;
        rgb[i] = scale * u * u * u; /* mostly dark, some bright */
    }
    return rgb;
}

/* A noisy image with many bright pixels, the default radius: totals unchanged. */
Test(bloom, a_noisy_image_keeps_its_light)
{
    const int width = 160, height = 90;
    float *rgb = random_image(width, height, 20.0f);
    bloom_keeping_the_totals(rgb, width, height, 0.8f, 0.0f);
    free(rgb);
}

/* Strength 0 is the identity, and so is any strength on an image with nothing above the
 * threshold: bit for bit. */
Test(bloom, strength_zero_and_dim_images_are_left_as_they_are)
{
    const int width = 64, height = 48;
    size_t bytes = (size_t)width * height * 3 * sizeof(float);
    float *rgb = random_image(width, height, 20.0f), *copy = malloc(bytes);
    cr_assert(copy);
    memcpy(copy, rgb, bytes);
    Error err = {0};
    cr_assert(bloom_apply(dev, rgb, width, height, 0.0f, 8.0f, &err), "%s", err.message);
    cr_expect(memcmp(rgb, copy, bytes) == 0, "strength 0 changed the image");
    free(rgb);
    rgb = random_image(width, height, 0.99f); /* luminance below 1 everywhere */
    memcpy(copy, rgb, bytes);
    cr_assert(bloom_apply(dev, rgb, width, height, 1.0f, 8.0f, &err), "%s", err.message);
    cr_expect(memcmp(rgb, copy, bytes) == 0, "an image below the threshold changed");
    free(rgb);
    free(copy);
}

Test(bloom, kernel_weights_sum_to_one_and_default_radius)
{
    float weights[(int)BLOOM_MAX_RADIUS + 1];
    const float radii[] = {0.5f, 1.0f, 2.5f, 44.0f, 1024.0f};
    for (size_t i = 0; i < sizeof radii / sizeof *radii; i++) {
        int taps = bloom_weights(radii[i], weights, (int)BLOOM_MAX_RADIUS + 1);
        cr_expect_eq(taps, (int)ceilf(radii[i]));
        double sum = weights[0];
        for (int k = 1; k <= taps; k++) {
            sum += 2.0 * weights[k];
            cr_expect(weights[k] <= weights[k - 1], "radius %g: not decreasing at %d", radii[i], k);
        }
        cr_expect(fabs(sum - 1.0) <= 1e-6, "radius %g: the kernel sums to %.9g", radii[i], sum);
    }
    cr_expect(fabsf(bloom_default_radius(3840, 2160) - 44.06f) < 0.01f, "%g",
              bloom_default_radius(3840, 2160));
    cr_expect_eq(bloom_default_radius(32, 32), 1.0f);
}

Test(bloom, bad_values_are_refused)
{
    float rgb[3] = {5, 5, 5};
    Error err = {0};
    cr_expect_not(bloom_apply(dev, rgb, 1, 1, 1.5f, 3.0f, &err));
    cr_expect(err.code == ERR_SETTINGS && strstr(err.message, "strength"), "%s", err.message);
    err = (Error){0}; /* error_set keeps the first error */
    cr_expect_not(bloom_apply(dev, rgb, 1, 1, NAN, 3.0f, &err));
    err = (Error){0};
    cr_expect_not(bloom_apply(dev, rgb, 1, 1, 0.5f, 5000.0f, &err));
    cr_expect(strstr(err.message, "radius"), "%s", err.message);
    cr_expect_not(bloom_apply(dev, rgb, 0, 1, 0.5f, 3.0f, &err));
    cr_expect(rgb[0] == 5.0f, "a refused call left the image as it was");
}

static float *read_exr(const char *path, int *width, int *height)
{
    float *rgb = NULL;
    Error err = {0};
    cr_assert(image_read_exr(path, &rgb, width, height, &err), "%s", err.message);
    return rgb;
}

/* --bloom with --preview: the EXR holds the same pixels as without it (linear, no bloom); the PNG
 * is different. */
Test(bloom, pt_render_blooms_the_png_and_not_the_exr)
{
    const char *dir = test_temp_dir();
    char cmd[2048], exr[2][600], png[2][600];
    for (int i = 0; i < 2; i++) {
        snprintf(exr[i], sizeof exr[i], "%s/%s.exr", dir, i ? "bloom" : "plain");
        snprintf(png[i], sizeof png[i], "%s/%s.png", dir, i ? "bloom" : "plain");
        snprintf(cmd, sizeof cmd,
                 "'%s' render scenes/cornell-box --width 48 --height 36 --spp 2 -q -o '%s' "
                 "--preview %s >/dev/null",
                 test_pt_bin(), exr[i], i ? "--bloom 1,6" : "");
        int status = system(cmd);
        cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s failed", cmd);
    }
    int w0, h0, w1, h1;
    float *plain = read_exr(exr[0], &w0, &h0), *bloomed = read_exr(exr[1], &w1, &h1);
    cr_assert(w0 == 48 && h0 == 36 && w1 == w0 && h1 == h0);
    cr_expect(memcmp(plain, bloomed, (size_t)w0 * h0 * 3 * sizeof(float)) == 0,
              "--bloom changed the EXR");
    size_t size[2];
    char *bytes[2] = {test_read_file(png[0], &size[0]), test_read_file(png[1], &size[1])};
    cr_assert(bytes[0] && bytes[1]);
    cr_expect(size[0] != size[1] || memcmp(bytes[0], bytes[1], size[0]) != 0,
              "--bloom did not change the PNG");
    free(plain), free(bloomed), free(bytes[0]), free(bytes[1]);
}
