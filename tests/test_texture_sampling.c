// SPDX-License-Identifier: MIT
/* Texture sampling modes (cl/shared/material.h TEXTURE_FLAG_*: glTF's samplers and textureInfos):
 * on the device, texture_sample with clamp, mirrored and repeating wrap per axis, nearest and
 * bilinear filtering, a uv transform, a channel moved to x and a scale matches a host reference
 * that works on the unreduced texel lattice (GL's definition of the wrap modes); a
 * KHR_texture_transform converted to pt's uv frame samples the texel glTF's frame names; the
 * sampled views share the image's texels and are added once. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/gltf_texture.h"
#include "scene/texture.h"
#include "texture_sampling.h"

#define W 4
#define H 2

/* Texel (i, j) (row 0 the top) of the test image: every channel different, alpha too. */
static double texel(int i, int j, int c)
{
    double id = i + W * j;
    return c == 3 ? 0.05 + 0.1 * id : id * (c == 0 ? 1.0 : c == 1 ? 10.0 : 100.0);
}

/* A W x H linear float image in a fresh set (index 0). */
static void image_set(TextureSet *set)
{
    memset(set, 0, sizeof *set);
    float rgba[W * H * 4];
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            for (int c = 0; c < 4; c++)
                rgba[4 * (j * W + i) + c] = (float)texel(i, j, c);
    set->texels = malloc(sizeof rgba);
    cr_assert(set->texels);
    memcpy(set->texels, rgba, sizeof rgba);
    set->num_texels = W * H * 4;
    TextureInfo info = {.offset = 0, .width = W, .height = H, .format = TEXTURE_RGBA32F};
    TextureStats stats = {.channels = 4, .mean = {1.0f, 1.0f, 1.0f}};
    cr_assert(texture_set_append(set, &info, &stats, "(test image)"));
}

/* GL's wrap of a texel index (OpenGL 4.6, 8.14.2), independent of the kernel's code. */
static int wrap_ref(int i, int n, uint32_t wrap)
{
    if (wrap == TEXTURE_WRAP_CLAMP)
        return i < 0 ? 0 : i >= n ? n - 1 : i;
    int m = ((i % (2 * n)) + 2 * n) % (2 * n);
    if (wrap == TEXTURE_WRAP_MIRROR) { /* (size - 1) - mirror((i mod 2 size) - size) */
        int a = m - n;
        return (n - 1) - (a >= 0 ? a : -(1 + a));
    }
    return m % n;
}

/* The reference sample at pt's uv (v up: row index from 1 - v). */
static void reference(const TextureSampling *s, double u, double v, double out[4])
{
    if (s->has_transform) {
        const float *t = s->transform;
        double u2 = t[0] * u + t[1] * v + t[2], v2 = t[3] * u + t[4] * v + t[5];
        u = u2, v = v2;
    }
    double x = u * W, y = (1.0 - v) * H;
    double c[4] = {0, 0, 0, 0};
    if (s->nearest) {
        int i = wrap_ref((int)floor(x), W, s->wrap_s), j = wrap_ref((int)floor(y), H, s->wrap_t);
        for (int k = 0; k < 4; k++)
            c[k] = texel(i, j, k);
    } else {
        double fx = floor(x - 0.5), fy = floor(y - 0.5), ax = x - 0.5 - fx, ay = y - 0.5 - fy;
        for (int dj = 0; dj < 2; dj++)
            for (int di = 0; di < 2; di++) {
                int i = wrap_ref((int)fx + di, W, s->wrap_s), j = wrap_ref((int)fy + dj, H, s->wrap_t);
                double w = (di ? ax : 1.0 - ax) * (dj ? ay : 1.0 - ay);
                for (int k = 0; k < 4; k++)
                    c[k] += w * texel(i, j, k);
            }
    }
    if (s->channel)
        c[0] = c[s->channel];
    double scale = s->has_scale ? s->scale : 1.0;
    for (int k = 0; k < 4; k++)
        out[k] = k < 3 ? c[k] * scale : c[k];
}

/* Off texel centres and edges, inside and outside [0, 1]. */
static const float UVS[][2] = {
    {0.1f, 0.3f},   {0.37f, 0.81f}, {0.9f, 0.05f},  {1.2f, 1.3f},   {1.7f, -0.4f}, {2.6f, 2.2f},
    {-0.3f, 0.6f},  {-1.4f, -1.15f}, {0.55f, 1.9f}, {3.05f, -2.7f}, {0.02f, 0.98f}, {0.99f, 0.51f},
};
#define NUV ((uint32_t)(sizeof UVS / sizeof UVS[0]))

static void expect_matches_reference(const TextureSampling *s, const char *what)
{
    TextureSet set;
    image_set(&set);
    Error err = {0};
    uint32_t index = texture_set_add_sampled(&set, 0, s, &err);
    cr_assert_eq(index, 1u, "%s: %s", what, err.message);
    cr_expect_eq(set.infos[1].offset, set.infos[0].offset, "%s: shares the image's texels", what);
    cr_expect_eq(texture_set_add_sampled(&set, 0, s, &err), 1u, "%s: added once", what);
    cl_float4 out[NUV];
    sample_on_device(&set, index, &UVS[0][0], NUV, out);
    for (uint32_t n = 0; n < NUV; n++) {
        double ref[4];
        reference(s, UVS[n][0], UVS[n][1], ref);
        for (int k = 0; k < 4; k++)
            cr_expect(fabs(out[n].s[k] - ref[k]) < 1e-3 * (1.0 + fabs(ref[k])),
                      "%s: uv (%g, %g) channel %d: %g, expected %g", what, (double)UVS[n][0],
                      (double)UVS[n][1], k, (double)out[n].s[k], ref[k]);
    }
    texture_set_free(&set);
}

