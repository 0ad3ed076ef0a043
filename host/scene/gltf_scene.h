/* SPDX-License-Identifier: MIT */
/* gltf_scene.h: a glTF file as objects of the scene description (host/scene/gltf_scene.c): each
 * (node, mesh primitive) of its scene becomes one object whose mesh is the primitive decoded in
 * memory (SceneDesc.object_meshes) and whose transform is the node's world matrix after the JSON
 * object's own; objects of one primitive share one key ("<file>#meshes[m].primitives[p]"), so
 * load_objects.c loads and builds it once and places it once per node. Its materials are appended
 * to the scene's (gltf_material.h), its KHR_lights_punctual lights to the scene's lights, and its
 * first perspective camera becomes the scene's camera when none was given. */
#ifndef PT_GLTF_SCENE_H
#define PT_GLTF_SCENE_H

#include <stdbool.h>

#include "base/error.h"
#include "io/gltf_loader.h"
#include "scene/gltf_material.h"
#include "scene/scene_types.h"

/* pt's radiometric unit per photometric one (KHR_lights_punctual candela and lux): 683 lm/W, the
 * luminous efficacy at 555 nm that defines the candela. point/spot intensity (W/sr) = colour x
 * candela / 683; directional irradiance (W/m^2) = colour x lux / 683. */
#define GLTF_LUMENS_PER_WATT 683.0

/* Loads the glTF at path (resolved) and appends its objects, materials, lights and camera to d.
 * options.material (NO_MATERIAL: each primitive's own) and transform apply to every object;
 * json_index is the JSON objects[] index (-1 for a bare .gltf / .glb) for material names. */
bool gltf_scene_add(SceneDesc *d, const char *path, const ObjectOptions *options,
                    const ObjectTransform *transform, int json_index, Error *err);

/* Room for `extra` objects after d->num_objects in every per-object array (object_meshes is
 * created on first use, NULL for the objects before). False: out of memory. */
bool scene_desc_reserve_objects(SceneDesc *d, int extra);

#endif
