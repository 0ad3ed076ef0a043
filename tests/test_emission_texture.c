// SPDX-License-Identifier: MIT
/* Emission textures (shared/DESIGN.md "Materials": emission colour or texture times
 * emission_strength; "Lights": emitters picked in proportion to their power). A 1 x 1 lamp facing
 * down at y = 1 whose emission texture is white on its -x half and black on its +x half, plus a
 * small plain lamp, over a diffuse floor seen from below the lamps, max_depth 2. Next-event
 * estimation with MIS and BSDF sampling alone must agree block by block (both look the texture up
 * where the light is: light_sample at its sampled point, emission_seen at the hit), the floor must
 * be brighter under the white half, and the light table must weigh the lamp by area x luminance x
 * strength x the texture's mean luminance (1/2). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <stb_image_write.h>

#include "scene/lights.h"
#include "support.h"

static const double PI = 3.14159265358979323846;
#define RES 32
#define BLOCK 8
#define STRENGTH 4.0

static const char *write_scene(const char *dir)
{
    /* 16 x 1: texels 0..7 white, 8..15 black (u < 1/2 lit); bilinear filtering keeps the mean 1/2. */
    unsigned char half[16 * 3];
    for (int i = 0; i < 16; i++)
        half[3 * i] = half[3 * i + 1] = half[3 * i + 2] = i < 8 ? 255 : 0;
    char path[600];
    snprintf(path, sizeof path, "%s/half.png", dir);
    cr_assert(stbi_write_png(path, 16, 1, 3, half, 16 * 3));
    test_write_file(dir, "floor.obj", "v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 4 3\nf 1 3 2\n");
    /* Counter-clockwise seen from below: the lamps emit downward. u runs along +x. */
    test_write_file(dir, "lamp.obj",
                    "v -0.5 1 -0.5\nv 0.5 1 -0.5\nv 0.5 1 0.5\nv -0.5 1 0.5\n"
                    "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    test_write_file(dir, "lamp2.obj",
                    "v 1 1 -0.2\nv 1.4 1 -0.2\nv 1.4 1 0.2\nv 1 1 0.2\nf 1 2 3\nf 1 3 4\n");
    char text[2048];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, 0.9, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], "
             "\"fov_y\": %.9g},\n \"film\": {\"width\": %d, \"height\": %d},\n"
             " \"textures\": {\"half\": {\"file\": \"half.png\", \"encoding\": \"linear\"}},\n"
             " \"materials\": {\"lamp\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": \"half\", "
             "\"emission_strength\": %g},\n"
             "               \"lamp2\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": [2, 2, 2]}},\n"
             " \"objects\": [{\"obj\": \"floor.obj\"}, {\"obj\": \"lamp.obj\", \"material\": \"lamp\"},\n"
             "             {\"obj\": \"lamp2.obj\", \"material\": \"lamp2\"}]}\n",
             2.0 * atan(2.0) * 180.0 / PI, RES, RES, STRENGTH);
    return test_write_file(dir, "scene.json", text);
}

static float *render(const char *scene, int spp, bool no_nee)
{
    RenderFixture f;
    render_fixture_open(&f, scene, 0, 0);
    float *rgb = render_fixture_render(
        &f, (RenderSettings){.spp = spp, .max_depth = 2, .seed = 7, .no_nee = no_nee}, NULL);
    render_fixture_close(&f);
    return rgb;
}

static double block_mean(const float *rgb, int bx, int by)
{
    double sum = 0.0;
    for (int j = by * BLOCK; j < (by + 1) * BLOCK; j++)
        for (int i = bx * BLOCK; i < (bx + 1) * BLOCK; i++)
            sum += rgb[3 * (j * RES + i) + 1];
    return sum / (BLOCK * BLOCK);
}

Test(emission_texture, nee_with_mis_and_bsdf_sampling_agree, .timeout = 300)
{
    const char *scene = write_scene(test_temp_dir());
    float *nee = render(scene, 64, false);
    float *bsdf = render(scene, 1024, true);
    int n = RES / BLOCK;
    double peak = 0.0;
    for (int by = 0; by < n; by++)
        for (int bx = 0; bx < n; bx++)
            peak = fmax(peak, block_mean(nee, bx, by));
    cr_assert(peak > 0.0);
    for (int by = 0; by < n; by++)
        for (int bx = 0; bx < n; bx++) {
            double a = block_mean(nee, bx, by), b = block_mean(bsdf, bx, by);
            cr_expect(fabs(a - b) < 0.04 * peak, "block (%d, %d): NEE+MIS %g, BSDF-only %g (peak %g)",
                      bx, by, a, b, peak);
        }
    /* Under the white half (x < 0: the left middle blocks) against under the black half. */
    double left = block_mean(nee, 1, 1) + block_mean(nee, 1, 2);
    double right = block_mean(nee, 2, 1) + block_mean(nee, 2, 2);
    cr_expect(left > 1.2 * right, "floor under the white half %g, under the black half %g", left, right);
    free(nee);
    free(bsdf);
}

Test(emission_texture, light_table_weighs_the_texture_mean)
{
    Scene scene;
    Error err = {0};
    cr_assert(scene_load(write_scene(test_temp_dir()), &scene, &err), "%s", err.message);
    LightTable table;
    light_table_build(&table, &scene.data);
    /* lamp: area 1 x luminance 1 x strength x mean 1/2; lamp2: area 0.16 x luminance 2. */
    double want = 1.0 * STRENGTH * 0.5 + 0.16 * 2.0;
    cr_expect(fabs(table.total_power - want) < 1e-4 * want, "total power %g, want %g",
              table.total_power, want);
    cr_assert_eq(table.count, 4);
    double lamp = 0.0;
    for (uint32_t i = 0; i < table.count; i++)
        if (scene.data.materials[scene.data.material_ids[table.entries[i].triangle]].tex[MATERIAL_TEX_EMISSION] != NO_TEXTURE)
            lamp += table.entries[i].pdf;
    cr_expect(fabs(lamp - STRENGTH * 0.5 / want) < 1e-5, "the lamp's pick probability %g, want %g",
              lamp, STRENGTH * 0.5 / want);
    light_table_free(&table);
    scene_free(&scene);
}
