// SPDX-License-Identifier: MIT
/* Normal and bump maps (shared/DESIGN.md "Materials": tangent space, OpenGL convention, +x along
 * increasing u, +y along increasing v, mirrored uv islands mirrored; bump maps as pbrt-v4's
 * BumpMap). Two diffuse quads (albedo 0.8) at y = 0 seen from straight above, max_depth 2, lit by
 * one directional light 45 degrees off the vertical: a pixel is 0.8 / pi x E x cos(light, n') with
 * n' the mapped normal. Quad A (x in [-2, 0]) has u along +x, quad B (x in [0, 2]) is its mirror
 * image, u along -x; both have v along -z. A map tilting toward +u must brighten A from +x and B
 * from -x; one tilting toward +v brightens both from -z (so a flipped green channel, or a
 * bitangent that ignores B's mirroring, fails). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "detail_fixture.h"

static const double PI = 3.14159265358979323846;
#define RES 32
#define CAM_H 4.0
#define TAN_HALF 0.5

static const char *write_scene(const char *dir, const double light_dir[3])
{
    test_write_file(dir, "quads.obj",
                    "v -2 0 -1\nv 0 0 -1\nv 0 0 1\nv -2 0 1\n"
                    "v 0 0 -1\nv 2 0 -1\nv 2 0 1\nv 0 0 1\n"
                    "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n"
                    "vt 1 1\nvt 0 1\nvt 0 0\nvt 1 0\n"
                    "f 1/1 4/4 3/3\nf 1/1 3/3 2/2\nf 5/5 8/8 7/7\nf 5/5 7/7 6/6\n");
    char text[2048];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, %g, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], "
             "\"fov_y\": %.9g},\n \"film\": {\"width\": %d, \"height\": %d},\n"
             " \"objects\": [{\"obj\": \"quads.obj\"}],\n"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [%.9g, %.9g, %.9g], "
             "\"irradiance\": [1, 1, 1]}]}\n",
             CAM_H, 2.0 * atan(TAN_HALF) * 180.0 / PI, RES, RES, light_dir[0], light_dir[1],
             light_dir[2]);
    return test_write_file(dir, "scene.json", text);
}

typedef struct {
    int slot;        /* MATERIAL_TEX_NORMAL or MATERIAL_TEX_BUMP */
    uint32_t width;  /* texels along u (one row) */
    const float *rgba;
    float bump_scale;
} MapPatch;

static void patch_map(Scene *scene, void *ctx)
{
    const MapPatch *m = ctx;
    uint32_t tex = detail_add_texture(&scene->data.textures, m->width, 1, m->rgba);
    for (uint32_t t = 0; t < 4; t++) { /* one material: both quads */
        Material *mat = detail_material(scene, t);
        mat->tex[m->slot] = tex;
        mat->bump_scale = m->bump_scale;
    }
}

/* The mean of the pixels that see x in [x0, x1], z in [-0.7, 0.7] (well inside one quad). */
static double region_mean(const float *rgb, double x0, double x1)
{
    double sum = 0.0;
    int n = 0;
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++) {
            double x = (2.0 * (i + 0.5) / RES - 1.0) * TAN_HALF * CAM_H;
            double z = -(1.0 - 2.0 * (j + 0.5) / RES) * TAN_HALF * CAM_H;
            if (x > x0 && x < x1 && fabs(z) < 0.7)
                sum += rgb[3 * (j * RES + i) + 1], n++;
        }
    cr_assert(n > 10);
    return sum / n;
}

/* Renders with the light travelling along dir and checks both quads against their mapped normals. */
static void expect_lit(MapPatch *patch, const double dir[3], const double n_a[3],
                       const double n_b[3], const char *what)
{
    const char *scene = write_scene(test_temp_dir(), dir);
    RenderFixture f;
    detail_fixture_open(&f, scene, patch_map, patch);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 2, .seed = 1}, NULL);
    render_fixture_close(&f);
    const double *normals[2] = {n_a, n_b};
    const double ranges[2][2] = {{-1.7, -0.3}, {0.3, 1.7}};
    for (int q = 0; q < 2; q++) {
        const double *n = normals[q];
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double c = -(dir[0] * n[0] + dir[1] * n[1] + dir[2] * n[2]) / len;
        double want = 0.8 / PI * fmax(c, 0.0);
        double got = region_mean(rgb, ranges[q][0], ranges[q][1]);
        cr_expect(fabs(got - want) < 0.01 * 0.8 / PI, "%s, quad %c: %g, want %g (cos %g)", what,
                  "AB"[q], got, want, c);
    }
    free(rgb);
}

