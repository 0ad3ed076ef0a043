// SPDX-License-Identifier: MIT
/* The scene's "textures" block (host/scene/texture_json.c, texture.c): files keep or change their
 * encoding as asked (8-bit sRGB stays 8-bit, 8-bit linear and sRGB floats become linear floats),
 * .hdr and .exr load as floats, noise stores its 9 parameters in the layout cl/shared.h gives
 * TEXTURE_NOISE, and the host statistics (channels, alpha, mean) are right. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <stb_image_write.h>

#include "io/image_io.h"
#include "scene/scene.h"
#include "support.h"

static char g_dir[64];

static const char *path_in_dir(const char *name)
{
    if (!g_dir[0])
        snprintf(g_dir, sizeof g_dir, "%s", test_temp_dir());
    static char path[8][256];
    static int next;
    char *p = path[next++ % 8];
    snprintf(p, 256, "%s/%s", g_dir, name);
    return p;
}

/* Loads a scene of one triangle with `textures` as its "textures" block. */
static void load(const char *textures, Scene *scene)
{
    path_in_dir("");
    test_write_file(g_dir, "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    char json[4096];
    snprintf(json, sizeof json, "{\"objects\": [{\"obj\": \"t.obj\"}], \"textures\": {%s}}", textures);
    const char *path = test_write_file(g_dir, "scene.json", json);
    Error err = {0};
    cr_assert(scene_load(path, scene, &err), "%s", err.message);
}

static float texel_float(const TextureSet *set, uint32_t t, size_t i)
{
    float f;
    memcpy(&f, &set->texels[set->infos[t].offset + i], sizeof f);
    return f;
}

Test(texture_json, encodings_of_8_bit_images)
{
    const unsigned char px[] = {255, 128, 0, 64, 0, 0, 0, 255};
    cr_assert(stbi_write_png(path_in_dir("a.png"), 2, 1, 4, px, 8));
    Scene scene;
    load("\"s\": {\"file\": \"a.png\"}, \"l\": {\"file\": \"a.png\", \"encoding\": \"linear\"}, "
         "\"s2\": {\"file\": \"a.png\", \"encoding\": \"srgb\"}", &scene);
    const TextureSet *set = &scene.data.textures;
    cr_assert_eq(set->count, 3u, "each encoding is its own texture");
    cr_expect_eq(set->infos[0].format, TEXTURE_RGBA8_SRGB, "8-bit default: sRGB");
    cr_expect_eq(set->infos[2].format, TEXTURE_RGBA8_SRGB);
    cr_expect_eq(set->infos[1].format, TEXTURE_RGBA8_LINEAR, "8-bit linear: stays 8-bit");
    /* The file's bytes, one uint per texel (r in the low byte), in both 8-bit formats. */
    for (uint32_t t = 0; t < 2; t++) {
        cr_expect_eq(set->texels[set->infos[t].offset], 0x400080ffu, "texture %u texel 0", t);
        cr_expect_eq(set->texels[set->infos[t].offset + 1], 0xff000000u, "texture %u texel 1", t);
    }
    cr_expect_eq(set->stats[0].channels, 4);
    cr_expect(set->stats[0].alpha_below_one);
    /* Mean of red: sRGB-decoded (1 + 0) / 2; linear: the same (1 and 0 are fixed points). */
    cr_expect(fabsf(set->stats[0].mean[0] - 0.5f) < 1e-6f, "%g", set->stats[0].mean[0]);
    /* Mean of green: sRGB 128 decodes to 0.2158; linear reads 0.502. */
    cr_expect(fabsf(set->stats[0].mean[1] - 0.5f * 0.21586f) < 1e-4f, "%g", set->stats[0].mean[1]);
    cr_expect(fabsf(set->stats[1].mean[1] - 0.5f * 128.0f / 255.0f) < 1e-6f, "%g", set->stats[1].mean[1]);
    scene_free(&scene);
}

Test(texture_json, hdr_and_exr_are_linear_floats_srgb_floats_are_decoded)
{
    const float rgb[] = {0.5f, 2.0f, 4.0f, 0.25f, 0.0f, 1.0f};
    cr_assert(stbi_write_hdr(path_in_dir("a.hdr"), 2, 1, 3, rgb));
    Error err = {0};
    cr_assert(image_write_exr(path_in_dir("a.exr"), rgb, 2, 1, &err), "%s", err.message);
    Scene scene;
    load("\"h\": {\"file\": \"a.hdr\"}, \"e\": {\"file\": \"a.exr\"}, "
         "\"es\": {\"file\": \"a.exr\", \"encoding\": \"srgb\"}", &scene);
    const TextureSet *set = &scene.data.textures;
    cr_assert_eq(set->count, 3u);
    for (uint32_t t = 0; t < 2; t++) {
        cr_expect_eq(set->infos[t].format, TEXTURE_RGBA32F);
        cr_expect_eq(set->infos[t].width, 2u);
        cr_expect_eq(set->stats[t].channels, 3);
        cr_expect_not(set->stats[t].alpha_below_one);
        for (int i = 0; i < 2; i++)
            for (int c = 0; c < 3; c++)
                cr_expect(fabsf(texel_float(set, t, 4 * (size_t)i + (size_t)c) - rgb[3 * i + c]) <
                              0.02f * rgb[3 * i + c] + 1e-6f,
                          "texture %u texel %d channel %d: %g", t, i, c,
                          texel_float(set, t, 4 * (size_t)i + (size_t)c));
        cr_expect_eq(texel_float(set, t, 3), 1.0f, "opaque");
    }
    /* sRGB-decoded 0.5 is 0.214; 1 stays 1. */
    cr_expect(fabsf(texel_float(set, 2, 0) - 0.21404f) < 1e-4f, "%g", texel_float(set, 2, 0));
    cr_expect(fabsf(texel_float(set, 2, 6) - 1.0f) < 1e-6f, "%g", texel_float(set, 2, 6));
    scene_free(&scene);
}

Test(texture_json, noise_stores_its_parameters_in_the_shared_layout)
{
    Scene scene;
    load("\"marble\": {\"type\": \"noise\", \"color0\": [0.9, 0.8, 0.7], \"color1\": [0.2, 0.3, 0.4], "
         "\"frequency\": 4.5, \"octaves\": 5, \"seed\": 17}, \"plain\": {\"type\": \"noise\"}", &scene);
    const TextureSet *set = &scene.data.textures;
    cr_assert_eq(set->count, 2u);
    TextureInfo info = set->infos[0];
    cr_expect_eq(info.format, TEXTURE_NOISE);
    cr_expect_eq(info.width, 1u);
    cr_expect_eq(info.height, 1u);
    const float expected[7] = {0.9f, 0.8f, 0.7f, 0.2f, 0.3f, 0.4f, 4.5f};
    for (int i = 0; i < 7; i++)
        cr_expect_eq(texel_float(set, 0, (size_t)i), expected[i], "uint %d: %g", i, texel_float(set, 0, (size_t)i));
    cr_expect_eq(set->texels[info.offset + 7], 5u, "octaves");
    cr_expect_eq(set->texels[info.offset + 8], 17u, "seed");
    cr_expect_eq(set->infos[1].offset, info.offset + 9, "9 uints each");
    /* Defaults: color0 0, color1 1, frequency 1, octaves 4, seed 0. */
    const float defaults[7] = {0, 0, 0, 1, 1, 1, 1};
    for (int i = 0; i < 7; i++)
        cr_expect_eq(texel_float(set, 1, (size_t)i), defaults[i], "default uint %d", i);
    cr_expect_eq(set->texels[set->infos[1].offset + 7], 4u);
    cr_expect_eq(set->texels[set->infos[1].offset + 8], 0u);
    cr_expect(fabsf(set->stats[0].mean[0] - 0.55f) < 1e-6f, "mean: the colours' midpoint");
    scene_free(&scene);
}

/* The sampling keys land in TextureInfo.flags, scale and transform (a view sharing the file's
 * texels); bad values name the key. */
Test(texture_json, sampling_keys_make_views_of_the_file)
{
    const unsigned char px[] = {255, 128, 0, 64, 0, 0, 0, 255};
    cr_assert(stbi_write_png(path_in_dir("a.png"), 2, 1, 4, px, 8));
    Scene scene;
    load("\"a\": {\"file\": \"a.png\"}, \"g\": {\"file\": \"a.png\", \"channel\": \"g\", "
         "\"scale\": 0.5, \"wrap\": [\"clamp\", \"mirror\"], \"filter\": \"nearest\", "
         "\"transform\": {\"offset\": [0.25, 0.5], \"rotation\": 90, \"scale\": [2, 4]}}",
         &scene);
    const TextureSet *set = &scene.data.textures;
    cr_assert_eq(set->count, 2u, "the file, and its view");
    TextureInfo plain = set->infos[0], view = set->infos[1];
    cr_expect_eq(plain.flags, 0u);
    cr_expect_eq(view.offset, plain.offset, "one copy of the texels");
    cr_expect_eq(TEXTURE_FLAG_WRAP_S(view.flags), TEXTURE_WRAP_CLAMP);
    cr_expect_eq(TEXTURE_FLAG_WRAP_T(view.flags), TEXTURE_WRAP_MIRROR);
    cr_expect_eq(TEXTURE_FLAG_CHANNEL(view.flags), 1u);
    cr_expect(view.flags & TEXTURE_FLAG_NEAREST);
    cr_expect((view.flags & TEXTURE_FLAG_SCALE) && view.scale == 0.5f, "scale %g", view.scale);
    cr_expect(view.flags & TEXTURE_FLAG_TRANSFORM);
    /* T R S with R 90 degrees counter-clockwise: u' = -4 v + 0.25, v' = 2 u + 0.5. */
    const float expected[6] = {0.0f, -4.0f, 0.25f, 2.0f, 0.0f, 0.5f};
    for (int i = 0; i < 6; i++)
        cr_expect(fabsf(view.transform[i] - expected[i]) < 1e-6f, "transform[%d] %g", i,
                  view.transform[i]);
    scene_free(&scene);
    const char *bad[][2] = {
        {"\"channel\": \"x\"", "textures.t.channel"},
        {"\"wrap\": \"loop\"", "textures.t.wrap"},
        {"\"filter\": 3", "textures.t.filter"},
        {"\"transform\": {\"skew\": 1}", "textures.t.transform"},
        {"\"scale\": \"big\"", "textures.t.scale"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char json[512];
        snprintf(json, sizeof json,
                 "{\"objects\": [{\"obj\": \"t.obj\"}], \"textures\": {\"t\": {\"file\": \"a.png\", %s}}}",
                 bad[i][0]);
        Error err = {0};
        Scene s;
        cr_expect_not(scene_load(test_write_file(g_dir, "bad.json", json), &s, &err), "%s accepted",
                      bad[i][0]);
        cr_expect(strstr(err.message, bad[i][1]), "%s: %s", bad[i][0], err.message);
    }
}
