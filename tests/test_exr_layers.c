// SPDX-License-Identifier: MIT
/* test_exr_layers.c: the multi-layer EXR (shared/DESIGN.md "Film and outputs"), read back with
 * OpenEXR's C API (exr_inspect.h): the writer's channels, types, values and attributes, and
 * `pt render --aov all`'s file: the layer names, 32-bit float channels, the metadata, and beauty
 * bits equal to those of the same render without AOVs. */
#define _XOPEN_SOURCE 700
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "base/version.h"
#include "exr_inspect.h"
#include "io/image_io.h"
#include "render/aov.h"
#include "support.h"

/* ---- the writer ------------------------------------------------------------------------------ */

Test(exr_layers, writer_sorts_channels_keeps_values_and_sets_attributes)
{
    enum { W = 5, H = 3, N = W * H };
    float rgb[3 * N], albedo[3 * N], depth[N], spp[N];
    for (int i = 0; i < 3 * N; i++)
        rgb[i] = 0.25f * (float)i, albedo[i] = 1.0f / (float)(i + 1);
    for (int i = 0; i < N; i++)
        depth[i] = 10.0f + (float)i, spp[i] = (float)(i % 4);
    depth[2] = INFINITY, depth[3] = NAN; /* the last guard: written as 0 */
    const ImageLayer layers[] = {{"spp", "Y", spp}, {"albedo", "RGB", albedo}, {"depth", "Z", depth}};
    const ImageAttribute attributes[] = {
        {.name = "spp", .type = IMAGE_ATTR_INT, .int_value = 27},
        {.name = "render_time", .type = IMAGE_ATTR_FLOAT, .float_value = 1.5f},
        {.name = "scene", .type = IMAGE_ATTR_STRING, .string_value = "scenes/x.json"},
    };
    ExrImage image = {rgb, W, H, layers, 3, attributes, 3, NULL};
    const char *path = test_write_file(test_temp_dir(), "layers.exr", "");
    Error err = {0};
    cr_assert(image_write_exr_layers(path, &image, &err), "%s", err.message);

    ExrInspect f;
    exr_inspect_open(&f, path);
    cr_assert_eq(f.width, W);
    cr_assert_eq(f.height, H);
    /* OpenEXR keeps the list sorted by name (bytewise: capitals first). */
    const char *expected[] = {"B", "G", "R", "albedo.B", "albedo.G", "albedo.R", "depth.Z", "spp.Y"};
    cr_assert_eq(f.channel_count, 8);
    for (int i = 0; i < 8; i++) {
        cr_expect_str_eq(f.names[i], expected[i]);
        cr_expect_eq(f.types[i], EXR_PIXEL_FLOAT, "%s is not FLOAT", f.names[i]);
    }
    exr_compression_t compression;
    cr_assert_eq(exr_get_compression(f.ctxt, 0, &compression), EXR_ERR_SUCCESS);
    cr_expect_eq(compression, EXR_COMPRESSION_ZIP);
    cr_expect_eq(exr_inspect_int(&f, "spp"), 27);
    cr_expect_eq(exr_inspect_float(&f, "render_time"), 1.5f);
    cr_expect_str_eq(exr_inspect_string(&f, "scene"), "scenes/x.json");

    float *g = exr_inspect_channel(&f, "G"), *albedo_b = exr_inspect_channel(&f, "albedo.B");
    float *z = exr_inspect_channel(&f, "depth.Z"), *y = exr_inspect_channel(&f, "spp.Y");
    for (int i = 0; i < N; i++) {
        cr_expect_eq(g[i], rgb[3 * i + 1], "G[%d]", i);
        cr_expect_eq(albedo_b[i], albedo[3 * i + 2], "albedo.B[%d]", i);
        cr_expect_eq(z[i], i == 2 || i == 3 ? 0.0f : depth[i], "depth.Z[%d]", i);
        cr_expect_eq(y[i], spp[i], "spp.Y[%d]", i);
    }
    free(g), free(albedo_b), free(z), free(y);
    exr_inspect_close(&f);
}

/* More lines than one batch of the writer's parallel encoding (32 chunks of 16 lines), and a last
 * chunk that is not full: every line of every channel reads back where it was written. */
