// SPDX-License-Identifier: MIT
#define _XOPEN_SOURCE 700 /* realpath */
#include "scene/texture.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "base/fs.h"
#include "io/image_checks.h"
#include "io/image_io.h"
#include "io/input_file.h"
#include "scene/srgb_decode_table.h"

/* Every offset and texel index is a uint in the kernel (and RGBA32F indices are multiplied by 4),
 * so the whole texel buffer is capped at 2^31 uints (8 GiB). */
#define TEXEL_BUFFER_LIMIT ((size_t)1 << 31)
/* One texture may declare at most 8192 x 8192 texels (1 GiB as floats): checked on the header
 * before decoding, so a tiny file declaring a huge image is refused without allocating. */
#define TEXTURE_MAX_TEXELS ((uint64_t)1 << 26)

/* Finds a texture already added under the same file (compared after realpath, so "a/../t.png" and
 * "t.png" share one copy). */
uint32_t texture_set_find_key(const TextureSet *set, const char *key)
{
    for (uint32_t i = 0; i < set->count; i++)
        if (strcmp(set->paths[i], key) == 0)
            return i;
    return NO_TEXTURE;
}

/* Decoded image, before packing: either 8-bit RGBA or float RGBA (stb expands grey and grey-alpha
 * to RGBA and fills a missing alpha with opaque). 8-bit rgb is sRGB-encoded unless linear8. */
typedef struct {
    int width, height, channels;
    unsigned char *rgba8;
    float *rgba32f;
    bool linear8;
} DecodedImage;

/* An OpenEXR image through io/exr_read.c (the reader the environment map uses): rgb, opaque. */
static bool decode_exr(const char *path, DecodedImage *img, Error *err)
{
    float *rgb = NULL;
    Error read_err = {0};
    if (!image_read_exr(path, &rgb, &img->width, &img->height, &read_err)) {
        error_set(err, read_err.code == ERR_FILE_MISSING ? ERR_FILE_MISSING : ERR_TEXTURE, path, 0,
                  "%s", read_err.message);
        return false;
    }
    size_t texels = (size_t)img->width * (size_t)img->height;
    if ((uint64_t)texels > TEXTURE_MAX_TEXELS || !(img->rgba32f = malloc(texels * 4 * sizeof(float)))) {
        free(rgb);
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: %dx%d texture is over the limit of %llu texels",
                  path, img->width, img->height, (unsigned long long)TEXTURE_MAX_TEXELS);
        return false;
    }
    for (size_t i = 0; i < texels; i++) {
        for (int c = 0; c < 3; c++)
            img->rgba32f[4 * i + c] = rgb[3 * i + c];
        img->rgba32f[4 * i + 3] = 1.0f;
    }
    free(rgb);
    img->channels = 3;
    return true;
}

/* An encoded image (PNG, JPEG, TGA, BMP, HDR) in memory; path names it in messages. */
static bool decode_bytes(const stbi_uc *bytes, size_t size, const char *path, DecodedImage *img,
                         Error *err)
{
    int length = size > INT_MAX ? INT_MAX : (int)size, channels = 0;
    bool ok = false;
    const char *problem = NULL;
    /* Before stbi_info, which already builds a JPEG's Huffman tables. */
    if ((problem = image_check_jpeg(bytes, (size_t)length))) {
        error_set(err, ERR_TEXTURE, path, 0, "%s: corrupt JPEG texture: %s", path, problem);
    } else if ((problem = image_check_png(bytes, (size_t)length))) {
        error_set(err, ERR_TEXTURE, path, 0, "%s: corrupt PNG texture: %s", path, problem);
    } else if (!stbi_info_from_memory(bytes, length, &img->width, &img->height, &channels)) {
        error_set(err, ERR_TEXTURE, path, 0, "%s: cannot decode texture: %s", path,
                  stbi_failure_reason());
    } else if (img->width <= 0 || img->height <= 0 ||
               (uint64_t)img->width * (uint64_t)img->height > TEXTURE_MAX_TEXELS) {
        error_set(err, ERR_TOO_LARGE, path, 0,
                  "%s: declared size %dx%d is over the limit of %llu texels per texture", path,
                  img->width, img->height, (unsigned long long)TEXTURE_MAX_TEXELS);
    } else if (stbi_is_hdr_from_memory(bytes, length) &&
               (problem = image_check_hdr(bytes, (size_t)length, img->width, img->height))) {
        error_set(err, ERR_TEXTURE, path, 0, "%s: corrupt HDR texture: %s", path, problem);
    } else {
        if (stbi_is_hdr_from_memory(bytes, length))
            img->rgba32f = stbi_loadf_from_memory(bytes, length, &img->width, &img->height,
                                                  &channels, 4);
        else
            img->rgba8 = stbi_load_from_memory(bytes, length, &img->width, &img->height,
                                               &channels, 4);
        ok = img->rgba32f || img->rgba8;
        img->channels = channels;
        if (!ok)
            error_set(err, ERR_TEXTURE, path, 0, "%s: cannot decode texture: %s", path,
                      stbi_failure_reason());
    }
    return ok;
}

