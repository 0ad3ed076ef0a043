// SPDX-License-Identifier: MIT
/* Alpha cut-out (shared/DESIGN.md "Materials": a ray passes through with probability 1 - opacity,
 * shadow rays too; a pass-through is not a bounce). A leaf card: a black 1 x 1 quad at y = 0.5
 * over a diffuse floor (albedo 0.8), its opacity a checker of 4 x 4 cells (mean 1/2), lit by a
 * directional light travelling along (2, -1, 0) so that the card's shadow falls beside it, at
 * x in [0.5, 1.5]; the camera looks straight down, max_depth 2 (direct light only). The shadow's
 * mean irradiance must be half the unshadowed one, and the card's pixels must show the lit floor
 * through its transparent cells (and black through its opaque ones). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "detail_fixture.h"

static const double PI = 3.14159265358979323846;
#define RES 64
#define CAM_H 5.0
#define TAN_HALF 0.4
#define CARD_Y 0.5
#define TEX 16 /* texels per side: cells of 4 x 4 texels, so bilinear filtering leaves flat centres */

static const char *write_scene(const char *dir)
{
    test_write_file(dir, "card.mtl", "newmtl floor\nKd 0.8 0.8 0.8\nnewmtl card\nKd 0 0 0\n");
    test_write_file(dir, "card.obj",
                    "mtllib card.mtl\n"
                    "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\n"
                    "v -0.5 0.5 -0.5\nv 0.5 0.5 -0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
                    "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\n"
                    "usemtl floor\nf 1/1 4/4 3/3\nf 1/1 3/3 2/2\n"
                    "usemtl card\nf 5/1 8/4 7/3\nf 5/1 7/3 6/2\n");
    char text[2048];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, %g, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], "
             "\"fov_y\": %.9g},\n \"film\": {\"width\": %d, \"height\": %d},\n"
             " \"objects\": [{\"obj\": \"card.obj\"}],\n"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [2, -1, 0], "
             "\"irradiance\": [1, 1, 1]}]}\n",
             CAM_H, 2.0 * atan(TAN_HALF) * 180.0 / PI, RES, RES);
    return test_write_file(dir, "scene.json", text);
}

/* Cell (cu, cv) of the card (u, v in quarters) is opaque when cu + cv is even. */
static bool cell_opaque(int cu, int cv) { return (cu + cv) % 2 == 0; }

/* ctx: a bool, true to put the checker in the base texture's alpha (an RGBA map_Kd, black rgb)
 * instead of an opacity texture's red channel. */
static void patch_card(Scene *scene, void *ctx)
{
    bool base_alpha = *(const bool *)ctx;
    float rgba[TEX * TEX * 4];
    for (int j = 0; j < TEX; j++) /* row 0 is the image's top, v = 1 */
        for (int i = 0; i < TEX; i++) {
            float o = cell_opaque(i / 4, (TEX - 1 - j) / 4) ? 1.0f : 0.0f;
            for (int c = 0; c < 4; c++)
                rgba[4 * (j * TEX + i) + c] = base_alpha ? (c == 3 ? o : 0.0f) : (c == 3 ? 1.0f : o);
        }
    Material *card = detail_material(scene, 2);
    cr_assert(card != detail_material(scene, 0));
    uint32_t tex = detail_add_texture(&scene->data.textures, TEX, TEX, rgba);
    card->tex[base_alpha ? MATERIAL_TEX_BASE : MATERIAL_TEX_OPACITY] = tex;
    card->flags |= MATERIAL_FLAG_CUTOUT | (base_alpha ? MATERIAL_FLAG_BASE_ALPHA : 0u);
}

/* The point at height y that pixel (i, j)'s centre sees; image x is +x, its top -z. */
static void pixel_at(int i, int j, double y, double *x, double *z)
{
    *x = (2.0 * (i + 0.5) / RES - 1.0) * TAN_HALF * (CAM_H - y);
    *z = -(1.0 - 2.0 * (j + 0.5) / RES) * TAN_HALF * (CAM_H - y);
}

static double floor_mean(const float *rgb, double x0, double x1, double z_half)
{
    double sum = 0.0;
    int n = 0;
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++) {
            double x, z;
            pixel_at(i, j, 0.0, &x, &z);
            if (x > x0 && x < x1 && fabs(z) < z_half)
                sum += rgb[3 * (j * RES + i) + 1], n++;
        }
    cr_assert(n > 20);
    return sum / n;
}

static float *render_card(int spp, bool base_alpha)
{
    RenderFixture f;
    detail_fixture_open(&f, write_scene(test_temp_dir()), patch_card, &base_alpha);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = spp, .max_depth = 2, .seed = 3}, NULL);
    render_fixture_close(&f);
    return rgb;
}

/* E cos = 1 / sqrt(5) on the floor, seen as 0.8 / pi of it. */
static double lit_floor(void) { return 0.8 / PI / sqrt(5.0); }

Test(cutout, shadow_of_a_half_open_card_is_half_as_dark, .timeout = 240)
{
    float *rgb = render_card(64, false);
    double lit = floor_mean(rgb, -1.8, -0.9, 0.3);
    cr_expect(fabs(lit - lit_floor()) < 0.01 * lit_floor(), "unshadowed floor %g, want %g", lit, lit_floor());
    /* The shadow's inner part x in [0.7, 1.3], |z| < 0.3 sees equal areas of open and opaque cells. */
    double shadow = floor_mean(rgb, 0.7, 1.3, 0.3);
    cr_expect(fabs(shadow / lit - 0.5) < 0.03, "shadow / unshadowed = %g, want 0.5", shadow / lit);
    free(rgb);
}

static void expect_floor_through_open_cells(bool base_alpha)
{
    float *rgb = render_card(16, base_alpha);
    double open_sum = 0.0, opaque_sum = 0.0;
    int n_open = 0, n_opaque = 0;
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++) {
            double x, z;
            pixel_at(i, j, CARD_Y, &x, &z);
            double u = x + 0.5, v = 0.5 - z; /* the card's uv */
            if (u <= 0.0 || u >= 1.0 || v <= 0.0 || v >= 1.0)
                continue;
            /* Only pixels near a cell's centre, where the filtered opacity is exactly 0 or 1. */
            double fu = u * 4.0 - floor(u * 4.0), fv = v * 4.0 - floor(v * 4.0);
            if (fabs(fu - 0.5) > 0.2 || fabs(fv - 0.5) > 0.2)
                continue;
            double value = rgb[3 * (j * RES + i) + 1];
            if (cell_opaque((int)(u * 4.0), (int)(v * 4.0)))
                opaque_sum += value, n_opaque++;
            else
                open_sum += value, n_open++;
        }
    cr_assert(n_open > 10 && n_opaque > 10, "%d open and %d opaque pixels", n_open, n_opaque);
    cr_expect(opaque_sum / n_opaque < 0.01 * lit_floor(), "opaque cells: %g", opaque_sum / n_opaque);
    cr_expect(fabs(open_sum / n_open - lit_floor()) < 0.02 * lit_floor(),
              "open cells: %g, the lit floor %g", open_sum / n_open, lit_floor());
    free(rgb);
}

Test(cutout, card_shows_the_floor_through_its_open_cells, .timeout = 240)
{
    expect_floor_through_open_cells(false);
}

Test(cutout, base_texture_alpha_cuts_out_too, .timeout = 240)
{
    expect_floor_through_open_cells(true);
}
