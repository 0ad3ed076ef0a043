// SPDX-License-Identifier: MIT
/* Textures: 8-bit images are packed one uint per texel (r in the low byte, sRGB kept), grey and
 * grey-alpha expanded, alpha 255 when absent; .hdr images are stored as linear float RGBA; row 0
 * is the image's top row; paths are de-duplicated; missing and corrupt files are told apart. On
 * the device, texture_sample decodes sRGB, filters bilinearly, repeats, and puts v = 0 at the
 * bottom. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <stb_image_write.h>

#include "device/device.h"
#include "support.h"
#include "scene/texture.h"
#include "texture_sampling.h"

static char g_path[512];

static const char *temp_file(const char *dir, const char *name)
{
    snprintf(g_path, sizeof g_path, "%s/%s", dir, name);
    return g_path;
}

static uint32_t pack(unsigned r, unsigned g, unsigned b, unsigned a)
{
    return r | g << 8 | b << 16 | a << 24;
}

Test(texture, rgb_png_packs_rgba8_with_opaque_alpha_top_row_first)
{
    const char *dir = test_temp_dir();
    /* 3 x 2, row 0 (top) then row 1. */
    const unsigned char rgb[] = {10, 20, 30, 40, 50, 60, 70, 80, 90,
                                 100, 110, 120, 130, 140, 150, 160, 170, 180};
    const char *path = temp_file(dir, "rgb.png");
    cr_assert(stbi_write_png(path, 3, 2, 3, rgb, 3 * 3));
    TextureSet set = {0};
    Error err = {0};
    uint32_t index = texture_set_add(&set, path, &err);
    cr_assert_eq(index, 0, "%s", err.message);
    cr_assert_eq(set.count, 1);
    TextureInfo info = set.infos[0];
    cr_expect_eq(info.format, TEXTURE_RGBA8_SRGB);
    cr_expect_eq(info.width, 3);
    cr_expect_eq(info.height, 2);
    cr_expect_eq(info.offset, 0);
    cr_assert_eq(set.num_texels, 6);
    for (int i = 0; i < 6; i++)
        cr_expect_eq(set.texels[i], pack(rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2], 255),
                     "texel %d: %08x", i, set.texels[i]);
    texture_set_free(&set);
}

Test(texture, grey_and_grey_alpha_expand_to_rgba)
{
    const char *dir = test_temp_dir();
    const unsigned char grey[] = {0, 77, 200, 255};
    const unsigned char grey_alpha[] = {12, 34, 56, 78};
    char grey_path[512], ga_path[512], rgba_path[512];
    snprintf(grey_path, sizeof grey_path, "%s/grey.png", dir);
    snprintf(ga_path, sizeof ga_path, "%s/grey_alpha.png", dir);
    snprintf(rgba_path, sizeof rgba_path, "%s/rgba.tga", dir);
    const unsigned char rgba[] = {1, 2, 3, 4, 250, 251, 252, 0};
    cr_assert(stbi_write_png(grey_path, 2, 2, 1, grey, 2));
    cr_assert(stbi_write_png(ga_path, 2, 1, 2, grey_alpha, 4));
    cr_assert(stbi_write_tga(rgba_path, 2, 1, 4, rgba));
    TextureSet set = {0};
    Error err = {0};
    cr_assert_eq(texture_set_add(&set, grey_path, &err), 0, "%s", err.message);
    cr_assert_eq(texture_set_add(&set, ga_path, &err), 1, "%s", err.message);
    cr_assert_eq(texture_set_add(&set, rgba_path, &err), 2, "%s", err.message);
    for (int i = 0; i < 4; i++)
        cr_expect_eq(set.texels[i], pack(grey[i], grey[i], grey[i], 255), "grey %d", i);
    cr_expect_eq(set.infos[1].offset, 4);
    cr_expect_eq(set.texels[4], pack(12, 12, 12, 34));
    cr_expect_eq(set.texels[5], pack(56, 56, 56, 78));
    cr_expect_eq(set.infos[2].offset, 6);
    cr_expect_eq(set.texels[6], pack(1, 2, 3, 4));
    cr_expect_eq(set.texels[7], pack(250, 251, 252, 0));
    cr_expect_eq(set.num_texels, 8);
    texture_set_free(&set);
}

