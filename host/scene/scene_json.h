/* SPDX-License-Identifier: MIT */
/* scene_json.h: the sections of a JSON scene (camera, film, render, objects, background,
 * environment, lights, textures, materials) read into a SceneDesc that holds the defaults. */
#ifndef PT_SCENE_JSON_H
#define PT_SCENE_JSON_H

#include <stdbool.h>

#include "scene/json.h"
#include "scene/scene_types.h"

/* Reads the parsed root of the scene file p->file over d; errors name the key path and line. */
bool scene_json_read(JsonParser *p, const cJSON *root, SceneDesc *d);

#endif
