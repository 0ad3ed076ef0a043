/* SPDX-License-Identifier: MIT */
/* texture.cl: texture lookups on the packed texel buffer (host/scene/texture.h). Bilinear filtering,
 * repeat wrapping; 8-bit sRGB texels are decoded before filtering. OBJ's v = 0 is the image's
 * bottom row, and row 0 of the stored image is its top. A texture with TextureInfo.flags (wrap
 * modes, nearest, a uv transform, a channel, a scale: glTF's samplers and textureInfos) takes
 * texture_sample_flagged; flags 0 keeps the plain path's code. Each format's decoding and the
 * flagged path are compiled only where the scene has such a texture (FLOAT_TEXTURE, SRGB_TEXTURE,
 * TEXTURE_SAMPLER: cl/shared/features.h), since every lookup inlines them. */

/* texels: the scene's texel words; srgb: its srgb_decode table, each 8-bit code's linear value
 * (host/scene/texture.h): correctly rounded and the same on every device, and a load where the
 * transfer function would cost a pow per channel, twelve per bilinear lookup. */
inline float4 texel_fetch(const global uint *texels, const global float *srgb, TextureInfo info,
                          int x, int y)
{
    uint index = (uint)y * info.width + (uint)x;
    if (PT_FEATURE(FLOAT_TEXTURE) && info.format == TEXTURE_RGBA32F) {
        const global uint *p = texels + info.offset + 4u * index;
        return (float4)(as_float(p[0]), as_float(p[1]), as_float(p[2]), as_float(p[3]));
    }
    uint packed = texels[info.offset + index];
    uint r = packed & 0xffu, g = (packed >> 8) & 0xffu, b = (packed >> 16) & 0xffu;
    /* A product, not a quotient: the same bits on every device (NVIDIA's division, within 2.5
     * ulp, is not correctly rounded unless PT_EXACT_MATHS). */
    float a = (float)(packed >> 24) * (1.0f / 255.0f);
    if (PT_FEATURE(SRGB_TEXTURE) && info.format == TEXTURE_RGBA8_SRGB)
        return (float4)(srgb[r], srgb[g], srgb[b], a);
    return (float4)((float)r * (1.0f / 255.0f), (float)g * (1.0f / 255.0f),
                    (float)b * (1.0f / 255.0f), a);
}

/* The four texels around a point, weighted by its fractions ax (towards x1) and ay (y1). */
inline float4 texel_bilinear(const global uint *texels, const global float *srgb, TextureInfo info,
                             int x0, int x1, int y0, int y1, float ax, float ay)
{
    float4 top = mix(texel_fetch(texels, srgb, info, x0, y0),
                     texel_fetch(texels, srgb, info, x1, y0), ax);
    float4 bottom = mix(texel_fetch(texels, srgb, info, x0, y1),
                        texel_fetch(texels, srgb, info, x1, y1), ax);
    return mix(top, bottom, ay);
}

inline int wrap_coord(int i, int n)
{
    int r = i % n;
    return r < 0 ? r + n : r;
}

/* wrap_coord for i in [-n, 2n), without its integer division (dozens of instructions on a GPU):
 * the corners of texture_sample's bilinear lookup, whose coordinate is clamped to the texture. */
inline int wrap_near(int i, int n) { return i < 0 ? i + n : (i >= n ? i - n : i); }

/* A coordinate brought into the wrap mode's period: [0, 1) repeating, [0, 2) mirrored (the second
 * unit runs backwards), [0, 1] clamped. */
inline float wrap_unit(float t, uint wrap)
{
    if (wrap == TEXTURE_WRAP_CLAMP)
        return clamp(t, 0.0f, 1.0f);
    if (wrap == TEXTURE_WRAP_MIRROR)
        return t - 2.0f * floor(0.5f * t);
    return t - floor(t);
}

/* A texel index of the infinite lattice mapped into [0, n): repeated, clamped to the edge, or
 * mirrored (period 2n: index -1 is texel 0, n is texel n - 1). */
inline int wrap_index(int i, int n, uint wrap)
{
    if (wrap == TEXTURE_WRAP_CLAMP)
        return clamp(i, 0, n - 1);
    if (wrap == TEXTURE_WRAP_MIRROR) {
        int r = wrap_coord(i, 2 * n);
        return r < n ? r : 2 * n - 1 - r;
    }
    return wrap_coord(i, n);
}

/* texture_sample with the sampling of info.flags (cl/shared/material.h TEXTURE_FLAG_*). The same
 * texel convention as the plain path: v flipped, texel centres at half-integers. */
