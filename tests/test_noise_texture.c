// SPDX-License-Identifier: MIT
/* Procedural noise textures (shared/DESIGN.md "Textures": fBm Perlin noise blending color0 to
 * color1 at `frequency` with `octaves`, in object space): texture_eval on the device against a C
 * copy of cl/material/texture.cl's noise at many points; deterministic, within the colours' range,
 * varying with the position and the seed, and image lookups unchanged by texture_eval. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "device/device.h"
#include "support.h"
#include "texture_sampling.h"
#include "xorshift.h"

#ifndef TEXTURE_NOISE
#define TEXTURE_NOISE 2u
#endif

/* ---- The C reference: cl/material/texture.cl's noise, operation for operation ---- */

static uint32_t hash_pcg(uint32_t v)
{
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

static float gradient(uint32_t h, float x, float y, float z)
{
    h &= 15u;
    float u = h < 8u ? x : y;
    float v = h < 4u ? y : (h == 12u || h == 14u ? x : z);
    return ((h & 1u) ? -u : u) + ((h & 2u) ? -v : v);
}

static uint32_t corner(int x, int y, int z, uint32_t seed)
{
    return hash_pcg((uint32_t)x ^ hash_pcg((uint32_t)y ^ hash_pcg((uint32_t)z ^ seed)));
}

static float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
static float lerp(float a, float b, float t) { return a + t * (b - a); }

static float perlin(const float p[3], uint32_t seed)
{
    int c[3];
    float r[3];
    for (int a = 0; a < 3; a++) {
        float f = floorf(p[a]);
        c[a] = (int)f;
        r[a] = p[a] - f;
    }
    float n[2][2][2];
    for (int dz = 0; dz < 2; dz++)
        for (int dy = 0; dy < 2; dy++)
            for (int dx = 0; dx < 2; dx++)
                n[dz][dy][dx] = gradient(corner(c[0] + dx, c[1] + dy, c[2] + dz, seed), r[0] - dx,
                                         r[1] - dy, r[2] - dz);
    float u = fade(r[0]), v = fade(r[1]), w = fade(r[2]);
    float y0 = lerp(lerp(n[0][0][0], n[0][0][1], u), lerp(n[0][1][0], n[0][1][1], u), v);
    float y1 = lerp(lerp(n[1][0][0], n[1][0][1], u), lerp(n[1][1][0], n[1][1][1], u), v);
    return lerp(y0, y1, w);
}

typedef struct {
    float c0[3], c1[3], frequency;
    uint32_t octaves, seed;
} Noise;

static void noise_reference(const Noise *nz, const float p[3], float out[3])
{
    float sum = 0.0f, norm = 0.0f, amplitude = 1.0f, frequency = nz->frequency;
    for (uint32_t i = 0; i < nz->octaves && i < 16u; i++) {
        float x[3] = {p[0] * frequency, p[1] * frequency, p[2] * frequency};
        sum += amplitude * perlin(x, nz->seed + i);
        norm += amplitude;
        amplitude *= 0.5f;
        frequency *= 2.0f;
    }
    float t = fminf(fmaxf(0.5f + 0.5f * (norm > 0.0f ? sum / norm : 0.0f), 0.0f), 1.0f);
    for (int c = 0; c < 3; c++)
        out[c] = nz->c0[c] + t * (nz->c1[c] - nz->c0[c]);
}

/* ---- The device side ---- */

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, 4);
    return u;
}

/* texels: the noise's 9 uints (TEXTURE_NOISE layout) after a 2 x 1 RGBA32F image. */
static void eval_on_device(const Noise *nz, uint32_t index, const cl_float4 *points, uint32_t n,
                           cl_float4 *out)
{
    uint32_t texels[8 + 9] = {0};
    float image[8] = {0.25f, 0.5f, 0.75f, 1.0f, 0.0f, 0.125f, 1.0f, 0.5f};
    memcpy(texels, image, sizeof image);
    uint32_t *q = texels + 8;
    for (int c = 0; c < 3; c++)
        q[c] = float_bits(nz->c0[c]), q[3 + c] = float_bits(nz->c1[c]);
    q[6] = float_bits(nz->frequency), q[7] = nz->octaves, q[8] = nz->seed;
    TextureInfo infos[2] = {{.offset = 0, .width = 2, .height = 1, .format = TEXTURE_RGBA32F},
                            {.offset = 8, .width = 1, .height = 1, .format = TEXTURE_NOISE}};
    run_texture_kernel("eval_texture_at_points", texels, sizeof texels, infos, 2, index, points,
                       n * sizeof(cl_float4), n, out);
}

