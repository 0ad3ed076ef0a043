// SPDX-License-Identifier: MIT
/* gltf_texture.c: a glTF textureInfo (image, sampler, KHR_texture_transform) as one of the scene's
 * TextureDescs, shared by every textureInfo that samples the same image the same way. */
#include "scene/gltf_texture.h"

#include <math.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"

static bool wrap_mode(int gl, uint32_t *out)
{
    switch (gl) {
    case GLTF_WRAP_REPEAT: *out = TEXTURE_WRAP_REPEAT; return true;
    case GLTF_WRAP_CLAMP: *out = TEXTURE_WRAP_CLAMP; return true;
    case GLTF_WRAP_MIRROR: *out = TEXTURE_WRAP_MIRROR; return true;
    default: return false;
    }
}

/* KHR_texture_transform's uv' = T R S uv (rotation counter-clockwise in glTF's frame, whose v runs
 * down the image) as an affine in pt's frame, v_pt = 1 - v_gltf (gltf_material.h): F M F with
 * F(u, v) = (u, 1 - v). */
void gltf_transform_to_pt(const GltfTextureRef *ref, float out[6])
{
    float c = cosf(ref->rotation), s = sinf(ref->rotation);
    float sx = ref->scale[0], sy = ref->scale[1], ox = ref->offset[0], oy = ref->offset[1];
    /* glTF: u' = c sx u + s sy v + ox, v' = -s sx u + c sy v + oy. */
    out[0] = c * sx;
    out[1] = -s * sy;
    out[2] = s * sy + ox;
    out[3] = s * sx;
    out[4] = c * sy;
    out[5] = 1.0f - c * sy - oy;
}

static bool sampling_equal(const TextureSampling *a, const TextureSampling *b)
{
    if (a->wrap_s != b->wrap_s || a->wrap_t != b->wrap_t || a->nearest != b->nearest ||
        a->channel != b->channel || a->has_scale != b->has_scale ||
        (a->has_scale && a->scale != b->scale) || a->has_transform != b->has_transform)
        return false;
    for (int i = 0; a->has_transform && i < 6; i++)
        if (a->transform[i] != b->transform[i])
            return false;
    return true;
}

/* The same image, encoding and sampling: one TextureDesc (and one TextureInfo). */
static bool desc_equal(const TextureDesc *a, const TextureDesc *b)
{
    return a->bytes == b->bytes && a->size == b->size && strcmp(a->path, b->path) == 0 &&
           a->encoding == b->encoding && sampling_equal(&a->sampling, &b->sampling);
}

static bool fail(GltfTextures *t, ErrorCode code, const char *fmt, const char *a, const char *b)
{
    error_set(t->err, code, t->gltf_path, 0, fmt, t->gltf_path, a, b);
    return false;
}

/* The image's source in desc: its bytes (named "file.glb: images[i]") or its file, which must
 * exist. */
static bool image_source(GltfTextures *t, const GltfTextureRef *ref, TextureDesc *desc)
{
    if (ref->image >= t->num_images) {
        char what[64];
        if (ref->image == INT_MAX) /* gltf_material_read: the index is beyond textures */
            snprintf(what, sizeof what, "its texture");
        else
            snprintf(what, sizeof what, "images[%d]", ref->image);
        return fail(t, ERR_JSON_VALUE, "%s: %s.index: %s does not exist", ref->json_path, what);
    }
    const GltfImage *img = &t->images[ref->image];
    if (img->bytes && img->size > 0) {
        desc->bytes = img->bytes;
        desc->size = img->size;
        snprintf(desc->path, sizeof desc->path, "%s: %s", t->gltf_path, img->json_path);
        return true;
    }
    if (!img->path[0])
        return fail(t, ERR_TEXTURE, "%s: %s: no image data (used by %s)", img->json_path,
                    ref->json_path);
    if (!fs_exists(img->path)) {
        error_set(t->err, ERR_FILE_MISSING, t->gltf_path, 0,
                  "%s: %s: image file %s not found (used by %s)", t->gltf_path, img->json_path,
                  img->path, ref->json_path);
        return false;
    }
    snprintf(desc->path, sizeof desc->path, "%s", img->path);
    return true;
}

bool gltf_texture(GltfTextures *t, const GltfTextureRef *ref, TextureEncoding encoding,
                  uint32_t channel, float scale, uint32_t *out)
{
    *out = NO_TEXTURE;
    if (ref->image < 0)
        return true;
    TextureDesc desc;
    memset(&desc, 0, sizeof desc);
    desc.encoding = encoding;
    if (!image_source(t, ref, &desc))
        return false;
    TextureSampling *s = &desc.sampling;
    if (!wrap_mode(ref->wrap_s, &s->wrap_s) || !wrap_mode(ref->wrap_t, &s->wrap_t)) {
        char modes[64];
        snprintf(modes, sizeof modes, "%d, %d", ref->wrap_s, ref->wrap_t);
        return fail(t, ERR_JSON_VALUE,
                    "%s: %s: sampler wrap modes (%s) are not REPEAT, CLAMP_TO_EDGE or "
                    "MIRRORED_REPEAT",
                    ref->json_path, modes);
    }
    s->nearest = ref->nearest;
    s->channel = channel;
    s->has_scale = scale != 1.0f;
    s->scale = scale;
    if (ref->has_transform) {
        s->has_transform = true;
        gltf_transform_to_pt(ref, s->transform);
    }
    if (ref->texcoord != 0)
        warn("%s: %s uses TEXCOORD_%d; pt reads TEXCOORD_0 for it", t->gltf_path, ref->json_path,
             ref->texcoord);
    for (int i = t->first; i < *t->num_textures; i++) {
        if (desc_equal(&(*t->textures)[i], &desc)) {
            *out = (uint32_t)i;
            return true;
        }
    }
    TextureDesc *grown = realloc(*t->textures, (size_t)(*t->num_textures + 1) * sizeof *grown);
    if (!grown)
        return fail(t, ERR_TOO_LARGE, "%s: %s: out of memory for textures%s", ref->json_path, "");
    *t->textures = grown;
    int index = (*t->num_textures)++;
    snprintf(desc.name, sizeof desc.name, "%stextures[%d]", t->prefix, index - t->first);
    snprintf(desc.label, sizeof desc.label, "%s of %s", t->images[ref->image].json_path,
             ref->json_path);
    grown[index] = desc;
    *out = (uint32_t)index;
    return true;
}