Test(exr_layers, tall_images_keep_every_line_across_encoding_batches)
{
    enum { W = 7, H = 32 * 16 * 2 + 5, N = W * H };
    float *rgb = malloc(3 * N * sizeof *rgb), *depth = malloc(N * sizeof *depth);
    cr_assert(rgb && depth);
    for (int i = 0; i < 3 * N; i++)
        rgb[i] = (float)i * 0.5f;
    for (int i = 0; i < N; i++)
        depth[i] = (float)(N - i);
    const ImageLayer layers[] = {{"depth", "Z", depth}};
    ExrImage image = {rgb, W, H, layers, 1, NULL, 0, NULL};
    const char *path = test_write_file(test_temp_dir(), "tall.exr", "");
    Error err = {0};
    cr_assert(image_write_exr_layers(path, &image, &err), "%s", err.message);
    ExrInspect f;
    exr_inspect_open(&f, path);
    cr_assert_eq(f.height, H);
    float *r = exr_inspect_channel(&f, "R"), *b = exr_inspect_channel(&f, "B");
    float *z = exr_inspect_channel(&f, "depth.Z");
    int wrong = 0;
    for (int i = 0; i < N; i++)
        wrong += r[i] != rgb[3 * i] || b[i] != rgb[3 * i + 2] || z[i] != depth[i];
    cr_expect_eq(wrong, 0, "%d of %d pixels differ", wrong, N);
    free(r), free(b), free(z), free(rgb), free(depth);
    exr_inspect_close(&f);
}

Test(exr_layers, layer_without_a_name_is_an_output_error)
{
    float rgb[3] = {0}, one[1] = {0};
    const ImageLayer layers[] = {{"", "Y", one}};
    ExrImage image = {.rgb = rgb, .width = 1, .height = 1, .layers = layers, .layer_count = 1};
    const char *dir = test_temp_dir();
    char path[300];
    snprintf(path, sizeof path, "%s/bad.exr", dir);
    Error err = {0};
    cr_assert_not(image_write_exr_layers(path, &image, &err));
    cr_expect_eq(err.code, ERR_OUTPUT);
    cr_expect(strstr(err.message, path), "%s", err.message);
    FILE *left = fopen(path, "rb");
    cr_expect_null(left, "a file was left behind");
    if (left)
        fclose(left);
}

/* ---- pt render --aov ------------------------------------------------------------------------- */

