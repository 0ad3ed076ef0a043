/* SPDX-License-Identifier: MIT */
/* instances.h: a scene's objects loaded as meshes and instances (shared/DESIGN.md "Objects"):
 * each distinct mesh (OBJ file, material override, smoothing) is loaded and flattened once,
 * however many objects name it; objects without a transform whose mesh is used once are merged
 * into one world-space mesh (instance 0), everything else is an instance of its mesh. */
#ifndef PT_INSTANCES_H
#define PT_INSTANCES_H

#include <stdbool.h>

#include "base/error.h"
#include "scene/scene.h"

/* Loads d's objects into data (before scene_data_finish) as `mode` says. */
bool scene_load_objects(SceneData *data, const SceneDesc *d, InstancingMode mode,
                        const NamedMaterials *named, Error *err);

/* Applies m to the triangles and vertices appended since first_triangle / first_vertex: points by
 * m, normals by its inverse transpose, and a mirroring m (det < 0) reverses each triangle's
 * corners so that the front stays where the transformed normal points (DESIGN "Objects"). */
void scene_data_bake_transform(SceneData *data, uint32_t first_triangle, uint32_t first_vertex,
                               const Affine *m);

#endif
