// SPDX-License-Identifier: MIT
/* The environment map renders without bias: the white furnace through the map path, and NEE + MIS
 * against BSDF-only sampling under a high-contrast map (alone and with a lamp in the same light
 * table) and under the Venice sunset HDR (scenes/venice). */
#include <stb_image_write.h>

#include "environment_maps.h"
#include "io/image_io.h"

/* White furnace through the map path: a constant map of 1 lights a convex sphere of albedo 0.8 to
 * exactly 0.8, as the constant background does; with NEE on, the map is sampled (noisy per sample,
 * 0.8 on average), with it off every sample is 0.8. */
Test(environment, white_furnace_with_a_constant_map, .timeout = 120)
{
    const char *dir = test_temp_dir();
    float ones[16 * 8 * 3];
    for (size_t i = 0; i < sizeof ones / sizeof ones[0]; i++)
        ones[i] = 1.0f;
    char exr[512];
    snprintf(exr, sizeof exr, "%s/ones.exr", dir);
    Error err = {0};
    cr_assert(image_write_exr(exr, ones, 16, 8, &err), "%s", err.message);
    write_ball_obj(dir, false);
    const char *scene = write_scene(dir, "scene.json", "[{\"obj\": \"ball.obj\"}]", "ones.exr", 30.0f,
                                    "{\"eye\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 40}");
    RenderFixture f;
    render_fixture_open(&f, scene, 48, 48);
    cr_assert_eq(f.buffers.params.num_emissive, 1, "the map is the only entry of the light table");
    for (int no_nee = 0; no_nee < 2; no_nee++) {
        float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 64, .max_depth = 8, .seed = 1, .no_nee = no_nee}, NULL);
        double sum = 0.0;
        int on_sphere = 0;
        for (int y = 0; y < 48; y++)
            for (int x = 0; x < 48; x++) {
                double r = hypot(x + 0.5 - 24, y + 0.5 - 24);
                const float *px = &rgb[3 * (y * 48 + x)];
                for (int c = 0; c < 3; c++) {
                    if (r < 14) {
                        sum += px[c];
                        if (no_nee)
                            cr_expect(fabsf(px[c] - 0.8f) < 1e-3f, "pixel %d,%d = %f, expected 0.8", x, y, px[c]);
                    } else if (r > 19) {
                        cr_expect(fabsf(px[c] - 1.0f) < 1e-5f, "sky pixel %d,%d = %f, expected 1", x, y, px[c]);
                    }
                }
                on_sphere += r < 14;
            }
        double mean = sum / (3.0 * on_sphere);
        cr_expect(fabs(mean - 0.8) < 2e-3, "no_nee %d: the sphere's mean is %.5f, expected 0.8", no_nee, mean);
        free(rgb);
    }
    render_fixture_close(&f);
}

/* Block means of a 32 x 32 image (8 x 8 blocks of 4 x 4 pixels) per channel. */
#define SIDE 32
#define BLOCK 8
#define NB ((SIDE / BLOCK) * (SIDE / BLOCK) * 3)
static void block_means(const float *rgb, double out[NB])
{
    memset(out, 0, NB * sizeof *out);
    for (int y = 0; y < SIDE; y++)
        for (int x = 0; x < SIDE; x++)
            for (int c = 0; c < 3; c++)
                out[((y / BLOCK) * (SIDE / BLOCK) + x / BLOCK) * 3 + c] += rgb[3 * (y * SIDE + x) + c] / (BLOCK * BLOCK);
}

/* NEE + MIS (the map sampled, escaped rays weighted) and BSDF-only sampling converge to the same
 * image of `scene`: each block's mean is compared with the spread of that mean over independent
 * seeds (with a floor of `error_floor` x the mean on its standard error), and the image means
 * agree within `image_tolerance` (relative). */
