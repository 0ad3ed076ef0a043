/* SPDX-License-Identifier: MIT */
/* scene_data.h: every mesh and texture of a scene flattened into one array per attribute, indexed by
 * offsets, ready to upload as is. Vertices are unified (one index per corner for position, normal
 * and uv). */
#ifndef PT_SCENE_DATA_H
#define PT_SCENE_DATA_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "io/obj_loader.h"
#include "base/shared_types.h"
#include "scene/environment.h"
#include "scene/materials.h" /* material_from_obj, for the flattener's users and tests */
#include "scene/texture.h"

typedef struct {
    float4 *positions; /* w = 0 */
    float4 *normals;   /* w = 0; zero where the mesh has none */
    float2 *uvs;
    uint32_t num_vertices;
    Triangle *triangles;
    uint32_t *material_ids; /* per triangle */
    uint32_t num_triangles;
    Material *materials;
    uint32_t num_materials;
    TextureSet textures;
    uint32_t *emissive_triangles; /* indices of triangles whose material emits */
    uint32_t num_emissive;
    float bounds_min[3], bounds_max[3];
    AnalyticLight *analytic_lights; /* the scene's "lights" (scene_load copies them in) */
    uint32_t num_analytic;
    Environment environment; /* width 0: none (scene_load loads it after scene_data_finish) */
    /* The first OBJ that added no triangles and why, for the message when the whole scene has
     * none ("x.obj: no faces (the file is empty)"). */
    char faceless_obj[512];
    char faceless_reason[128];
} SceneData;

/* How one object of the scene is added. */
typedef struct {
    uint32_t material; /* a scene material index for every triangle (JSON objects[i].material);
                          NO_MATERIAL: the OBJ's own (MTL) materials */
    bool smooth;       /* meshes without vn get area- and angle-weighted vertex normals */
} ObjectOptions;

void scene_data_init(SceneData *data);
/* Appends one loaded OBJ: vertices, triangles (indices offset), materials (ids offset), textures. */
bool scene_data_append_obj(SceneData *data, const ObjMesh *mesh, const char *obj_path, Error *err);
/* The same with the object's options; `named` (NULL: none) are the JSON materials. */
bool scene_data_append_object(SceneData *data, const ObjMesh *mesh, const char *obj_path,
                              const ObjectOptions *options, const NamedMaterials *named, Error *err);
/* Finishes: bounds, emissive table; ERR_NO_TRIANGLES for an empty scene (names scene_path, and the
 * first OBJ without faces and why). */
bool scene_data_finish(SceneData *data, const char *scene_path, Error *err);
void scene_data_free(SceneData *data);

#endif
