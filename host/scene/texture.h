/* SPDX-License-Identifier: MIT */
/* texture.h: textures packed into one texel buffer with per-texture offset, size and format
 * (cl/shared.h TextureInfo). 8-bit images (stb_image) stay 8-bit, sRGB-encoded (the kernel decodes
 * when sampling) or linear; .hdr (stb_image) and .exr (io/image_io.h) are stored as linear 32-bit
 * floats. Procedural noise textures store their parameters. Beside
 * the kernel's TextureInfo, the host keeps what material checks need (TextureStats). */
#ifndef PT_TEXTURE_H
#define PT_TEXTURE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "base/shared_types.h"

/* shared/DESIGN.md "Textures": the default is sRGB for 8-bit images and linear for .hdr/.exr. */
typedef enum { TEXTURE_ENCODING_DEFAULT, TEXTURE_ENCODING_SRGB, TEXTURE_ENCODING_LINEAR } TextureEncoding;

typedef struct {
    int channels;         /* in the file (1 grey, 2 grey-alpha, 3 rgb, 4 rgba); noise: 3 */
    bool alpha_below_one; /* some texel's alpha is below 1 (an RGBA map_Kd with cut-outs) */
    float mean[3];        /* linear rgb averaged over the texels (noise: the colours' midpoint) */
} TextureStats;

typedef struct {
    float color0[3], color1[3];
    float frequency;
    uint32_t octaves, seed;
} TextureNoise;

typedef struct {
    uint32_t *texels; /* see TEXTURE_RGBA8_SRGB / TEXTURE_RGBA32F / TEXTURE_NOISE / TEXTURE_RGBA8_LINEAR */
    size_t num_texels; /* in uints */
    TextureInfo *infos;
    TextureStats *stats; /* per texture, host only */
    uint32_t count;
    char **paths; /* for de-duplication: resolved path and encoding */
} TextureSet;

/* Adds the image at path with its default encoding (or finds it if already added) and returns its
 * index. A missing file is ERR_FILE_MISSING, an unreadable or corrupt one ERR_TEXTURE; both return
 * NO_TEXTURE. */
uint32_t texture_set_add(TextureSet *set, const char *path, Error *err);
/* The same with an explicit encoding; the same file with two encodings is stored twice. */
uint32_t texture_set_add_encoded(TextureSet *set, const char *path, TextureEncoding encoding,
                                 Error *err);
/* Adds an encoded image held in memory (a glTF's embedded PNG or JPEG); `name` is its key (the
 * same name and encoding are added once) and names it in messages. Corrupt bytes are
 * ERR_TEXTURE. */
uint32_t texture_set_add_memory(TextureSet *set, const unsigned char *bytes, size_t size,
                                const char *name, TextureEncoding encoding, Error *err);
/* Adds a noise texture (never shared). `name` is for messages. */
uint32_t texture_set_add_noise(TextureSet *set, const TextureNoise *noise, const char *name,
                               Error *err);
/* How a texture is sampled (cl/shared/material.h TEXTURE_FLAG_*). All zero is the plain lookup:
 * bilinear, repeating, rgba as stored, no transform, scale 1. */
typedef struct {
    uint32_t wrap_s, wrap_t; /* TEXTURE_WRAP_* */
    bool nearest;
    uint32_t channel;        /* 0..3: r, g, b or a becomes x (what a scalar parameter reads) */
    bool has_scale;
    float scale;             /* multiplies rgb */
    bool has_transform;
    float transform[6];      /* uv' = (t0 u + t1 v + t2, t3 u + t4 v + t5), pt's uv frame */
} TextureSampling;

/* Whether s is the plain lookup (no TextureInfo flags). */
bool texture_sampling_is_plain(const TextureSampling *s);
/* The texture `image` (an index of set) sampled as s: a TextureInfo sharing its texels, added once
 * per distinct (image, s); image itself when s is plain. Its stats are the image's, the mean
 * scaled. */
uint32_t texture_set_add_sampled(TextureSet *set, uint32_t image, const TextureSampling *s,
                                 Error *err);
/* The texture added under key (a resolved path and encoding, ...), or NO_TEXTURE; and the
 * appending of one entry under its key (false: out of memory). For the set's own files. */
uint32_t texture_set_find_key(const TextureSet *set, const char *key);
bool texture_set_append(TextureSet *set, const TextureInfo *info, const TextureStats *stats,
                        const char *key);
/* Luminance of the texture's mean colour (the emission weight of a textured emitter). */
float texture_mean_luminance(const TextureSet *set, uint32_t index);
void texture_set_free(TextureSet *set);

/* TEXTURE_SRGB_CODES floats: the linear value of each 8-bit sRGB code, computed in double and
 * rounded once, which the kernels read (cl/material/texture.cl texel_fetch) instead of evaluating
 * the transfer function per channel: correctly rounded, and the same on every device. */
const float *texture_srgb_decode_table(void);

#endif