static void check_nee_against_bsdf_sampling(const char *scene, int spp_nee, int spp_bsdf,
                                            double error_floor, double image_tolerance)
{
    RenderFixture f;
    render_fixture_open(&f, scene, SIDE, SIDE);
    enum { SEEDS = 8 };
    static double mean[2][SEEDS][NB];
    for (int no_nee = 0; no_nee < 2; no_nee++)
        for (int s = 0; s < SEEDS; s++) {
            RenderSettings rs = {.spp = no_nee ? spp_bsdf : spp_nee, .max_depth = 4, .seed = 11 + 7 * s + no_nee, .no_nee = no_nee};
            float *img = render_fixture_render(&f, rs, NULL);
            block_means(img, mean[no_nee][s]);
            free(img);
        }
    double worst = 0.0, total[2] = {0, 0};
    for (int b = 0; b < NB; b++) {
        double m[2], var[2];
        for (int k = 0; k < 2; k++) {
            m[k] = var[k] = 0.0;
            for (int s = 0; s < SEEDS; s++)
                m[k] += mean[k][s][b] / SEEDS;
            for (int s = 0; s < SEEDS; s++)
                var[k] += (mean[k][s][b] - m[k]) * (mean[k][s][b] - m[k]) / (SEEDS - 1) / SEEDS;
            total[k] += m[k];
        }
        /* A floor on the standard error: blocks of pure sky have no noise at all. */
        double floor = error_floor * m[1];
        double z = fabs(m[0] - m[1]) / sqrt(var[0] + var[1] + floor * floor + 1e-12);
        worst = fmax(worst, z);
        if (z > 3.0)
            cr_log_info("block %d channel %d: NEE %.4f +- %.4f, BSDF-only %.4f +- %.4f (z = %.1f)", b / 3, b % 3, m[0], sqrt(var[0]), m[1], sqrt(var[1]), z);
        cr_expect(z < 5.0, "block %d channel %d: NEE %.4f, BSDF-only %.4f (z = %.1f)", b / 3, b % 3, m[0], m[1], z);
    }
    cr_log_info("worst block z %.2f; image means NEE %.4f, BSDF-only %.4f", worst, total[0] / NB, total[1] / NB);
    cr_expect(fabs(total[0] - total[1]) < image_tolerance * total[1], "image means NEE %.4f, BSDF-only %.4f",
              total[0] / NB, total[1] / NB);
    render_fixture_close(&f);
}

/* A diffuse sphere on a floor under a generated map with a small bright sun, a black row and a
 * noisy sky; `objects` is the scene's object list (the ball and floor, plus anything else). */
static void check_contrast_map(const char *dir, const char *objects)
{
    int w = 64, h = 32;
    float *rgb = contrast_map(w, h);
    char hdr[512];
    snprintf(hdr, sizeof hdr, "%s/sky.hdr", dir);
    cr_assert(stbi_write_hdr(hdr, w, h, 3, rgb));
    free(rgb);
    write_ball_obj(dir, true);
    const char *scene = write_scene(dir, "scene.json", objects, "sky.hdr", 20.0f,
                                    "{\"eye\": [0, 1, 4], \"target\": [0, -0.3, 0], \"fov_y\": 45}");
    check_nee_against_bsdf_sampling(scene, 256, 2048, 0.003, 0.01);
}

Test(environment, nee_with_mis_agrees_with_bsdf_sampling, .timeout = 300)
{
    check_contrast_map(test_temp_dir(), "[{\"obj\": \"ball.obj\"}]");
}

/* The same with a small lamp (two emissive triangles facing down) above the ball: triangles and
 * the map share one light table, so each one's MIS weight (emission_seen, environment_seen) must
 * use its share of the table's power. */
Test(environment, nee_with_mis_agrees_with_a_lamp_in_the_same_light_table, .timeout = 300)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "lamp.mtl", "newmtl lamp\nKd 0 0 0\nKe 20 18 15\n");
    test_write_file(dir, "lamp.obj",
                    "mtllib lamp.mtl\nusemtl lamp\nv -0.3 2.5 -0.3\nv 0.3 2.5 -0.3\nv 0.3 2.5 0.3\n"
                    "v -0.3 2.5 0.3\nf 1 2 3\nf 1 3 4\n");
    check_contrast_map(dir, "[{\"obj\": \"ball.obj\"}, {\"obj\": \"lamp.obj\"}]");
}

/* The unbiasedness check on a real map: the diffuse sphere on a floor of scenes/venice
 * (the Venice sunset HDR, CC0, in the repository) through NEE + MIS and BSDF-only, on the bilinear
 * map. The sun makes BSDF-only heavy-tailed (rare hits), so 8 seeds' spread underestimates its
 * error: a 1% floor on the blocks' standard error (at 4x the spp the worst block is at z < 2
 * without it), and the image means within 0.5%. */
Test(environment, nee_with_mis_agrees_with_bsdf_sampling_under_venice_sunset, .timeout = 300)
{
    check_nee_against_bsdf_sampling("scenes/venice/sphere.json", 128, 1024, 0.01, 0.005);
}
