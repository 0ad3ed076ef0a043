// SPDX-License-Identifier: MIT
/* Transforms, instancing and motion blur through the whole renderer (shared/DESIGN.md "Objects",
 * "Camera" shutter): an instanced scene renders the image of the same scene with the transforms
 * baked into the vertices (bit for bit where every transform is the identity, within noise
 * otherwise); the order of a transform's operations, the rotation sense and the matrix layout
 * give hand-computed depths; a mirrored emitter shines on the side its transformed normal points
 * to; a moving object renders the average over the shutter of stratified fixed-time renders.
 * Flat BVHs over instances: tests/test_instances_flat.c. */
#define _DEFAULT_SOURCE /* realpath */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/transform.h"
#include "render/aov.h"
#include "support.h"
#include "turned_instances.h"

/* A 2 x 2 quad in the plane z = `z`, counter-clockwise seen from +z (its front). */
static const char *quad_obj(const char *dir, const char *name, float z)
{
    char text[256];
    snprintf(text, sizeof text, "v -1 -1 %g\nv 1 -1 %g\nv 1 1 %g\nv -1 1 %g\nf 1 2 3 4\n", z, z,
             z, z);
    return test_write_file(dir, name, text);
}

/* ---- Bit for bit: identity instances are the merged mesh --------------------------------- */

Test(instances_render, identity_instances_render_the_same_bits, .timeout = 120)
{
    const char *scene = box_and_tetra_scene("  {\"obj\": \"tetra.obj\"}");
    RenderSettings s = {.spp = 8, .max_depth = 6, .seed = 5};
    RenderFixture merged, instanced;
    render_fixture_open_with(&merged, scene, 32, 32, INSTANCING_AUTO);
    cr_assert_eq(merged.scene.data.num_instances, 1, "auto merges both objects");
    float *a = render_fixture_render(&merged, s, NULL);
    render_fixture_close(&merged);
    render_fixture_open_with(&instanced, scene, 32, 32, INSTANCING_ALWAYS);
    cr_assert_eq(instanced.scene.data.num_instances, 2, "always makes each object an instance");
    float *b = render_fixture_render(&instanced, s, NULL);
    render_fixture_close(&instanced);
    cr_expect(memcmp(a, b, 32 * 32 * 3 * sizeof(float)) == 0,
              "identity instances changed the image (their rays and points are the same bits)");
    free(a), free(b);
}

/* ---- Within noise: transformed instances against their baked copies ---------------------- */

/* Mean image over `renders` seeds, and each 8 x 8 block's mean and standard error. */
typedef struct {
    double block[16][3], se[16][3];
} BlockEstimate;

static BlockEstimate block_estimate(RenderFixture *f, RenderSettings s, int renders)
{
    BlockEstimate e;
    double sum[16][3] = {{0}}, sum2[16][3] = {{0}};
    for (int k = 0; k < renders; k++) {
        s.seed = 100u + 7919u * (unsigned)k;
        float *rgb = render_fixture_render(f, s, NULL);
        double m[16][3] = {{0}};
        for (int y = 0; y < 32; y++)
            for (int x = 0; x < 32; x++)
                for (int c = 0; c < 3; c++)
                    m[(y / 8) * 4 + x / 8][c] += rgb[3 * (y * 32 + x) + c] / 64.0;
        for (int b = 0; b < 16; b++)
            for (int c = 0; c < 3; c++)
                sum[b][c] += m[b][c], sum2[b][c] += m[b][c] * m[b][c];
        free(rgb);
    }
    for (int b = 0; b < 16; b++)
        for (int c = 0; c < 3; c++) {
            e.block[b][c] = sum[b][c] / renders;
            double var = (sum2[b][c] - renders * e.block[b][c] * e.block[b][c]) / (renders - 1);
            e.se[b][c] = sqrt(fmax(var, 0.0) / renders);
        }
    return e;
}

/* Every block's difference within z < 5 of the two estimates' noise (48 comparisons). */
static void expect_same_blocks(const BlockEstimate *a, const BlockEstimate *b, const char *what)
{
    for (int i = 0; i < 16; i++)
        for (int c = 0; c < 3; c++) {
            double se = sqrt(a->se[i][c] * a->se[i][c] + b->se[i][c] * b->se[i][c]) + 1e-6;
            double z = fabs(a->block[i][c] - b->block[i][c]) / se;
            cr_expect(z < 5.0, "%s: block %d channel %d: %f vs %f (z = %.1f)", what, i, c,
                      a->block[i][c], b->block[i][c], z);
        }
}