Test(texture_sampling, clamp_to_edge_bilinear)
{
    TextureSampling s = {.wrap_s = TEXTURE_WRAP_CLAMP, .wrap_t = TEXTURE_WRAP_CLAMP};
    expect_matches_reference(&s, "clamp");
}

Test(texture_sampling, mirrored_repeat_bilinear)
{
    TextureSampling s = {.wrap_s = TEXTURE_WRAP_MIRROR, .wrap_t = TEXTURE_WRAP_MIRROR};
    expect_matches_reference(&s, "mirror");
}

Test(texture_sampling, wrap_modes_per_axis_with_nearest)
{
    TextureSampling a = {.wrap_s = TEXTURE_WRAP_CLAMP, .wrap_t = TEXTURE_WRAP_MIRROR, .nearest = true};
    expect_matches_reference(&a, "clamp s, mirror t, nearest");
    TextureSampling b = {.wrap_s = TEXTURE_WRAP_MIRROR, .wrap_t = TEXTURE_WRAP_REPEAT, .nearest = true};
    expect_matches_reference(&b, "mirror s, repeat t, nearest");
}

Test(texture_sampling, uv_transform_then_wrap)
{
    double r = 0.5235987755982988; /* 30 degrees */
    TextureSampling s = {.wrap_s = TEXTURE_WRAP_MIRROR, .has_transform = true,
                         .transform = {(float)(2.0 * cos(r)), (float)(-0.5 * sin(r)), 0.1f,
                                       (float)(2.0 * sin(r)), (float)(0.5 * cos(r)), -0.2f}};
    expect_matches_reference(&s, "transform");
}

Test(texture_sampling, channel_to_x_and_scale)
{
    TextureSampling g = {.channel = 1, .has_scale = true, .scale = 0.5f};
    expect_matches_reference(&g, "channel g times 0.5");
    TextureSampling b = {.channel = 2};
    expect_matches_reference(&b, "channel b");
    TextureSampling a = {.channel = 3, .has_scale = true, .scale = 0.25f};
    expect_matches_reference(&a, "channel a times 0.25");
}

/* The plain path (flags 0) and the flagged one agree on repeat + bilinear. */
Test(texture_sampling, flagged_repeat_matches_the_plain_path)
{
    TextureSet set;
    image_set(&set);
    Error err = {0};
    TextureSampling plain = {0}, scaled = {.has_scale = true, .scale = 2.0f};
    cr_expect_eq(texture_set_add_sampled(&set, 0, &plain, &err), 0u, "plain is the image itself");
    uint32_t index = texture_set_add_sampled(&set, 0, &scaled, &err);
    cl_float4 a[NUV], b[NUV];
    sample_on_device(&set, 0, &UVS[0][0], NUV, a);
    sample_on_device(&set, index, &UVS[0][0], NUV, b);
    for (uint32_t n = 0; n < NUV; n++)
        for (int k = 0; k < 4; k++)
            cr_expect(fabsf(b[n].s[k] - (k < 3 ? 2.0f : 1.0f) * a[n].s[k]) < 1e-3f * (1.0f + fabsf(b[n].s[k])),
                      "uv %u channel %d: %g vs %g", n, k, (double)b[n].s[k], (double)a[n].s[k]);
    texture_set_free(&set);
}

/* KHR_texture_transform in glTF's frame (uv origin at the image's top left): with nearest
 * filtering and repeat, pt's lookup at (u, 1 - v) must give the texel glTF's transformed uv
 * falls in, floor(u' W), floor(v' H) counted from the top. */
Test(texture_sampling, gltf_transform_samples_the_texel_gltf_names)
{
    GltfTextureRef ref = {.has_transform = true, .offset = {0.3f, -0.15f}, .rotation = 0.4f,
                          .scale = {1.5f, 0.75f}};
    TextureSampling s = {.nearest = true, .has_transform = true};
    gltf_transform_to_pt(&ref, s.transform);
    TextureSet set;
    image_set(&set);
    Error err = {0};
    uint32_t index = texture_set_add_sampled(&set, 0, &s, &err);
    float pt_uv[NUV][2];
    for (uint32_t n = 0; n < NUV; n++)
        pt_uv[n][0] = UVS[n][0], pt_uv[n][1] = 1.0f - UVS[n][1];
    cl_float4 out[NUV];
    sample_on_device(&set, index, &pt_uv[0][0], NUV, out);
    double c = cos(ref.rotation), sn = sin(ref.rotation);
    for (uint32_t n = 0; n < NUV; n++) {
        double u = UVS[n][0] * ref.scale[0], v = UVS[n][1] * ref.scale[1];
        double u2 = c * u + sn * v + ref.offset[0], v2 = -sn * u + c * v + ref.offset[1];
        if (fabs(u2 * W - round(u2 * W)) < 1e-3 || fabs(v2 * H - round(v2 * H)) < 1e-3)
            continue; /* on a texel edge: float rounding may pick either side */
        int i = wrap_ref((int)floor(u2 * W), W, 0), j = wrap_ref((int)floor(v2 * H), H, 0);
        cr_expect(fabs(out[n].s[0] - texel(i, j, 0)) < 1e-4,
                  "glTF uv (%g, %g) -> (%g, %g): texel %g, expected texel (%d, %d) = %g",
                  (double)UVS[n][0], (double)UVS[n][1], u2, v2, (double)out[n].s[0], i, j,
                  texel(i, j, 0));
    }
    texture_set_free(&set);
}