float4 texture_sample_flagged(const global uint *texels, const global float *srgb,
                              TextureInfo info, float2 uv)
{
    uint flags = info.flags;
    if (flags & TEXTURE_FLAG_TRANSFORM)
        uv = (float2)(info.transform[0] * uv.x + info.transform[1] * uv.y + info.transform[2],
                      info.transform[3] * uv.x + info.transform[4] * uv.y + info.transform[5]);
    uint wrap_s = TEXTURE_FLAG_WRAP_S(flags), wrap_t = TEXTURE_FLAG_WRAP_T(flags);
    int w = (int)info.width, h = (int)info.height;
    /* Within +-2 periods whatever uv was (NaN included: fmax picks the number), so that the
     * float-to-int conversions below stay defined. */
    float x = fmin(fmax(wrap_unit(uv.x, wrap_s) * (float)w, -2.0f * w), 2.0f * w);
    float y = fmin(fmax((1.0f - wrap_unit(uv.y, wrap_t)) * (float)h, -2.0f * h), 2.0f * h);
    float4 c;
    if (flags & TEXTURE_FLAG_NEAREST) {
        c = texel_fetch(texels, srgb, info, wrap_index((int)floor(x), w, wrap_s),
                        wrap_index((int)floor(y), h, wrap_t));
    } else {
        float fx = floor(x - 0.5f), fy = floor(y - 0.5f);
        float ax = x - 0.5f - fx, ay = y - 0.5f - fy;
        int x0 = wrap_index((int)fx, w, wrap_s), x1 = wrap_index((int)fx + 1, w, wrap_s);
        int y0 = wrap_index((int)fy, h, wrap_t), y1 = wrap_index((int)fy + 1, h, wrap_t);
        c = texel_bilinear(texels, srgb, info, x0, x1, y0, y1, ax, ay);
    }
    uint channel = TEXTURE_FLAG_CHANNEL(flags);
    c.x = channel == 1u ? c.y : channel == 2u ? c.z : channel == 3u ? c.w : c.x;
    if (flags & TEXTURE_FLAG_SCALE)
        c = (float4)(c.x * info.scale, c.y * info.scale, c.z * info.scale, c.w);
    return c;
}

float4 texture_sample(const SceneView *scene, uint index, float2 uv)
{
    const global uint *texels = scene->texels;
    const global float *srgb = scene->srgb_decode;
    TextureInfo info = scene->textures[index];
    if (PT_FEATURE(TEXTURE_SAMPLER) && info.flags != 0u)
        return texture_sample_flagged(texels, srgb, info, uv);
    /* Texel centres sit at half-integer coordinates; flip v so v = 0 is the bottom row. The
     * fmin/fmax keep a NaN or infinite uv (and rounding of the fraction up to 1) from reaching the
     * float-to-int conversions below, whose out-of-range result is undefined. */
    float w = (float)info.width, h = (float)info.height;
    float x = fmin(fmax((uv.x - floor(uv.x)) * w - 0.5f, -0.5f), w - 0.5f);
    float y = fmin(fmax((1.0f - (uv.y - floor(uv.y))) * h - 0.5f, -0.5f), h - 0.5f);
    float fx = floor(x), fy = floor(y);
    float ax = x - fx, ay = y - fy;
    int x0 = wrap_near((int)fx, (int)info.width), x1 = wrap_near((int)fx + 1, (int)info.width);
    int y0 = wrap_near((int)fy, (int)info.height), y1 = wrap_near((int)fy + 1, (int)info.height);
    return texel_bilinear(texels, srgb, info, x0, x1, y0, y1, ax, ay);
}

/* ---- Procedural noise (TEXTURE_NOISE) ------------------------------------------------------ */

#ifndef TEXTURE_NOISE /* cl/shared.h defines it with the host's JSON textures */
#define TEXTURE_NOISE 2u
#endif
#define NOISE_MAX_OCTAVES 16u

/* Improved Perlin noise (Perlin 2002, "Improving Noise"): the 12 edge gradients, chosen per lattice
 * corner by a hash of (x, y, z, seed) instead of a permutation table, so that every seed is its own
 * noise and nothing but the texel buffer is read. tests/test_noise_texture.c has a C copy. */
inline float noise_gradient(uint h, float x, float y, float z)
{
    h &= 15u;
    float u = h < 8u ? x : y;
    float v = h < 4u ? y : (h == 12u || h == 14u ? x : z);
    return ((h & 1u) ? -u : u) + ((h & 2u) ? -v : v);
}