static float texel_float(const TextureSet *set, uint32_t texture, uint32_t texel, int channel)
{
    float f;
    memcpy(&f, &set->texels[set->infos[texture].offset + 4 * texel + (uint32_t)channel], sizeof f);
    return f;
}

Test(texture, hdr_is_stored_as_linear_float_rgba)
{
    const char *dir = test_temp_dir();
    char png_path[512], hdr_path[512];
    snprintf(png_path, sizeof png_path, "%s/first.png", dir);
    snprintf(hdr_path, sizeof hdr_path, "%s/radiance.hdr", dir);
    const unsigned char one[] = {9, 9, 9};
    cr_assert(stbi_write_png(png_path, 1, 1, 3, one, 3));
    /* Values that RGBE stores exactly (shared exponent, 8-bit mantissas), some above 1. */
    const float rgb[] = {1.0f, 0.5f, 0.25f, 1024.0f, 256.0f, 0.0f, 0.125f, 0.0625f, 0.03125f,
                         3.0f, 2.0f, 1.0f};
    cr_assert(stbi_write_hdr(hdr_path, 2, 2, 3, rgb));
    TextureSet set = {0};
    Error err = {0};
    cr_assert_eq(texture_set_add(&set, png_path, &err), 0, "%s", err.message);
    cr_assert_eq(texture_set_add(&set, hdr_path, &err), 1, "%s", err.message);
    TextureInfo info = set.infos[1];
    cr_expect_eq(info.format, TEXTURE_RGBA32F);
    cr_expect_eq(info.width, 2);
    cr_expect_eq(info.height, 2);
    cr_expect_eq(info.offset, 1, "after the 1-texel PNG");
    cr_expect_eq(set.num_texels, 1 + 4 * 4);
    for (uint32_t t = 0; t < 4; t++) {
        for (int c = 0; c < 3; c++)
            cr_expect_eq(texel_float(&set, 1, t, c), rgb[3 * t + (uint32_t)c], "texel %u channel %d: %g",
                         t, c, (double)texel_float(&set, 1, t, c));
        cr_expect_eq(texel_float(&set, 1, t, 3), 1.0f, "alpha of texel %u", t);
    }
    texture_set_free(&set);
}

Test(texture, same_file_is_added_once)
{
    const char *dir = test_temp_dir();
    char path[512], other_spelling[512], second[512];
    snprintf(path, sizeof path, "%s/t.png", dir);
    snprintf(other_spelling, sizeof other_spelling, "%s/./t.png", dir);
    snprintf(second, sizeof second, "%s/u.png", dir);
    const unsigned char px[] = {1, 2, 3, 4, 5, 6};
    cr_assert(stbi_write_png(path, 2, 1, 3, px, 6));
    cr_assert(stbi_write_png(second, 1, 2, 3, px, 3));
    TextureSet set = {0};
    Error err = {0};
    cr_expect_eq(texture_set_add(&set, path, &err), 0);
    cr_expect_eq(texture_set_add(&set, second, &err), 1);
    cr_expect_eq(texture_set_add(&set, path, &err), 0);
    cr_expect_eq(texture_set_add(&set, other_spelling, &err), 0);
    cr_expect_eq(set.count, 2);
    cr_expect_eq(set.num_texels, 4);
    cr_expect_not(error_is_set(&err), "%s", err.message);
    texture_set_free(&set);
}

Test(texture, missing_and_corrupt_files_are_different_errors)
{
    const char *dir = test_temp_dir();
    char missing[512], corrupt[512];
    snprintf(missing, sizeof missing, "%s/nowhere.png", dir);
    snprintf(corrupt, sizeof corrupt, "%s/garbage.png", dir);
    FILE *f = fopen(corrupt, "wb");
    cr_assert(f);
    fputs("this is not a PNG at all, just bytes", f);
    fclose(f);
    TextureSet set = {0};
    Error err = {0};
    cr_expect_eq(texture_set_add(&set, missing, &err), NO_TEXTURE);
    cr_expect_eq(err.code, ERR_FILE_MISSING, "%s", error_code_name(err.code));
    cr_expect(strstr(err.message, "nowhere.png"), "%s", err.message);
    Error err2 = {0};
    cr_expect_eq(texture_set_add(&set, corrupt, &err2), NO_TEXTURE);
    cr_expect_eq(err2.code, ERR_TEXTURE, "%s", error_code_name(err2.code));
    cr_expect(strstr(err2.message, "garbage.png"), "%s", err2.message);
    cr_expect_eq(set.count, 0);
    texture_set_free(&set);
}

