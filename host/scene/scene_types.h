/* SPDX-License-Identifier: MIT */
/* scene_types.h: the scene as the user wrote it (JSON of shared/DESIGN.md, or a bare mesh file),
 * the types every reader of scene/ fills (scene_json.c, gltf_scene.c, transform_json.c) and
 * load_objects.c reads. The floor below the readers: scene.h, which loads by calling them, sits
 * above (tools/check-layers.sh refuses a reader that includes it). */
#ifndef PT_SCENE_TYPES_H
#define PT_SCENE_TYPES_H

#include <stdbool.h>

#include "base/error.h"
#include "io/gltf_loader.h"
#include "scene/camera.h"
#include "scene/material_json.h"
#include "scene/media_json.h"
#include "scene/scene_data.h"
#include "scene/scene_import.h"
#include "scene/texture_json.h"

/* The limits of the film and of path depth, for the scene file and the command line alike. */
#define FILM_SIZE_LIMIT 65536
#define MAX_DEPTH_LIMIT 1024

/* objects[i].transform and transform_end (shared/DESIGN.md "Objects"), composed. */
typedef struct {
    Affine transform;     /* identity when absent */
    Affine transform_end; /* at shutter close; equal to transform when absent */
    bool has_end;         /* "transform_end" was given */
} ObjectTransform;

/* How objects become instances (scene_load_with, pt --instancing). */
typedef enum {
    INSTANCING_AUTO,   /* objects without a transform whose mesh is used once are merged into one
                          world-space mesh; every other object is an instance */
    INSTANCING_ALWAYS, /* every object is an instance (tests, and measuring the two levels' cost) */
    INSTANCING_NEVER,  /* every static object is baked into world space, one level when nothing
                          moves (the reference of the equivalence tests; memory grows with
                          instances) */
} InstancingMode;

/* What an object's file is, by the key that named it ("obj", "ply" or "gltf"), never by its
 * extension. A MESH_GLTF object is one primitive of a glTF placed by one node: its mesh is in
 * memory (SceneDesc.object_meshes), its objects[i] the primitive's key "<file>#meshes[m].primitives[p]".
 * A MESH_IMPORTED object names a mesh of SceneDesc.imported: its key is "<file>#<mesh name>". */
typedef enum { MESH_OBJ, MESH_PLY, MESH_GLTF, MESH_IMPORTED } MeshFormat;

/* A glTF file the description read (scene/gltf_scene.h), kept until scene_desc_free: its decoded
 * primitives are the objects' meshes, its images the materials' embedded textures. */
typedef struct {
    GltfFile file;
    void *images; /* GltfImage array (scene/gltf_material.h) */
} SceneGltf;

typedef struct {
    char path[1024];    /* the scene file (.json or .obj) */
    bool camera_given;  /* false: frame the camera on the scene's bounds (bare .obj) */
    CameraDesc camera;
    int width, height;  /* film; default 512 x 512 */
    int spp, max_depth; /* default 64, 8 */
    float noise_threshold; /* render.noise_threshold: adaptive sampling; 0 = off */
    int min_spp;           /* render.min_spp; 0 = the default (render/wavefront.h) */
    bool denoise;          /* render.denoise: pt render denoises (as --denoise) */
    int sampler;           /* render.sampler: SAMPLER_* (scene/sampler.h); 0 = not given */
    float background[3];
    char environment[1024];   /* the map's path resolved against the scene file; "" = none */
    float environment_scale;  /* default 1 */
    float environment_rotation; /* degrees */
    AnalyticLight *lights; /* the "lights" array (host/scene/analytic_lights.h) */
    int num_lights;
    BlackHole *black_holes; /* the "black_holes" array, holes of mass 0 left out (scene/black_holes.h) */
    int num_black_holes;
    int num_objects;
    char (*objects)[1024]; /* mesh paths, resolved against the scene file's folder */
    MeshFormat *object_formats; /* per object, by the key that named it; NULL: all MESH_OBJ */
    ObjectOptions *object_options; /* per object; material indexes `materials` */
    ObjectTransform *object_transforms; /* per object */
    const Mesh **object_meshes; /* per object: the in-memory mesh of a MESH_GLTF object, else
                                      NULL (objects[i] is read); NULL: none */
    SceneGltf *gltf_files; /* the glTF files the objects come from */
    int num_gltf_files;
    ImportedScene imported; /* a foreign scene file's meshes (scene/scene_import.h), named by
                               objects' "mesh" key; its root is freed once read */
    TextureDesc *textures;   /* the "textures" block */
    int num_textures;
    MaterialDesc *materials; /* the "materials" block; scene material i is materials[i] */
    int num_materials;
    MediumDesc *media;      /* the "media" block; medium slot k is media[k - 1] */
    int num_media;
    uint32_t world_medium;  /* the top-level "medium": a slot, 0 = none */
    uint32_t camera_medium; /* camera.medium: a slot, 0 = the world medium */
} SceneDesc;

#endif
