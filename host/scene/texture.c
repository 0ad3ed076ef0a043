// SPDX-License-Identifier: MIT
#define _XOPEN_SOURCE 700 /* realpath */
#include "scene/texture.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>

#include "io/image_checks.h"
#include "io/input_file.h"

/* Every offset and texel index is a uint in the kernel (and RGBA32F indices are multiplied by 4),
 * so the whole texel buffer is capped at 2^31 uints (8 GiB). */
#define TEXEL_BUFFER_LIMIT ((size_t)1 << 31)
/* One texture may declare at most 8192 x 8192 texels (1 GiB as floats): checked on the header
 * before decoding, so a tiny file declaring a huge image is refused without allocating. */
#define TEXTURE_MAX_TEXELS ((uint64_t)1 << 26)

/* Finds a texture already added under the same file (compared after realpath, so "a/../t.png" and
 * "t.png" share one copy). */
static uint32_t find_texture(const TextureSet *set, const char *key)
{
    for (uint32_t i = 0; i < set->count; i++)
        if (strcmp(set->paths[i], key) == 0)
            return i;
    return NO_TEXTURE;
}

/* Decoded image, before packing: either 8-bit RGBA or float RGBA (stb expands grey and grey-alpha
 * to RGBA and fills a missing alpha with opaque). */
typedef struct {
    int width, height;
    unsigned char *rgba8;
    float *rgba32f;
} DecodedImage;

static bool decode_image(const char *path, DecodedImage *img, Error *err)
{
    memset(img, 0, sizeof *img);
    char *file = NULL;
    size_t size = 0;
    Error read_err = {0};
    if (!input_file_read(path, "a texture", INPUT_LIMIT_TEXTURE, &file, &size, &read_err)) {
        /* Anything but a missing file is a texture that cannot be used. */
        error_set(err, read_err.code == ERR_FILE_MISSING ? ERR_FILE_MISSING : ERR_TEXTURE, path, 0,
                  "%s", read_err.message);
        return false;
    }
    const stbi_uc *bytes = (const stbi_uc *)file;
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
        if (!ok)
            error_set(err, ERR_TEXTURE, path, 0, "%s: cannot decode texture: %s", path,
                      stbi_failure_reason());
    }
    free(file);
    return ok;
}

/* Appends the decoded texels in the kernel's layout (cl/shared.h TEXTURE_*). */
static bool pack_texels(TextureSet *set, const char *path, const DecodedImage *img,
                        TextureInfo *info, Error *err)
{
    size_t texels = (size_t)img->width * (size_t)img->height;
    size_t uints = img->rgba32f ? 4 * texels : texels;
    if (uints > TEXEL_BUFFER_LIMIT - set->num_texels) {
        error_set(err, ERR_TOO_LARGE, path, 0,
                  "%s: %dx%d texture takes the texture buffer over 2^31 entries", path, img->width,
                  img->height);
        return false;
    }
    uint32_t *grown = realloc(set->texels, (set->num_texels + uints) * sizeof *grown);
    if (!grown) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory for %dx%d texture", path,
                  img->width, img->height);
        return false;
    }
    set->texels = grown;
    uint32_t *dst = grown + set->num_texels;
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
        .format = img->rgba32f ? TEXTURE_RGBA32F : TEXTURE_RGBA8_SRGB,
    };
    set->num_texels += uints;
    return true;
}

static bool append_info(TextureSet *set, const TextureInfo *info, const char *key)
{
    TextureInfo *infos = realloc(set->infos, (set->count + 1) * sizeof *infos);
    if (infos)
        set->infos = infos;
    char **paths = realloc(set->paths, (set->count + 1) * sizeof *paths);
    if (paths)
        set->paths = paths;
    char *copy = strdup(key);
    if (!infos || !paths || !copy) {
        free(copy);
        return false;
    }
    set->infos[set->count] = *info;
    set->paths[set->count] = copy;
    set->count++;
    return true;
}

uint32_t texture_set_add(TextureSet *set, const char *path, Error *err)
{
    char resolved[4096];
    const char *key = realpath(path, resolved) ? resolved : path;
    uint32_t found = find_texture(set, key);
    if (found != NO_TEXTURE)
        return found;
    if (set->count >= NO_TEXTURE - 1) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: too many textures", path);
        return NO_TEXTURE;
    }
    DecodedImage img;
    if (!decode_image(path, &img, err))
        return NO_TEXTURE;
    TextureInfo info;
    bool ok = pack_texels(set, path, &img, &info, err);
    stbi_image_free(img.rgba8);
    stbi_image_free(img.rgba32f);
    if (!ok)
        return NO_TEXTURE;
    if (!append_info(set, &info, key)) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
        return NO_TEXTURE;
    }
    return set->count - 1;
}

void texture_set_free(TextureSet *set)
{
    for (uint32_t i = 0; i < set->count; i++)
        free(set->paths[i]);
    free(set->paths);
    free(set->infos);
    free(set->texels);
    memset(set, 0, sizeof *set);
}