#define N 4096
static cl_float4 g_points[N], g_out[N], g_again[N];

static void random_points(uint64_t seed, float scale)
{
    uint64_t s = seed;
    for (int i = 0; i < N; i++)
        for (int a = 0; a < 3; a++)
            g_points[i].s[a] = (float)((xorshift_next(&s) * (1.0 / 4294967296.0) * 2.0 - 1.0) * scale);
}

static const Noise MARBLE = {{0.9f, 0.9f, 0.9f}, {0.2f, 0.2f, 0.3f}, 4.0f, 5, 1};

Test(noise_texture, matches_the_c_reference_and_stays_in_range, .timeout = 120)
{
    random_points(12345, 3.0f);
    eval_on_device(&MARBLE, 1, g_points, N, g_out);
    double worst = 0.0, lo = 1.0, hi = 0.0;
    for (int i = 0; i < N; i++) {
        float want[3];
        noise_reference(&MARBLE, g_points[i].s, want);
        for (int c = 0; c < 3; c++) {
            worst = fmax(worst, fabs(g_out[i].s[c] - want[c]));
            cr_assert(g_out[i].s[c] >= fminf(MARBLE.c0[c], MARBLE.c1[c]) - 1e-6f &&
                          g_out[i].s[c] <= fmaxf(MARBLE.c0[c], MARBLE.c1[c]) + 1e-6f,
                      "point %d channel %d: %g outside the colours", i, c, g_out[i].s[c]);
        }
        cr_assert_eq(g_out[i].s[3], 1.0f);
        lo = fmin(lo, g_out[i].s[2]), hi = fmax(hi, g_out[i].s[2]);
    }
    cr_expect(worst < 1e-4, "device and reference differ by %g", worst);
    /* Not a constant: the blend spans a good part of [color1, color0]. */
    cr_expect(hi - lo > 0.2, "blue spans only [%g, %g]", lo, hi);
}

Test(noise_texture, deterministic_and_seeded, .timeout = 120)
{
    random_points(777, 10.0f);
    eval_on_device(&MARBLE, 1, g_points, N, g_out);
    eval_on_device(&MARBLE, 1, g_points, N, g_again);
    cr_assert(memcmp(g_out, g_again, sizeof g_out) == 0, "two evaluations differ");
    Noise other = MARBLE;
    other.seed = 2;
    eval_on_device(&other, 1, g_points, N, g_again);
    int same = 0;
    for (int i = 0; i < N; i++)
        same += g_out[i].s[0] == g_again[i].s[0];
    cr_expect(same < N / 100, "%d of %d points do not change with the seed", same, N);
}

Test(noise_texture, image_textures_are_looked_up_at_uv_as_before, .timeout = 120)
{
    /* Texture 0, 2 x 1: at u = 0.25 and 0.75 the texel centres, whatever the position. */
    cl_float4 pts[2] = {{{5.0f, -3.0f, 2.0f, 0.25f}}, {{-1.0f, 7.0f, 0.5f, 0.75f}}};
    cl_float4 out[2];
    eval_on_device(&MARBLE, 0, pts, 2, out);
    const float want[2][4] = {{0.25f, 0.5f, 0.75f, 1.0f}, {0.0f, 0.125f, 1.0f, 0.5f}};
    for (int i = 0; i < 2; i++)
        for (int c = 0; c < 4; c++)
            cr_expect(fabsf(out[i].s[c] - want[i][c]) < 1e-6f, "texel %d channel %d: %g", i, c,
                      out[i].s[c]);
}
