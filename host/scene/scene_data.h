/* SPDX-License-Identifier: MIT */
/* scene_data.h: every mesh and texture of a scene flattened into one array per attribute, indexed by
 * offsets, ready to upload as is. Vertices are unified (one index per corner for position, normal
 * and uv). */
#ifndef PT_SCENE_DATA_H
#define PT_SCENE_DATA_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "base/transform.h"
#include "io/mesh.h"
#include "base/shared_types.h"
#include "scene/environment.h"
#include "scene/materials.h" /* material_from_obj, for the flattener's users and tests */
#include "scene/texture.h"

/* One distinct mesh: a contiguous range of the flattened arrays, in object space (cl/shared.h
 * "Instances"). Mesh 0 is the merged static mesh when a scene has one. */
typedef struct {
    uint32_t first_triangle, num_triangles;
    uint32_t first_vertex, num_vertices;
    uint32_t first_emissive, num_emissive; /* its range of SceneData.emissive_triangles */
    float bounds_min[3], bounds_max[3];    /* of its vertices (object space) */
} SceneMesh;

/* One placement of a mesh. */
typedef struct {
    uint32_t mesh;
    int32_t object;      /* the JSON objects[] index it comes from; -1: the merged static mesh */
    Affine to_world;     /* a moving instance's at shutter open */
    bool moving;         /* motion[] holds its transforms at open and close (trs_align'ed) */
    Trs motion[2];
    float bounds_min[3], bounds_max[3]; /* world box, swept over the shutter when moving */
} SceneInstance;

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
    uint32_t *emissive_triangles; /* indices of triangles whose material emits, ascending */
    uint32_t num_emissive;
    SceneMesh *meshes;            /* at least one after scene_data_finish */
    uint32_t num_meshes;
    SceneInstance *instances;     /* at least one after scene_data_finish */
    uint32_t num_instances;
    uint32_t num_moving;          /* instances with moving set */
    /* Whether the kernels must traverse two levels: any instance other than one identity instance
     * of mesh 0 (scene_data_finish). */
    bool two_level;
    /* Keep two BVH levels where a flat BVH would do (render/scene_upload.h scene_accel_levels):
     * INSTANCING_ALWAYS, which measures their cost. */
    bool keep_two_levels;
    float bounds_min[3], bounds_max[3]; /* world bounds over every instance */
    AnalyticLight *analytic_lights; /* the scene's "lights" (scene_load copies them in) */
    uint32_t num_analytic;
    Environment environment; /* width 0: none (scene_load loads it after scene_data_finish) */
    /* Media (shared/medium.h; scene/scene_media.h): slot k is media[k - 1]; the grid media's
     * bricks, values and majorants in one array each (Medium's offsets index them). */
    Medium *media;
    uint32_t num_media;
    uint32_t world_medium, camera_medium; /* slots; 0: none */
    uint32_t *grid_bricks;
    size_t num_grid_bricks;
    float *grid_values;
    size_t num_grid_values;
    float *grid_majorants;
    size_t num_grid_majorants;
    /* The first mesh file that added no triangles and why, for the message when the whole scene has
     * none ("x.obj: no faces (the file is empty)"). */
    char faceless_mesh[512];
    char faceless_reason[128];
    /* Allocated lengths of the arrays that grow while objects are added (positions, normals and
     * uvs share one; triangles and material_ids one): they grow geometrically, since growing by
     * each object's size copied O(n^2) bytes for 10^5 objects (minutes under ASan). */
    size_t vertex_capacity, triangle_capacity, mesh_capacity, instance_capacity;
} SceneData;

/* The capacity to allocate for `needed` elements: `capacity` when it suffices, else at least
 * double it. */
size_t scene_data_grown_capacity(size_t capacity, size_t needed);

/* How one object of the scene is added. */
typedef struct {
    uint32_t material; /* a scene material index for every triangle (JSON objects[i].material);
                          NO_MATERIAL: the OBJ's own (MTL) materials */
    bool smooth;       /* meshes without vn get area- and angle-weighted vertex normals */
    /* "interior" / "exterior" (shared/DESIGN.md "Media"): medium slots, 0 = not given; either
     * makes the object's materials bound media (scene/object_media.h). */
    uint32_t interior, exterior;
    int json_object;   /* the JSON objects[] index, for messages (-1: none) */
} ObjectOptions;

void scene_data_init(SceneData *data);
/* Appends one loaded mesh: vertices, triangles (indices offset), materials (ids offset), textures. */
bool scene_data_append_mesh(SceneData *data, const Mesh *mesh, const char *mesh_path, Error *err);
/* The same with the object's options; `named` (NULL: none) are the JSON materials. */
bool scene_data_append_object(SceneData *data, const Mesh *mesh, const char *mesh_path,
                              const ObjectOptions *options, const NamedMaterials *named, Error *err);
/* Finishes: bounds, emissive table; ERR_NO_TRIANGLES for an empty scene (names scene_path, and the
 * first OBJ without faces and why). */
bool scene_data_finish(SceneData *data, const char *scene_path, Error *err);
void scene_data_free(SceneData *data);
/* Makes the triangles and vertices appended since first_triangle / first_vertex one mesh (its
 * bounds too; scene_data_finish_instances finds its emissive range). */
bool scene_data_add_mesh(SceneData *data, uint32_t first_triangle, uint32_t first_vertex,
                         Error *err);
bool scene_data_add_instance(SceneData *data, const SceneInstance *instance, Error *err);
/* After the emissive table: each mesh's emissive range, each instance's world box (swept when it
 * moves, with its motion aligned to the shortest arc), num_moving, two_level and the world
 * bounds. scene_data_finish calls it (adding mesh 0 and one identity instance when no mesh was
 * added); call it again after changing instances. */
void scene_data_finish_instances(SceneData *data);
/* Applies m to the triangles and vertices appended since first_triangle / first_vertex: points by
 * m, normals by its inverse transpose, and a mirroring m (det < 0) reverses each triangle's
 * corners so that the front stays where the transformed normal points (DESIGN "Objects"). */
void scene_data_bake_transform(SceneData *data, uint32_t first_triangle, uint32_t first_vertex,
                               const Affine *m);

#endif