inline uint noise_corner_hash(int x, int y, int z, uint seed)
{
    return hash_pcg((uint)x ^ hash_pcg((uint)y ^ hash_pcg((uint)z ^ seed)));
}

inline float noise_fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

/* In about [-1, 1]; p within +-2^24 (texture_noise clamps). */
inline float perlin_noise(float3 p, uint seed)
{
    float3 f = floor(p);
    int x = (int)f.x, y = (int)f.y, z = (int)f.z;
    float3 r = p - f;
    float n000 = noise_gradient(noise_corner_hash(x, y, z, seed), r.x, r.y, r.z);
    float n100 = noise_gradient(noise_corner_hash(x + 1, y, z, seed), r.x - 1.0f, r.y, r.z);
    float n010 = noise_gradient(noise_corner_hash(x, y + 1, z, seed), r.x, r.y - 1.0f, r.z);
    float n110 = noise_gradient(noise_corner_hash(x + 1, y + 1, z, seed), r.x - 1.0f, r.y - 1.0f, r.z);
    float n001 = noise_gradient(noise_corner_hash(x, y, z + 1, seed), r.x, r.y, r.z - 1.0f);
    float n101 = noise_gradient(noise_corner_hash(x + 1, y, z + 1, seed), r.x - 1.0f, r.y, r.z - 1.0f);
    float n011 = noise_gradient(noise_corner_hash(x, y + 1, z + 1, seed), r.x, r.y - 1.0f, r.z - 1.0f);
    float n111 = noise_gradient(noise_corner_hash(x + 1, y + 1, z + 1, seed), r.x - 1.0f, r.y - 1.0f,
                                r.z - 1.0f);
    float u = noise_fade(r.x), v = noise_fade(r.y), w = noise_fade(r.z);
    float nx00 = n000 + u * (n100 - n000), nx10 = n010 + u * (n110 - n010);
    float nx01 = n001 + u * (n101 - n001), nx11 = n011 + u * (n111 - n011);
    float nxy0 = nx00 + v * (nx10 - nx00), nxy1 = nx01 + v * (nx11 - nx01);
    return nxy0 + w * (nxy1 - nxy0);
}

/* fBm in [0, 1]: octave i has frequency frequency * 2^i, amplitude 2^-i and seed seed + i; the
 * sum over the amplitudes' sum, mapped from [-1, 1] to [0, 1] (also the accretion disks' noise). */
inline float noise_fbm(float3 position, float frequency, uint octaves, uint seed)
{
    float sum = 0.0f, norm = 0.0f, amplitude = 1.0f;
    for (uint i = 0u; i < octaves; i++) {
        float3 x = position * frequency;
        if (all(isfinite(x)))
            sum += amplitude * perlin_noise(clamp(x, -16777216.0f, 16777216.0f), seed + i);
        norm += amplitude;
        amplitude *= 0.5f;
        frequency *= 2.0f;
    }
    return clamp(0.5f + 0.5f * (norm > 0.0f ? sum / norm : 0.0f), 0.0f, 1.0f);
}

/* fBm (noise_fbm): octave i has frequency frequency * 2^i, amplitude 2^-i and seed seed + i; the sum over the
 * amplitudes' sum, mapped from [-1, 1] to the blend factor [0, 1] between color0 and color1.
 * Evaluated at the hit's object-space position (SurfaceHit.object_position): noise stays on an
 * instance as it moves. Objects merged into the world-space mesh (no transform, or --instancing
 * never) have world space as their object space. */
inline float4 texture_noise(const global uint *texels, TextureInfo info, float3 position)
{
    const global uint *q = texels + info.offset;
    float3 c0 = (float3)(as_float(q[0]), as_float(q[1]), as_float(q[2]));
    float3 c1 = (float3)(as_float(q[3]), as_float(q[4]), as_float(q[5]));
    float frequency = as_float(q[6]);
    float t = noise_fbm(position, frequency, min(q[7], NOISE_MAX_OCTAVES), q[8]);
    return (float4)(c0 + t * (c1 - c0), 1.0f);
}

/* Any texture at a hit: image textures at uv (texture_sample), procedural ones at the position. */
inline float4 texture_eval(const SceneView *scene, uint index, float2 uv, float3 position)
{
    TextureInfo info = scene->textures[index];
    if (PT_FEATURE(NOISE_TEXTURE) && info.format == TEXTURE_NOISE)
        return texture_noise(scene->texels, info, position);
    return texture_sample(scene, index, uv);
}
