/* SPDX-License-Identifier: MIT */
/* texture.h: textures (stb_image) packed into one texel buffer with per-texture offset, size and
 * format (cl/shared.h TextureInfo). 8-bit images stay sRGB-encoded (the kernel decodes when
 * sampling); HDR images (.hdr) are stored linear as 32-bit floats. */
#ifndef PT_TEXTURE_H
#define PT_TEXTURE_H

#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "base/shared_types.h"

typedef struct {
    uint32_t *texels; /* see TEXTURE_RGBA8_SRGB / TEXTURE_RGBA32F */
    size_t num_texels; /* in uints */
    TextureInfo *infos;
    uint32_t count;
    char **paths; /* for de-duplication */
} TextureSet;

/* Adds the image at path (or finds it if already added) and returns its index. A missing file is
 * ERR_FILE_MISSING, an unreadable or corrupt one ERR_TEXTURE; both return NO_TEXTURE. */
uint32_t texture_set_add(TextureSet *set, const char *path, Error *err);
void texture_set_free(TextureSet *set);

#endif
