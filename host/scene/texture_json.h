/* SPDX-License-Identifier: MIT */
/* texture_json.h: the scene's "textures" block (shared/DESIGN.md "Textures"): named image files
 * with an encoding, and procedural noise. Read with the scene description; loaded into the
 * scene's TextureSet by scene_load. */
#ifndef PT_TEXTURE_JSON_H
#define PT_TEXTURE_JSON_H

#include <stdbool.h>
#include <stdint.h>

#include "scene/json.h"
#include "scene/texture.h"

#define SCENE_NAME_LIMIT 128 /* texture and material names, with the NUL */

typedef struct {
    char name[SCENE_NAME_LIMIT];
    char path[1024];          /* resolved against the scene file; "" for noise and embedded */
    TextureEncoding encoding; /* files */
    bool is_noise;
    TextureNoise noise;
    /* An embedded image (a glTF's PNG or JPEG bytes) instead of a file: borrowed from the glTF
     * loader, so it must outlive textures_load; `path` then names it ("model.glb: images[3]"),
     * which is also its key (added once). */
    const unsigned char *bytes;
    size_t size;
    /* Said after a load error instead of naming "textures.<name>.file" ("used by model.glb:
     * materials[2].pbrMetallicRoughness.baseColorTexture"); "" for JSON textures. */
    char label[320];
    /* Keys channel, scale, wrap, filter, transform (zero: the plain lookup). */
    TextureSampling sampling;
} TextureDesc;

/* Reads the "textures" object into a malloc'ed array (*out, *count); paths are resolved against
 * p->file's folder. */
bool textures_from_json(JsonParser *p, const cJSON *obj, TextureDesc **out, int *count);
/* The index of the texture called name in descs, or -1. */
int texture_desc_find(const TextureDesc *descs, int count, const char *name);
/* Loads every described texture into set; indices[i] is the set's index of descs[i]. Errors name
 * scene_path and the key ("scene.json: textures.bricks.file: ..."). */
bool textures_load(const TextureDesc *descs, int count, TextureSet *set, uint32_t *indices,
                   const char *scene_path, Error *err);

#endif
