// SPDX-License-Identifier: MIT
/* texture_sampling.c: one image sampled several ways (wrap modes, filter, uv transform, channel,
 * scale: glTF's samplers, textureInfos and factors) as TextureInfos that share its texels. */
#include "scene/texture.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool texture_sampling_is_plain(const TextureSampling *s)
{
    return s->wrap_s == TEXTURE_WRAP_REPEAT && s->wrap_t == TEXTURE_WRAP_REPEAT && !s->nearest &&
           s->channel == 0 && !(s->has_scale && s->scale != 1.0f) && !s->has_transform;
}

/* The key of the image sampled as s: the image's own key and every parameter (floats in %a, so
 * that two samplings share a TextureInfo only when they are bit-for-bit the same). */
static void sampled_key(const TextureSet *set, uint32_t image, const TextureSampling *s, char *key,
                        size_t size)
{
    const float *t = s->transform;
    float scale = s->has_scale ? s->scale : 1.0f;
    if (s->has_transform)
        snprintf(key, size, "%s\n(sampled %u %u %d %u %a %a %a %a %a %a %a)", set->paths[image],
                 s->wrap_s, s->wrap_t, s->nearest, s->channel, (double)scale, (double)t[0],
                 (double)t[1], (double)t[2], (double)t[3], (double)t[4], (double)t[5]);
    else
        snprintf(key, size, "%s\n(sampled %u %u %d %u %a)", set->paths[image], s->wrap_s, s->wrap_t,
                 s->nearest, s->channel, (double)scale);
}

uint32_t texture_set_add_sampled(TextureSet *set, uint32_t image, const TextureSampling *s,
                                 Error *err)
{
    if (texture_sampling_is_plain(s))
        return image;
    char key[4600];
    sampled_key(set, image, s, key, sizeof key);
    uint32_t found = texture_set_find_key(set, key);
    if (found != NO_TEXTURE)
        return found;
    TextureInfo info = set->infos[image];
    info.flags = TEXTURE_FLAGS_MAKE(s->wrap_s, s->wrap_t, s->channel);
    if (s->nearest)
        info.flags |= TEXTURE_FLAG_NEAREST;
    info.scale = 1.0f;
    if (s->has_scale && s->scale != 1.0f) {
        info.flags |= TEXTURE_FLAG_SCALE;
        info.scale = s->scale;
    }
    if (s->has_transform) {
        info.flags |= TEXTURE_FLAG_TRANSFORM;
        memcpy(info.transform, s->transform, sizeof info.transform);
    }
    TextureStats stats = set->stats[image];
    for (int c = 0; c < 3; c++)
        stats.mean[c] *= info.scale;
    if (set->count >= NO_TEXTURE - 1 || !texture_set_append(set, &info, &stats, key)) {
        error_set(err, ERR_TOO_LARGE, set->paths[image], 0, "%s: out of memory for textures",
                  set->paths[image]);
        return NO_TEXTURE;
    }
    return set->count - 1;
}
