/* SPDX-License-Identifier: MIT */
/* gltf_texture.h: glTF textureInfos (io/gltf_material_read.h GltfTextureRef) as the scene's
 * TextureDescs: the image (embedded bytes or a file), the sampler's wrap modes and filter,
 * KHR_texture_transform in pt's uv frame, and the channel and factor a material parameter reads. */
#ifndef PT_GLTF_TEXTURE_H
#define PT_GLTF_TEXTURE_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "io/gltf_material_read.h"
#include "scene/texture_json.h"

/* Where the TextureDescs go and what messages name. */
typedef struct {
    const GltfImage *images;
    int num_images;
    const char *gltf_path, *prefix;
    TextureDesc **textures; /* grown */
    int *num_textures;
    int first;              /* *num_textures on entry: the glTF's own descs, searched for sharing */
    Error *err;
} GltfTextures;

/* The TextureDesc index (absolute in *textures) of ref sampled with `encoding`, its `channel`
 * moved to x and rgb times `scale`; NO_TEXTURE when ref has no image. An existing desc with the
 * same image, encoding and sampling is reused. Errors: an image index out of range, a missing
 * image file, a wrap mode GL does not have. */
bool gltf_texture(GltfTextures *t, const GltfTextureRef *ref, TextureEncoding encoding,
                  uint32_t channel, float scale, uint32_t *out);
/* KHR_texture_transform of ref as TextureSampling.transform (pt's uv frame). */
void gltf_transform_to_pt(const GltfTextureRef *ref, float out[6]);

#endif
