/* SPDX-License-Identifier: MIT */
/* material_json.h: the scene's "materials" block (shared/DESIGN.md "Materials"): every type of
 * cl/shared.h MATERIAL_TYPES with its keys, read into kernel Materials whose texture slots name
 * the scene's JSON textures and whose mixes name other JSON materials. Checked when read (ranges,
 * unknown names, mix cycles and depth) and when loaded (normal maps need rgb). */
#ifndef PT_MATERIAL_JSON_H
#define PT_MATERIAL_JSON_H

#include <stdbool.h>
#include <stdint.h>

#include "base/shared_types.h"
#include "scene/json.h"
#include "scene/texture_json.h"

typedef struct {
    char name[SCENE_NAME_LIMIT];
    /* Constants as the kernels take them. tex[] holds indices into the scene's TextureDesc array
     * (or NO_TEXTURE); mix_a / mix_b index the MaterialDesc array. emission.w is set on load. */
    Material m;
    float subsurface_radius[3]; /* principled: mean free paths (m.subsurface > 0: its medium) */
} MaterialDesc;

/* Reads the "materials" object; texture names are looked up in textures[0..num_textures). */
bool materials_from_json(JsonParser *p, const cJSON *obj, const TextureDesc *textures,
                         int num_textures, MaterialDesc **out, int *count);
/* The index of the material called name, or -1. */
int material_desc_find(const MaterialDesc *descs, int count, const char *name);
/* The kernels' materials of descs[0..count), in the same order (a mix's indices are offset by
 * `first`, the scene index of descs[0]): texture slots mapped through texture_indices, emission
 * weight computed. A normal map whose file has fewer than 3 channels is an error naming the key. */
bool materials_load(const MaterialDesc *descs, int count, const TextureDesc *textures,
                    const TextureSet *set, const uint32_t *texture_indices, uint32_t first, Material *out,
                    const char *scene_path, Error *err);

#endif
