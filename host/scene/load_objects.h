/* SPDX-License-Identifier: MIT */
/* load_objects.h: a scene's objects loaded as meshes and instances (shared/DESIGN.md "Objects"):
 * each distinct mesh (mesh file, material override, smoothing) is loaded and flattened once,
 * however many objects name it; objects without a transform whose mesh is used once are merged
 * into one world-space mesh (instance 0), everything else is an instance of its mesh. */
#ifndef PT_LOAD_OBJECTS_H
#define PT_LOAD_OBJECTS_H

#include <stdbool.h>

#include "base/error.h"
#include "scene/scene_types.h"

/* Loads d's objects into data (before scene_data_finish) as `mode` says. */
bool scene_load_objects(SceneData *data, const SceneDesc *d, InstancingMode mode,
                        const NamedMaterials *named, Error *err);

#endif