static bool decode_image(const char *path, DecodedImage *img, Error *err)
{
    memset(img, 0, sizeof *img);
    if (fs_has_suffix(path, ".exr") || fs_has_suffix(path, ".EXR"))
        return decode_exr(path, img, err);
    char *file = NULL;
    size_t size = 0;
    Error read_err = {0};
    if (!input_file_read(path, "a texture", INPUT_LIMIT_TEXTURE, &file, &size, &read_err)) {
        /* Anything but a missing file is a texture that cannot be used. */
        error_set(err, read_err.code == ERR_FILE_MISSING ? ERR_FILE_MISSING : ERR_TEXTURE, path, 0,
                  "%s", read_err.message);
        return false;
    }
    bool ok = decode_bytes((const stbi_uc *)file, size, path, img, err);
    free(file);
    return ok;
}

static float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c / 12.92f : powf((c + 0.055f) / 1.055f, 2.4f);
}

/* Brings the image to the encoding it is stored with: 8-bit stays 8-bit (TEXTURE_RGBA8_SRGB or
 * TEXTURE_RGBA8_LINEAR; the kernel decodes); float read as sRGB is decoded here. */
static void apply_encoding(DecodedImage *img, TextureEncoding encoding)
{
    size_t n = 4 * (size_t)img->width * (size_t)img->height;
    if (img->rgba8 && encoding == TEXTURE_ENCODING_LINEAR) {
        img->linear8 = true;
    } else if (img->rgba32f && encoding == TEXTURE_ENCODING_SRGB) {
        for (size_t i = 0; i < n; i++)
            if (i % 4 != 3)
                img->rgba32f[i] = srgb_to_linear(img->rgba32f[i]);
    }
}

const float *texture_srgb_decode_table(void) { return srgb_decode_table; }

/* What the host's material checks need: channels, cut-out alpha, the mean linear colour. */
static TextureStats image_stats(const DecodedImage *img)
{
    TextureStats st = {.channels = img->channels};
    size_t texels = (size_t)img->width * (size_t)img->height;
    double sum[3] = {0.0, 0.0, 0.0};
    const float *srgb = texture_srgb_decode_table();
    for (size_t i = 0; i < texels; i++) {
        for (int c = 0; c < 3; c++) {
            float v = !img->rgba8    ? img->rgba32f[4 * i + c]
                      : img->linear8 ? img->rgba8[4 * i + c] / 255.0f
                                     : srgb[img->rgba8[4 * i + c]];
            sum[c] += isfinite(v) && v > 0.0f ? v : 0.0f;
        }
        float alpha = img->rgba8 ? img->rgba8[4 * i + 3] / 255.0f : img->rgba32f[4 * i + 3];
        st.alpha_below_one |= alpha < 1.0f;
    }
    for (int c = 0; c < 3; c++)
        st.mean[c] = texels ? (float)(sum[c] / (double)texels) : 0.0f;
    return st;
}

/* Makes room for `uints` more entries in the texel buffer; returns where they go. */
static uint32_t *reserve_texels(TextureSet *set, size_t uints, const char *path, Error *err)
{
    if (uints > TEXEL_BUFFER_LIMIT - set->num_texels) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: texture takes the texture buffer over 2^31 entries",
                  path);
        return NULL;
    }
    uint32_t *grown = realloc(set->texels, (set->num_texels + uints) * sizeof *grown);
    if (!grown) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory for a texture", path);
        return NULL;
    }
    set->texels = grown;
    return grown + set->num_texels;
}

/* Appends the decoded texels in the kernel's layout (cl/shared.h TEXTURE_*). */
static bool pack_texels(TextureSet *set, const char *path, const DecodedImage *img,
                        TextureInfo *info, Error *err)
{
    size_t texels = (size_t)img->width * (size_t)img->height;
    size_t uints = img->rgba32f ? 4 * texels : texels;
    uint32_t *dst = reserve_texels(set, uints, path, err);
    if (!dst)
        return false;
    if (img->rgba32f) {
        memcpy(dst, img->rgba32f, uints * sizeof *dst); /* float bits, linear */
    } else {
        for (size_t i = 0; i < texels; i++) {
            const unsigned char *p = img->rgba8 + 4 * i;
            dst[i] = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                     (uint32_t)p[3] << 24;
        }
    }
    *info = (TextureInfo){
        .offset = (uint32_t)set->num_texels,
        .width = (uint32_t)img->width,
        .height = (uint32_t)img->height,
        .format = img->rgba32f  ? TEXTURE_RGBA32F
                  : img->linear8 ? TEXTURE_RGBA8_LINEAR
                                 : TEXTURE_RGBA8_SRGB,
    };
    set->num_texels += uints;
    return true;
}

