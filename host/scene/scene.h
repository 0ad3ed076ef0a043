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

/* Frames the camera on the scene's bounds (camera/camera_frame_model) for the film's aspect, with
 * the given up axis; the camera counts as not given. */
void scene_frame_camera(Scene *scene, UpAxis up);
/* Whether path is a model file given bare (OBJ, PLY, glTF) rather than a scene description. */
bool scene_is_bare_model(const char *path);

/* The default rig (scene/default_rig.h; README "The first image") a scene gets:
 *   - none when the scene brings "lights", an environment map or a non-black background;
 *   - a bare model file (OBJ, PLY, glTF) without emitters, or whose emitters are tiny (less than a
 *     tenth of what the rig's sky gives its bounding disc: glowing labels, indicator lamps): the
 *     sky, the sun and a ground (as Blender keeps its world whatever a model emits);
 *   - a JSON scene without any light (no emitters either): the sky and the sun, no ground (its
 *     author placed its objects); a JSON scene with emitters keeps its own light only. */
typedef enum { RIG_NONE, RIG_SKY_AND_KEY, RIG_WITH_GROUND } RigChoice;
typedef struct {
    UpAxis up;      /* pt --up */
    bool no_ground; /* pt --no-ground */
} RigOptions;
RigChoice scene_default_rig_choice(const Scene *scene);
/* Adds the rig scene_default_rig_choice picks, with one warning naming why; call before the BVH
 * is built. False: out of memory (err set). */
bool scene_add_default_rig(Scene *scene, const RigOptions *options, Error *err);
/* scene_add_default_rig with Y up and the ground; true when it added a rig. */
bool scene_add_default_light(Scene *scene);

#endif
