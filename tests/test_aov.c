// SPDX-License-Identifier: MIT
/* test_aov.c: the AOV pass (cl/stages/render_aov.cl, render/aov.h). Albedo and normal follow a
 * smooth mirror (reflected) and smooth glass (refracted) to the first non-delta hit, as denoisers
 * expect; depth is the camera ray's own first hit, and a pixel no ray hits gets AOV_DEPTH_MISS.
 *
 * The scene, seen from z = 5 looking down -z: at z = 0 a mirror (x in [-3, 0]) and a glass pane
 * (x in [0, 3]), both |y| <= 1; behind the camera at z = 10 a large red wall facing -z (what the
 * mirror shows), at z = -5 a green wall facing +z for x in [-0.5, 8], |y| <= 2.5 (what the glass
 * shows). Above the panes on the left, camera rays meet nothing. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "render/aov.h"
#include "support.h"

#define WIDTH 32
#define HEIGHT 16

static const float red[3] = {0.8f, 0.1f, 0.1f}, green[3] = {0.1f, 0.7f, 0.2f};

static const char *write_scene(int max_depth)
{
    const char *dir = test_temp_dir();
    /* The JSON materials replace these (same names). */
    test_write_file(dir, "aov.mtl", "newmtl mirror\nnewmtl glass\nnewmtl red\nnewmtl green\n");
    test_write_file(dir, "aov.obj",
                    "mtllib aov.mtl\n"
                    "v -3 -1 0\nv 0 -1 0\nv 0 1 0\nv -3 1 0\n"      /* mirror, faces +z */
                    "v 0 -1 0\nv 3 -1 0\nv 3 1 0\nv 0 1 0\n"        /* glass, faces +z */
                    "v -20 -20 10\nv -20 20 10\nv 20 20 10\nv 20 -20 10\n" /* red, faces -z */
                    "v -0.5 -2.5 -5\nv 8 -2.5 -5\nv 8 2.5 -5\nv -0.5 2.5 -5\n" /* green, +z */
                    "usemtl mirror\nf 1 2 3\nf 1 3 4\n"
                    "usemtl glass\nf 5 6 7\nf 5 7 8\n"
                    "usemtl red\nf 9 10 11\nf 9 11 12\n"
                    "usemtl green\nf 13 14 15\nf 13 15 16\n");
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"eye\": [0, 0, 5], \"target\": [0, 0, 0], \"up\": [0, 1, 0], "
             "\"fov_y\": 40},\n"
             " \"render\": {\"spp\": 4, \"max_depth\": %d},\n"
             " \"materials\": {\"mirror\": {\"type\": \"conductor\", \"reflectance\": [0.9, 0.9, 0.9], "
             "\"roughness\": 0},\n"
             "   \"glass\": {\"type\": \"dielectric\", \"ior\": 1.5, \"roughness\": 0},\n"
             "   \"red\": {\"type\": \"diffuse\", \"albedo\": [%g, %g, %g]},\n"
             "   \"green\": {\"type\": \"diffuse\", \"albedo\": [%g, %g, %g]}},\n"
             " \"objects\": [{\"obj\": \"aov.obj\"}]}\n",
             max_depth, red[0], red[1], red[2], green[0], green[1], green[2]);
    return test_write_file(dir, "scene.json", json);
}

typedef struct {
    float albedo[WIDTH * HEIGHT * 3], normal[WIDTH * HEIGHT * 3], depth[WIDTH * HEIGHT];
} Layers;

static void render_layers(int max_depth, Layers *out)
{
    RenderFixture f;
    render_fixture_open(&f, write_scene(max_depth), WIDTH, HEIGHT);
    AovSettings settings = {.spp = 4, .max_depth = max_depth, .seed = 3};
    AovImages images = {out->albedo, out->normal, out->depth, NULL};
    Error err = {0};
    cr_assert(aov_render_layers(f.dev, &f.scene, &f.buffers, &settings, &images, &err), "%s",
              err.message);
    render_fixture_close(&f);
}

static void expect_rgb(const float *layer, int x, int y, const float want[3], const char *what)
{
    const float *got = &layer[3 * (y * WIDTH + x)];
    for (int c = 0; c < 3; c++)
        cr_expect_float_eq(got[c], want[c], 1e-4f, "%s at (%d, %d): (%g, %g, %g), want (%g, %g, %g)",
                           what, x, y, got[0], got[1], got[2], want[0], want[1], want[2]);
}

/* (8, 8) sees the mirror at x = -1.7; (24, 8) the glass at x = +1.8; (1, 0) nothing. */
Test(aov, albedo_and_normal_follow_mirror_and_glass, .timeout = 300)
{
    static Layers l;
    render_layers(8, &l);
    expect_rgb(l.albedo, 8, 8, red, "albedo seen in the mirror (the red wall's)");
    expect_rgb(l.albedo, 24, 8, green, "albedo seen through the glass (the green wall's)");
    const float toward_mirror[3] = {0, 0, -1}, toward_camera[3] = {0, 0, 1};
    expect_rgb(l.normal, 8, 8, toward_mirror, "normal seen in the mirror (the red wall's)");
    expect_rgb(l.normal, 24, 8, toward_camera, "normal seen through the glass (the green wall's)");
    /* Depth is the camera ray's: the mirror at 5 / cos of the pixel's angle, not the wall. */
    cr_expect(l.depth[8 * WIDTH + 8] > 5.0f && l.depth[8 * WIDTH + 8] < 6.0f, "mirror depth %g",
              l.depth[8 * WIDTH + 8]);
    const float black[3] = {0, 0, 0};
    expect_rgb(l.albedo, 1, 0, black, "albedo of a miss");
    expect_rgb(l.normal, 1, 0, black, "normal of a miss");
    cr_expect_eq(l.depth[1], AOV_DEPTH_MISS, "depth of a miss: %g", l.depth[1]);
}

/* max_depth 1: no segment is left to follow, so the delta surfaces' own values stand. */
Test(aov, the_walk_is_bounded_by_max_depth, .timeout = 300)
{
    static Layers l;
    render_layers(1, &l);
    const float mirror[3] = {0.9f, 0.9f, 0.9f}, white[3] = {1, 1, 1}, up_z[3] = {0, 0, 1};
    expect_rgb(l.albedo, 8, 8, mirror, "albedo of the mirror itself");
    expect_rgb(l.albedo, 24, 8, white, "albedo (tint) of the glass itself");
    expect_rgb(l.normal, 8, 8, up_z, "normal of the mirror itself");
}
