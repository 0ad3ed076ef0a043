/* SPDX-License-Identifier: MIT */
/* scene.h: the whole scene loaded and flattened (scene_load), the top floor of scene/: it reads the
 * description through the readers (scene_json.h, gltf_scene.h) and builds it through load_objects.h,
 * all of which see only the types of scene_types.h below them. */
#ifndef PT_SCENE_H
#define PT_SCENE_H

#include <stdbool.h>

#include "base/error.h"
#include "scene/scene_data.h"
#include "scene/scene_types.h"

/* Reads a scene description. path: a .json scene, a bare .obj, .ply, .gltf or .glb, or a folder
 * holding scene.json. A bare glTF's own camera, when it has one, is used instead of framing.
 * Errors name the file and line (malformed JSON) or the key (unknown key, wrong type, bad value). */
bool scene_desc_load(const char *path, SceneDesc *out, Error *err);
void scene_desc_free(SceneDesc *desc);

typedef struct {
    SceneDesc desc;
    SceneData data;
} Scene;

/* scene_desc_load + scene_data_build, and frames the camera when none was given. */
bool scene_load(const char *path, Scene *out, Error *err);
/* The same with a choice of instancing (scene_load: INSTANCING_AUTO). */
bool scene_load_with(const char *path, InstancingMode instancing, Scene *out, Error *err);
void scene_free(Scene *scene);

/* A scene with no light at all (no emissive triangle, no "lights", no environment map and a black
 * background) gets a uniform white sky, background [1, 1, 1], with one warning naming what is
 * missing; true when it did. */
bool scene_add_default_light(Scene *scene);

#endif