/* ---- Device: texture_sample ---------------------------------------------------------------- */

static double srgb_decode(unsigned value)
{
    double c = value / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

/* The kernels' decode table is the formula in double, rounded to float once: every code. */
Test(texture, srgb_decode_table_is_the_transfer_function_rounded_once)
{
    const float *table = texture_srgb_decode_table();
    for (unsigned code = 0; code < TEXTURE_SRGB_CODES; code++)
        cr_expect_eq(table[code], (float)srgb_decode(code), "code %u: %a against %a", code,
                     (double)table[code], (double)(float)srgb_decode(code));
    cr_expect_eq(table[0], 0.0f);
    cr_expect_eq(table[255], 1.0f);
}

typedef struct {
    double rgba[4];
} Rgba;

static Rgba decoded(const unsigned char *p)
{
    return (Rgba){{srgb_decode(p[0]), srgb_decode(p[1]), srgb_decode(p[2]), p[3] / 255.0}};
}

static Rgba blend(Rgba a, double wa, Rgba b, double wb)
{
    Rgba out;
    for (int i = 0; i < 4; i++)
        out.rgba[i] = wa * a.rgba[i] + wb * b.rgba[i];
    return out;
}

static Rgba average4(Rgba a, Rgba b, Rgba c, Rgba d)
{
    return blend(blend(a, 0.5, b, 0.5), 0.5, blend(c, 0.5, d, 0.5), 0.5);
}

Test(texture, device_sampling_decodes_srgb_filters_repeats_and_flips_v)
{
    const char *dir = test_temp_dir();
    char path[512];
    snprintf(path, sizeof path, "%s/quad.png", dir);
    /* 2 x 2 RGBA; row 0 is the image's top row: A B / C D. */
    const unsigned char px[] = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 255, 200, 100, 30, 0};
    cr_assert(stbi_write_png(path, 2, 2, 4, px, 8));
    TextureSet set = {0};
    Error err = {0};
    cr_assert_eq(texture_set_add(&set, path, &err), 0, "%s", err.message);
    Rgba a = decoded(px), b = decoded(px + 4), c = decoded(px + 8), d = decoded(px + 12);
    const float uv[][2] = {
        {0.25f, 0.75f}, {0.75f, 0.75f}, {0.25f, 0.25f}, {0.75f, 0.25f}, /* texel centres */
        {0.5f, 0.25f},  {0.25f, 0.5f},  {0.5f, 0.5f},                   /* bilinear midpoints */
        {1.25f, 0.75f}, {-0.75f, 0.25f}, {2.75f, -1.75f},              /* repeat */
        {0.25f, 0.0f},  {0.0f, 0.25f},  {0.25f, 0.375f},               /* edges: wrap across */
        {NAN, 0.25f},   {0.75f, INFINITY},                             /* no crash, finite */
    };
    const Rgba expected[] = {
        a, b, c, d,
        blend(c, 0.5, d, 0.5), blend(a, 0.5, c, 0.5), average4(a, b, c, d),
        a, c, d,
        blend(c, 0.5, a, 0.5), blend(c, 0.5, d, 0.5), blend(c, 0.75, a, 0.25),
    };
    enum { CHECKED = sizeof expected / sizeof expected[0] };
    enum { N = sizeof uv / sizeof uv[0] };
    cl_float4 out[N];
    sample_on_device(&set, 0, &uv[0][0], N, out);
    for (int i = CHECKED; i < N; i++)
        for (int ch = 0; ch < 4; ch++) /* any texel blend: inside [0, 1] */
            cr_expect(out[i].s[ch] >= 0.0f && out[i].s[ch] <= 1.0f, "uv %d channel %d: %g", i, ch,
                      (double)out[i].s[ch]);
    for (int i = 0; i < CHECKED; i++)
        for (int ch = 0; ch < 4; ch++)
            cr_expect(fabs(out[i].s[ch] - expected[i].rgba[ch]) < 1e-4,
                      "uv (%g, %g) channel %d: got %g, expected %g", (double)uv[i][0],
                      (double)uv[i][1], ch, (double)out[i].s[ch], expected[i].rgba[ch]);
    texture_set_free(&set);
}