static const double S45 = 0.70710678118654752;
static const double FROM_PLUS_X[3] = {-0.70710678118654752, -0.70710678118654752, 0};
static const double FROM_MINUS_X[3] = {0.70710678118654752, -0.70710678118654752, 0};
static const double FROM_MINUS_Z[3] = {0, -0.70710678118654752, 0.70710678118654752};
static const double FROM_PLUS_Z[3] = {0, -0.70710678118654752, -0.70710678118654752};

Test(normal_map, tilt_toward_plus_u_brightens_the_side_lit_from_plus_u, .timeout = 240)
{
    double a = 30.0 * PI / 180.0;
    float texel[4] = {(float)(0.5 * sin(a) + 0.5), 0.5f, (float)(0.5 * cos(a) + 0.5), 1.0f};
    MapPatch patch = {MATERIAL_TEX_NORMAL, 1, texel, 1.0f};
    double n_a[3] = {sin(a), cos(a), 0}, n_b[3] = {-sin(a), cos(a), 0};
    (void)S45;
    expect_lit(&patch, FROM_PLUS_X, n_a, n_b, "+u map, light from +x");
    expect_lit(&patch, FROM_MINUS_X, n_a, n_b, "+u map, light from -x");
}

Test(normal_map, tilt_toward_plus_v_brightens_the_side_lit_from_plus_v, .timeout = 240)
{
    double a = 30.0 * PI / 180.0;
    float texel[4] = {0.5f, (float)(0.5 * sin(a) + 0.5), (float)(0.5 * cos(a) + 0.5), 1.0f};
    MapPatch patch = {MATERIAL_TEX_NORMAL, 1, texel, 1.0f};
    /* v grows toward -z on both quads (B is mirrored in u only). */
    double n[3] = {0, cos(a), -sin(a)};
    expect_lit(&patch, FROM_MINUS_Z, n, n, "+v map, light from -z");
    expect_lit(&patch, FROM_PLUS_Z, n, n, "+v map, light from +z");
}

Test(normal_map, bump_scale_scales_the_maps_xy, .timeout = 240)
{
    /* -bm 0.5 halves the tangent part: (0.5 sin a, cos a) normalised. */
    double a = 40.0 * PI / 180.0;
    float texel[4] = {(float)(0.5 * sin(a) + 0.5), 0.5f, (float)(0.5 * cos(a) + 0.5), 1.0f};
    MapPatch patch = {MATERIAL_TEX_NORMAL, 1, texel, 0.5f};
    double n_a[3] = {0.5 * sin(a), cos(a), 0}, n_b[3] = {-0.5 * sin(a), cos(a), 0};
    expect_lit(&patch, FROM_PLUS_X, n_a, n_b, "+u map at bump_scale 0.5, light from +x");
}

Test(bump_map, a_ramp_tilts_the_surface_by_its_slope, .timeout = 240)
{
    /* Height = u over 64 texels: with bump_scale s the surface rises s over quad A's 2 units of x
     * (toward +x), so its normal is (-s/2, 1, 0); B's u runs the other way: (s/2, 1, 0). */
    float ramp[64 * 4];
    for (int i = 0; i < 64; i++)
        for (int c = 0; c < 4; c++)
            ramp[4 * i + c] = c == 3 ? 1.0f : (float)i / 64.0f;
    double s = 2.0 * tan(20.0 * PI / 180.0);
    MapPatch patch = {MATERIAL_TEX_BUMP, 64, ramp, (float)s};
    double n_a[3] = {-s / 2.0, 1.0, 0}, n_b[3] = {s / 2.0, 1.0, 0};
    expect_lit(&patch, FROM_PLUS_X, n_a, n_b, "ramp bump, light from +x");
    expect_lit(&patch, FROM_MINUS_X, n_a, n_b, "ramp bump, light from -x");
}