Test(instances_render, instances_render_their_baked_copies, .timeout = 300)
{
    const char *scene = turned_instances_scene();
    RenderSettings s = {.spp = 32, .max_depth = 5};
    RenderFixture baked, instanced;
    render_fixture_open_with(&baked, scene, 32, 32, INSTANCING_NEVER);
    cr_assert_not(baked.scene.data.two_level, "never bakes everything into one level");
    BlockEstimate a = block_estimate(&baked, s, 4);
    render_fixture_close(&baked);
    render_fixture_open_with(&instanced, scene, 32, 32, INSTANCING_AUTO);
    cr_assert_eq(instanced.scene.data.num_meshes, 2, "the box merged, the tetrahedron once");
    cr_assert_eq(instanced.scene.data.num_instances, 4);
    BlockEstimate b = block_estimate(&instanced, s, 4);
    render_fixture_close(&instanced);
    expect_same_blocks(&a, &b, "instanced vs baked");
}

/* The two-level BVH (its TLAS boxes: the exact boxes of turned instances, render/scene_upload.c)
 * finds the hits that testing every instance's every triangle finds: the same bits. A TLAS box
 * that cut off part of an instance would lose hits there. */
Test(instances_render, turned_instances_render_the_brute_force_bits, .timeout = 300)
{
    RenderFixture f;
    render_fixture_open_with(&f, turned_instances_scene(), 48, 48, INSTANCING_AUTO);
    cr_assert(f.scene.data.two_level);
    expect_brute_force_bits(&f, "the two-level BVH");
}

/* ---- Order, rotation sense, matrix layout: depths by hand ------------------------------------ */

/* The depth AOV at the centre of a 9 x 9 film of a scene with one quad (z = quad_z) under
 * `transform` (JSON), seen by a narrow camera at eye looking at the origin. */
static float centre_depth(float quad_z, const char *transform, const char *eye, const char *up)
{
    const char *dir = test_temp_dir();
    quad_obj(dir, "quad.obj", quad_z);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"eye\": %s, \"target\": [0, 0, 0], \"up\": %s, \"fov_y\": 5},\n"
             " \"objects\": [{\"obj\": \"quad.obj\", \"transform\": %s}]}\n",
             eye, up, transform);
    RenderFixture f;
    render_fixture_open(&f, test_write_file(dir, "scene.json", json), 9, 9);
    float rgb[9 * 9 * 3];
    aov_render(f.dev, &f.scene, &f.buffers, AOV_DEPTH, 4, 0, rgb);
    render_fixture_close(&f);
    return rgb[3 * (4 * 9 + 4)];
}

#define FROM_Z "[0, 0, 10]", "[0, 1, 0]"
#define FROM_X "[10, 0, 0]", "[0, 1, 0]"
#define FROM_MINUS_Y "[0, -10, 0]", "[0, 0, 1]"

Test(instances_render, operations_apply_in_the_order_written, .timeout = 120)
{
    /* scale 2 then +1 in z: the plane z = 0 goes to z = 1 (depth 9 from z = 10); the quad at
     * z = 1 to z = 3 (depth 7) and, the other way round, to z = 4 (depth 6). */
    float scale_first = centre_depth(1, "[{\"scale\": 2}, {\"translate\": [0, 0, 1]}]", FROM_Z);
    float translate_first = centre_depth(1, "[{\"translate\": [0, 0, 1]}, {\"scale\": 2}]", FROM_Z);
    cr_expect_float_eq(scale_first, 7.0f, 0.01f, "scale, then translate: z = 2 * 1 + 1");
    cr_expect_float_eq(translate_first, 6.0f, 0.01f, "translate, then scale: z = (1 + 1) * 2");
}

Test(instances_render, positive_angles_turn_counter_clockwise, .timeout = 120)
{
    /* Looking down +y toward the origin, counter-clockwise takes +z to +x: the quad at z = 1
     * turned +90 degrees about +y lies in x = 1 (depth 9 from x = 10; 11 the wrong way). */
    cr_expect_float_eq(centre_depth(1, "[{\"rotate\": {\"axis\": [0, 1, 0], \"angle\": 90}}]",
                                    FROM_X),
                       9.0f, 0.01f, "+90 about +y takes +z to +x");
    /* About +x, +y goes to +z and +z to -y: the quad lies in y = -1 (depth 9 from y = -10). */
    cr_expect_float_eq(centre_depth(1, "[{\"rotate\": {\"axis\": [1, 0, 0], \"angle\": 90}}]",
                                    FROM_MINUS_Y),
                       9.0f, 0.01f, "+90 about +x takes +z to -y");
}