/* An 8-bit image read as linear stays one uint per texel, and the device reads value / 255 with
 * no decoding, bilinear like the rest, at its offset after another texture. At a texel's centre
 * the value is exactly value * (1 / 255), a product, which every device rounds alike (3, 6 and 7
 * over 255 as quotients round to other floats). */
Test(texture, device_sampling_of_8_bit_linear_is_undecoded_at_its_offset)
{
    const char *dir = test_temp_dir();
    char before[512], path[512];
    snprintf(before, sizeof before, "%s/srgb-first.png", dir);
    snprintf(path, sizeof path, "%s/linear.png", dir);
    const unsigned char first[] = {9, 9, 9, 255};
    cr_assert(stbi_write_png(before, 1, 1, 4, first, 4));
    const unsigned char px[] = {255, 128, 3, 64, 6, 7, 200, 255}; /* 2 x 1 RGBA */
    cr_assert(stbi_write_png(path, 2, 1, 4, px, 8));
    TextureSet set = {0};
    Error err = {0};
    cr_assert_eq(texture_set_add(&set, before, &err), 0, "%s", err.message);
    cr_assert_eq(texture_set_add_encoded(&set, path, TEXTURE_ENCODING_LINEAR, &err), 1, "%s",
                 err.message);
    cr_expect_eq(set.infos[1].format, TEXTURE_RGBA8_LINEAR);
    cr_expect_eq(set.num_texels, 3u, "one uint per texel");
    const float uv[][2] = {{0.25f, 0.5f}, {0.75f, 0.5f}, {0.5f, 0.5f}};
    cl_float4 out[3];
    sample_on_device(&set, 1, &uv[0][0], 3, out);
    for (int i = 0; i < 3; i++)
        for (int ch = 0; ch < 4; ch++) {
            double a = px[ch] / 255.0, b = px[4 + ch] / 255.0;
            double expected = i == 0 ? a : i == 1 ? b : 0.5 * (a + b);
            cr_expect(fabs(out[i].s[ch] - expected) < 1e-6, "uv %d channel %d: got %g, expected %g",
                      i, ch, (double)out[i].s[ch], expected);
            if (i < 2) {
                float product = (float)px[4 * i + ch] * (1.0f / 255.0f);
                cr_expect(memcmp(&out[i].s[ch], &product, sizeof product) == 0,
                          "texel %d channel %d: %.9g, not the product %.9g", i, ch,
                          (double)out[i].s[ch], (double)product);
            }
        }
    texture_set_free(&set);
}

Test(texture, device_sampling_of_hdr_is_linear_at_its_offset)
{
    const char *dir = test_temp_dir();
    char png_path[512], hdr_path[512];
    snprintf(png_path, sizeof png_path, "%s/before.png", dir);
    snprintf(hdr_path, sizeof hdr_path, "%s/two.hdr", dir);
    const unsigned char px[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    cr_assert(stbi_write_png(png_path, 3, 1, 3, px, 9));
    const float rgb[] = {4.0f, 2.0f, 1.0f, 0.5f, 0.25f, 0.125f}; /* 2 x 1, exact in RGBE */
    cr_assert(stbi_write_hdr(hdr_path, 2, 1, 3, rgb));
    TextureSet set = {0};
    Error err = {0};
    cr_assert_eq(texture_set_add(&set, png_path, &err), 0, "%s", err.message);
    cr_assert_eq(texture_set_add(&set, hdr_path, &err), 1, "%s", err.message);
    const float uv[][2] = {{0.25f, 0.5f}, {0.75f, 0.5f}, {0.5f, 0.9f}};
    const double expected[][3] = {{4.0, 2.0, 1.0}, {0.5, 0.25, 0.125}, {2.25, 1.125, 0.5625}};
    cl_float4 out[3];
    sample_on_device(&set, 1, &uv[0][0], 3, out);
    for (int i = 0; i < 3; i++) {
        for (int ch = 0; ch < 3; ch++)
            cr_expect(fabs(out[i].s[ch] - expected[i][ch]) < 1e-5, "uv %d channel %d: got %g", i, ch,
                      (double)out[i].s[ch]);
        cr_expect(fabs(out[i].s[3] - 1.0) < 1e-6, "alpha %g", (double)out[i].s[3]);
    }
    texture_set_free(&set);
}