bool texture_set_append(TextureSet *set, const TextureInfo *info, const TextureStats *stats,
                        const char *key)
{
    TextureInfo *infos = realloc(set->infos, (set->count + 1) * sizeof *infos);
    if (infos)
        set->infos = infos;
    TextureStats *all_stats = realloc(set->stats, (set->count + 1) * sizeof *all_stats);
    if (all_stats)
        set->stats = all_stats;
    char **paths = realloc(set->paths, (set->count + 1) * sizeof *paths);
    if (paths)
        set->paths = paths;
    char *copy = strdup(key);
    if (!infos || !all_stats || !paths || !copy) {
        free(copy);
        return false;
    }
    set->infos[set->count] = *info;
    set->stats[set->count] = *stats;
    set->paths[set->count] = copy;
    set->count++;
    return true;
}

static const char *const encoding_suffix[] = {"", "\n(srgb)", "\n(linear)"};

/* Adds a decoded image under key (img freed). */
static uint32_t add_decoded(TextureSet *set, DecodedImage img, TextureEncoding encoding,
                            const char *path, const char *key, Error *err)
{
    TextureInfo info;
    apply_encoding(&img, encoding);
    TextureStats stats = image_stats(&img);
    bool ok = pack_texels(set, path, &img, &info, err);
    free(img.rgba8);
    free(img.rgba32f);
    if (!ok)
        return NO_TEXTURE;
    if (!texture_set_append(set, &info, &stats, key)) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
        return NO_TEXTURE;
    }
    return set->count - 1;
}

static bool room_for_one_more(const TextureSet *set, const char *name, Error *err)
{
    if (set->count < NO_TEXTURE - 1)
        return true;
    error_set(err, ERR_TOO_LARGE, name, 0, "%s: too many textures", name);
    return false;
}

uint32_t texture_set_add_encoded(TextureSet *set, const char *path, TextureEncoding encoding,
                                 Error *err)
{
    char resolved[4096], key[4200];
    snprintf(key, sizeof key, "%s%s", realpath(path, resolved) ? resolved : path,
             encoding_suffix[encoding]);
    uint32_t found = texture_set_find_key(set, key);
    if (found != NO_TEXTURE)
        return found;
    DecodedImage img;
    if (!room_for_one_more(set, path, err) || !decode_image(path, &img, err))
        return NO_TEXTURE;
    return add_decoded(set, img, encoding, path, key, err);
}

uint32_t texture_set_add_memory(TextureSet *set, const unsigned char *bytes, size_t size,
                                const char *name, TextureEncoding encoding, Error *err)
{
    char key[4200];
    /* A key no file can have (a path never starts with a newline). */
    snprintf(key, sizeof key, "\n(memory)%s%s", name, encoding_suffix[encoding]);
    uint32_t found = texture_set_find_key(set, key);
    if (found != NO_TEXTURE)
        return found;
    DecodedImage img;
    memset(&img, 0, sizeof img);
    if (!room_for_one_more(set, name, err) || !decode_bytes(bytes, size, name, &img, err))
        return NO_TEXTURE;
    return add_decoded(set, img, encoding, name, key, err);
}

uint32_t texture_set_add(TextureSet *set, const char *path, Error *err)
{
    return texture_set_add_encoded(set, path, TEXTURE_ENCODING_DEFAULT, err);
}

uint32_t texture_set_add_noise(TextureSet *set, const TextureNoise *noise, const char *name,
                               Error *err)
{
    uint32_t *dst = reserve_texels(set, 9, name, err);
    if (!dst)
        return NO_TEXTURE;
    float floats[7] = {noise->color0[0], noise->color0[1], noise->color0[2], noise->color1[0],
                       noise->color1[1], noise->color1[2], noise->frequency};
    memcpy(dst, floats, sizeof floats);
    dst[7] = noise->octaves;
    dst[8] = noise->seed;
    TextureInfo info = {.offset = (uint32_t)set->num_texels, .width = 1, .height = 1,
                        .format = TEXTURE_NOISE};
    TextureStats stats = {.channels = 3};
    for (int c = 0; c < 3; c++)
        stats.mean[c] = 0.5f * (noise->color0[c] + noise->color1[c]);
    set->num_texels += 9;
    /* A key no file can have: noise textures are never shared by path. */
    char key[64];
    snprintf(key, sizeof key, "\n(noise %u)", set->count);
    if (!texture_set_append(set, &info, &stats, key)) {
        error_set(err, ERR_TOO_LARGE, name, 0, "%s: out of memory", name);
        return NO_TEXTURE;
    }
    return set->count - 1;
}

float texture_mean_luminance(const TextureSet *set, uint32_t index)
{
    const float *m = set->stats[index].mean;
    return 0.2126f * m[0] + 0.7152f * m[1] + 0.0722f * m[2];
}

void texture_set_free(TextureSet *set)
{
    for (uint32_t i = 0; i < set->count; i++)
        free(set->paths[i]);
    free(set->paths);
    free(set->infos);
    free(set->stats);
    free(set->texels);
    memset(set, 0, sizeof *set);
}