Test(instances_render, matrices_are_row_major_with_column_vectors, .timeout = 120)
{
    /* The translation is the last column of the rows: z + 2. */
    cr_expect_float_eq(centre_depth(0, "[{\"matrix\": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 2, 0, 0, "
                                       "0, 1]}]", FROM_Z),
                       8.0f, 0.01f, "p' = M p: z = 0 + 2");
    /* Rows (0 0 1), (0 1 0), (-1 0 0): x' = z, the quad at z = 1 lies in x = 1, as the rotation
     * of +90 degrees about +y puts it (its transpose would put it in x = -1). */
    cr_expect_float_eq(centre_depth(1, "[{\"matrix\": [0, 0, 1, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, "
                                       "0, 1]}]", FROM_X),
                       9.0f, 0.01f, "x' = z");
}

/* ---- Mirrored emitters --------------------------------------------------------------------- */

/* The radiance seen at the centre pixel from eye (max_depth 1: emitters only) of a lamp quad in
 * z = 0 (front +z) under `transform`. */
static float lamp_seen(const char *transform, const char *eye, InstancingMode mode)
{
    const char *dir = test_temp_dir();
    quad_obj(dir, "lamp.obj", 0);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"eye\": %s, \"target\": [0, 0, 0], \"fov_y\": 5},\n"
             " \"materials\": {\"lamp\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": [2, 2, 2]}},\n"
             " \"objects\": [{\"obj\": \"lamp.obj\", \"material\": \"lamp\", \"transform\": %s},\n"
             "             {\"obj\": \"lamp.obj\", \"material\": \"lamp\", \"transform\": "
             "[{\"translate\": [0, 100, 0]}]}]}\n",
             eye, transform);
    RenderFixture f;
    render_fixture_open_with(&f, test_write_file(dir, "scene.json", json), 9, 9, mode);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 1}, NULL);
    float centre = rgb[3 * (4 * 9 + 4)];
    free(rgb);
    render_fixture_close(&f);
    return centre;
}

Test(instances_render, a_mirrored_emitter_shines_where_its_normal_points, .timeout = 120)
{
    /* Mirrored in z, the quad's normal (0, 0, 1) becomes (0, 0, -1) (inverse transpose): it
     * shines toward -z, where its corners, seen from there, run clockwise. */
    const char *mirror = "[{\"scale\": [1, 1, -1]}]", *plain = "[{\"translate\": [0, 0, 0]}]";
    for (int mode = INSTANCING_AUTO; mode <= INSTANCING_NEVER; mode++) {
        InstancingMode m = (InstancingMode)mode;
        cr_expect_float_eq(lamp_seen(plain, "[0, 0, 5]", m), 2.0f, 1e-4f, "mode %d: front +z", mode);
        cr_expect_float_eq(lamp_seen(plain, "[0, 0, -5]", m), 0.0f, 1e-6f, "mode %d: back", mode);
        cr_expect_float_eq(lamp_seen(mirror, "[0, 0, -5]", m), 2.0f, 1e-4f,
                           "mode %d: the mirrored lamp shines toward -z", mode);
        cr_expect_float_eq(lamp_seen(mirror, "[0, 0, 5]", m), 0.0f, 1e-6f,
                           "mode %d: and not toward +z", mode);
    }
}

/* ---- Motion blur ------------------------------------------------------------------------------ */

/* A lamp bar (the quad scaled to 1.2 x 0.3: a turn shows, unlike a square's) moving from
 * (-1, 0, 0) to (1, 0, 0) while turning 90 degrees about z,
 * seen from z = 10 (max_depth 1); `transform` overrides the motion with a fixed matrix. */
static float *render_lamp_motion(const char *dir, const char *object, int spp, unsigned seed)
{
    char json[4096];
    snprintf(json, sizeof json,
             "{\"camera\": {\"eye\": [0, 0, 10], \"target\": [0, 0, 0], \"fov_y\": 16, "
             "\"shutter\": [0, 1]},\n"
             " \"materials\": {\"lamp\": {\"type\": \"diffuse\", \"albedo\": 0, \"emission\": [1, 1, 1]}},\n"
             " \"objects\": [{\"obj\": \"lamp.obj\", \"material\": \"lamp\", %s}]}\n",
             object);
    RenderFixture f;
    render_fixture_open(&f, test_write_file(dir, "scene.json", json), 32, 32);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = spp, .max_depth = 1, .seed = seed}, NULL);
    render_fixture_close(&f);
    return rgb;
}

static Affine lamp_pose(double x, double angle)
{
    Affine scale = affine_scale(0.6, 0.15, 0.3), rotate, translate = affine_translate(x, 0, 0);
    const double z_axis[3] = {0, 0, 1};
    cr_assert(affine_rotate(z_axis, angle, &rotate));
    Affine rs = affine_mul(&rotate, &scale);
    return affine_mul(&translate, &rs);
}

static double image_mean(const float *rgb)
{
    double sum = 0.0;
    for (int i = 0; i < 32 * 32; i++)
        sum += rgb[3 * i];
    return sum / (32 * 32);
}