/* Runs pt with args (stdout and stderr to files); returns the exit status, stderr in err. */
static int run_pt(const char *args, char *err, size_t size)
{
    char err_path[300], cmd[2048];
    snprintf(err_path, sizeof err_path, "%s/stderr", test_temp_dir());
    snprintf(cmd, sizeof cmd, "'%s' %s >/dev/null 2>'%s'", test_pt_bin(), args, err_path);
    int status = system(cmd);
    char *text = test_read_file(err_path, NULL);
    snprintf(err, size, "%s", text ? text : "");
    free(text);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

#define RENDER_ARGS "render scenes/cornell-box --device cpu --width 16 --height 16 --spp 3 --seed 7"

static float *read_plane(const ExrInspect *f, const char *name) { return exr_inspect_channel(f, name); }

Test(exr_layers, pt_render_aov_all_writes_every_layer_and_the_metadata, .timeout = 600)
{
    const char *dir = test_temp_dir();
    char with[400], without[400], args[1200], err[8192];
    snprintf(with, sizeof with, "%s/with.exr", dir);
    snprintf(without, sizeof without, "%s/without.exr", dir);
    snprintf(args, sizeof args, RENDER_ARGS " --aov all -o '%s'", with);
    cr_assert_eq(run_pt(args, err, sizeof err), 0, "%s", err);
    snprintf(args, sizeof args, RENDER_ARGS " -o '%s'", without);
    cr_assert_eq(run_pt(args, err, sizeof err), 0, "%s", err);

    ExrInspect f, plain;
    exr_inspect_open(&f, with);
    exr_inspect_open(&plain, without);
    const char *expected[] = {"A",        "B",        "G",        "R",        "albedo.B", "albedo.G",
                              "albedo.R", "depth.Z",  "normal.X", "normal.Y", "normal.Z",
                              "spp.Y",    "variance.B", "variance.G", "variance.R"};
    int count = (int)(sizeof expected / sizeof expected[0]);
    cr_assert_eq(f.channel_count, count);
    for (int i = 0; i < count; i++) {
        cr_expect_str_eq(f.names[i], expected[i]);
        cr_expect_eq(f.types[i], EXR_PIXEL_FLOAT, "%s is not FLOAT", f.names[i]);
    }
    cr_expect_eq(plain.channel_count, 4, "without --aov: R, G, B and the coverage A only");

    /* The AOVs must not change the beauty: the same bits as the render without them. */
    const char *beauty[] = {"R", "G", "B"};
    size_t n = (size_t)f.width * (size_t)f.height;
    double sum = 0.0;
    for (int c = 0; c < 3; c++) {
        float *a = read_plane(&f, beauty[c]), *b = read_plane(&plain, beauty[c]);
        cr_expect_eq(memcmp(a, b, n * sizeof *a), 0, "channel %s differs with --aov all", beauty[c]);
        for (size_t i = 0; i < n; i++)
            sum += a[i];
        free(a), free(b);
    }
    cr_expect_gt(sum, 0.0, "the beauty is black");

    cr_expect_eq(exr_inspect_int(&f, "spp"), 3);
    cr_expect_eq(exr_inspect_int(&f, "spp_requested"), 3);
    cr_expect_eq(exr_inspect_int(&f, "partial"), 0);
    cr_expect_str_eq(exr_inspect_string(&f, "seed"), "7");
    cr_expect_str_eq(exr_inspect_string(&f, "pt_version"), PT_VERSION);
    cr_expect_str_eq(exr_inspect_string(&f, "scene"), "scenes/cornell-box");
    cr_expect_gt(exr_inspect_float(&f, "render_time"), 0.0f);
    cr_expect(strstr(exr_inspect_string(&f, "devices"), "Portable Computing Language"), "%s",
              exr_inspect_string(&f, "devices"));
    /* The scene's camera, in the form --camera takes. */
    cr_expect_str_eq(exr_inspect_string(&f, "camera"),
                     "{\"eye\": [0, 1, 3.9], \"target\": [0, 1, 0], \"up\": [0, 1, 0], "
                     "\"fov_y\": 39.3, \"aperture\": 0, \"focus_distance\": 0}");

    /* Every pixel got the 3 samples; every depth is finite (a miss is AOV_DEPTH_MISS); the middle
     * of the view is the box's inside: hits, with an albedo and a mean of unit normals (at an
     * edge between two faces, of 3 samples, at least sqrt(5) / 3). */
    float *spp = read_plane(&f, "spp.Y"), *depth = read_plane(&f, "depth.Z");
    float *nx = read_plane(&f, "normal.X"), *ny = read_plane(&f, "normal.Y"),
          *nz = read_plane(&f, "normal.Z"), *albedo_r = read_plane(&f, "albedo.R");
    for (size_t i = 0; i < n; i++) {
        cr_expect_eq(spp[i], 3.0f, "spp.Y[%zu] = %g", i, spp[i]);
        cr_expect(depth[i] > 1.0f && depth[i] <= AOV_DEPTH_MISS, "depth.Z[%zu] = %g", i, depth[i]);
        int x = (int)(i % (size_t)f.width), y = (int)(i / (size_t)f.width);
        if (x < f.width / 4 || x >= 3 * f.width / 4 || y < f.height / 4 || y >= 3 * f.height / 4)
            continue;
        cr_expect(depth[i] < 10.0f, "depth.Z[%zu] = %g", i, depth[i]);
        float len = sqrtf(nx[i] * nx[i] + ny[i] * ny[i] + nz[i] * nz[i]);
        cr_expect(len > 0.5f && len < 1.0001f, "|normal[%zu]| = %g", i, len);
        cr_expect(albedo_r[i] > 0.0f && albedo_r[i] <= 1.0f, "albedo.R[%zu] = %g", i, albedo_r[i]);
    }
    free(spp), free(depth), free(nx), free(ny), free(nz), free(albedo_r);
    exr_inspect_close(&f);
    exr_inspect_close(&plain);
}

Test(exr_layers, aov_with_a_png_output_is_refused, .timeout = 120)
{
    char args[600], err[4096], png[400];
    snprintf(png, sizeof png, "%s/x.png", test_temp_dir());
    snprintf(args, sizeof args, RENDER_ARGS " --aov albedo -o '%s'", png);
    cr_expect_eq(run_pt(args, err, sizeof err), 1, "%s", err);
    cr_expect(!strncmp(err, "pt: ", 4) && strstr(err, "--aov") && strstr(err, ".exr"), "%s", err);
    cr_expect(strchr(err, '\n') && strchr(err, '\n')[1] == '\0', "one line: %s", err);
    FILE *written = fopen(png, "rb");
    cr_expect_null(written, "a PNG was written");
    if (written)
        fclose(written);
}
