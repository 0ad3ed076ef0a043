// SPDX-License-Identifier: MIT
/* Alpha MASK (glTF's alphaMode MASK; a material's alpha_cutoff): opacity becomes 1 where it reaches
 * the cutoff and 0 below, so a card whose opacity texture is a checker of 0.3 and 0.7 with cutoff
 * 0.5 is fully open and fully opaque in its cells, not 70% and 30% see-through. A black 1 x 1
 * card at y = 0.5 over a diffuse floor (albedo 0.8) lit straight down by a directional light,
 * seen from above (direct light only): the open cells show the lit floor 0.8 / pi, the opaque
 * ones black. The glTF mapping gives this material (test_scene_gltf_material's MASK case). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <stb_image_write.h>

#include "support.h"

static const double PI = 3.14159265358979323846;
#define RES 64
#define CAM_H 5.0
#define TAN_HALF 0.4
#define CARD_Y 0.5
#define TEX 16 /* cells of 4 x 4 texels: bilinear filtering leaves flat centres */

static bool cell_opaque(int cu, int cv) { return (cu + cv) % 2 == 0; }

static const char *write_scene(const char *dir, const char *cutoff)
{
    unsigned char px[TEX * TEX];
    for (int j = 0; j < TEX; j++) /* row 0 is the image's top, v = 1 */
        for (int i = 0; i < TEX; i++)
            px[j * TEX + i] = cell_opaque(i / 4, (TEX - 1 - j) / 4) ? 178 : 77; /* 0.7, 0.3 */
    char png[512];
    snprintf(png, sizeof png, "%s/mask.png", dir);
    cr_assert(stbi_write_png(png, TEX, TEX, 1, px, TEX));
    test_write_file(dir, "floor.mtl", "newmtl floor\nKd 0.8 0.8 0.8\n");
    test_write_file(dir, "floor.obj", "mtllib floor.mtl\nv -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\n"
                                      "usemtl floor\nf 1 4 3\nf 1 3 2\n");
    test_write_file(dir, "card.obj", "v -0.5 0.5 -0.5\nv 0.5 0.5 -0.5\nv 0.5 0.5 0.5\nv -0.5 0.5 0.5\n"
                                     "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nf 1/1 4/4 3/3\nf 1/1 3/3 2/2\n");
    char text[2048];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [0, %g, 0], \"target\": [0, 0, 0], \"up\": [0, 0, -1], "
             "\"fov_y\": %.9g},\n \"film\": {\"width\": %d, \"height\": %d},\n"
             " \"textures\": {\"mask\": {\"file\": \"mask.png\", \"encoding\": \"linear\"}},\n"
             " \"materials\": {\"card\": {\"type\": \"diffuse\", \"albedo\": 0, \"opacity\": \"mask\"%s}},\n"
             " \"objects\": [{\"obj\": \"floor.obj\"}, {\"obj\": \"card.obj\", \"material\": \"card\"}],\n"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [0, -1, 0], "
             "\"irradiance\": [1, 1, 1]}]}\n",
             CAM_H, 2.0 * atan(TAN_HALF) * 180.0 / PI, RES, RES, cutoff);
    return test_write_file(dir, "scene.json", text);
}

/* Mean green of the pixels near the centres of the card's open and opaque cells. */
static void cell_means(const float *rgb, double *open, double *opaque)
{
    double sum[2] = {0.0, 0.0};
    int n[2] = {0, 0};
    for (int j = 0; j < RES; j++)
        for (int i = 0; i < RES; i++) {
            double x = (2.0 * (i + 0.5) / RES - 1.0) * TAN_HALF * (CAM_H - CARD_Y);
            double z = -(1.0 - 2.0 * (j + 0.5) / RES) * TAN_HALF * (CAM_H - CARD_Y);
            double u = x + 0.5, v = 0.5 - z;
            if (u <= 0.0 || u >= 1.0 || v <= 0.0 || v >= 1.0)
                continue;
            double fu = u * 4.0 - floor(u * 4.0), fv = v * 4.0 - floor(v * 4.0);
            if (fabs(fu - 0.5) > 0.2 || fabs(fv - 0.5) > 0.2)
                continue;
            int k = cell_opaque((int)(u * 4.0), (int)(v * 4.0));
            sum[k] += rgb[3 * (j * RES + i) + 1];
            n[k]++;
        }
    cr_assert(n[0] > 10 && n[1] > 10, "%d open and %d opaque pixels", n[0], n[1]);
    *open = sum[0] / n[0];
    *opaque = sum[1] / n[1];
}

Test(alpha_mask, cutoff_makes_cells_fully_open_or_opaque, .timeout = 600)
{
    RenderFixture f;
    render_fixture_open(&f, write_scene(test_temp_dir(), ", \"alpha_cutoff\": 0.5"), 0, 0);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 16, .max_depth = 2, .seed = 5}, NULL);
    render_fixture_close(&f);
    double open, opaque, lit = 0.8 / PI;
    cell_means(rgb, &open, &opaque);
    cr_expect(fabs(open - lit) < 0.02 * lit, "open cells (opacity 0.3 < 0.5): %g, the lit floor %g",
              open, lit);
    cr_expect(opaque < 0.01 * lit, "opaque cells (opacity 0.7 >= 0.5): %g", opaque);
    free(rgb);
}