Test(instances_render, motion_blur_is_the_average_over_the_shutter, .timeout = 300)
{
    const char *dir = test_temp_dir();
    quad_obj(dir, "lamp.obj", 0);
    const char *motion = "\"transform\": [{\"scale\": [0.6, 0.15, 0.3]}, {\"translate\": [-1, 0, 0]}], "
                         "\"transform_end\": [{\"scale\": [0.6, 0.15, 0.3]}, {\"rotate\": {\"axis\": [0, 0, 1], "
                         "\"angle\": 90}}, {\"translate\": [1, 0, 0]}]";
    const int K = 16, spp_each = 32;
    float *moving = render_lamp_motion(dir, motion, K * spp_each, 1);
    /* The same integral over the shutter by the midpoint rule: K renders at fixed times, the
     * pose from the host's T R S interpolation. */
    Trs open, close;
    Affine a = lamp_pose(-1, 0), b = lamp_pose(1, 90);
    cr_assert(trs_decompose(&a, &open) && trs_decompose(&b, &close));
    trs_align(&open, &close);
    double *average = calloc(32 * 32, sizeof *average);
    for (int k = 0; k < K; k++) {
        Trs at = trs_interpolate(&open, &close, (k + 0.5) / K);
        Affine m = trs_compose(&at);
        char object[1024];
        snprintf(object, sizeof object,
                 "\"transform\": [{\"matrix\": [%.17g, %.17g, %.17g, %.17g, %.17g, %.17g, %.17g, "
                 "%.17g, %.17g, %.17g, %.17g, %.17g, 0, 0, 0, 1]}]",
                 m.m[0][0], m.m[0][1], m.m[0][2], m.m[0][3], m.m[1][0], m.m[1][1], m.m[1][2],
                 m.m[1][3], m.m[2][0], m.m[2][1], m.m[2][2], m.m[2][3]);
        float *still = render_lamp_motion(dir, object, spp_each, 100u + (unsigned)k);
        for (int i = 0; i < 32 * 32; i++)
            average[i] += still[3 * i] / K;
        free(still);
    }
    float *at_open = render_lamp_motion(dir, "\"transform\": [{\"scale\": [0.6, 0.15, 0.3]}, {\"translate\": [-1, 0, 0]}]",
                                        64, 2);
    /* 4 x 4 blocks: each pixel's value is the fraction of (time, position) samples on the lamp;
     * a block's difference is within the Monte Carlo noise (p (1 - p) / n per pixel) and the
     * midpoint rule's error (an edge crossing a pixel moves 1/K of the shutter between times). */
    double worst = 0.0, moved_away = 0.0;
    for (int by = 0; by < 8; by++)
        for (int bx = 0; bx < 8; bx++) {
            double m = 0.0, s = 0.0, o = 0.0;
            for (int y = 4 * by; y < 4 * by + 4; y++)
                for (int x = 4 * bx; x < 4 * bx + 4; x++) {
                    m += moving[3 * (y * 32 + x)] / 16.0;
                    s += average[y * 32 + x] / 16.0;
                    o += at_open[3 * (y * 32 + x)] / 16.0;
                }
            double noise = sqrt(fmax(m * (1.0 - m), 0.01) / (16.0 * K * spp_each)) * 2.0;
            double bound = 5.0 * noise + 1.0 / K;
            worst = fmax(worst, fabs(m - s) / bound);
            moved_away = fmax(moved_away, fabs(m - o));
        }
    cr_expect(worst < 1.0, "a block differs from the stratified average by %.2f of its bound", worst);
    double mean_average = 0.0;
    for (int i = 0; i < 32 * 32; i++)
        mean_average += average[i] / (32 * 32);
    cr_expect(fabs(image_mean(moving) - mean_average) < 0.01 * mean_average + 1e-3,
              "the lamp's total light: %f moving vs %f averaged", image_mean(moving), mean_average);
    cr_expect(moved_away > 0.3, "the moving lamp is smeared away from its opening pose (%f)",
              moved_away);
    free(moving), free(average), free(at_open);
}

Test(instances_render, an_unchanged_transform_end_changes_no_bit, .timeout = 120)
{
    const char *dir = test_temp_dir();
    quad_obj(dir, "lamp.obj", 0);
    float *with_end = render_lamp_motion(dir, "\"transform\": [{\"translate\": [0.2, 0, 0]}], "
                                              "\"transform_end\": [{\"translate\": [0.2, 0, 0]}]",
                                         8, 3);
    float *without = render_lamp_motion(dir, "\"transform\": [{\"translate\": [0.2, 0, 0]}]", 8, 3);
    cr_expect(memcmp(with_end, without, 32 * 32 * 3 * sizeof(float)) == 0,
              "a transform_end equal to the transform changed the image");
    free(with_end), free(without);
}
