/* SPDX-License-Identifier: MIT */
/* assimp_reader.h: the formats pt does not read itself (FBX, STL, 3DS, X3D, old .blend, OFF...)
 * through Assimp's C API (assimp/cimport.h), as plain data: one triangle mesh per Assimp mesh
 * (one material each, MTL-like terms: diffuse colour and texture, emission, opacity, and
 * PBR metallic-roughness where the file gives it), the node hierarchy flattened to instances
 * with world matrices, cameras and lights in world space. Mapping to pt's scene is
 * scene/import_assimp.c's business.
 * Assimp reads the file from memory (aiImportFileFromMemory) after io/input_file.h has checked
 * it, so Assimp itself opens no other file: a path named inside the file (a texture) is resolved
 * by us with fs_resolve_inside and may not leave the file's folder. */
#ifndef PT_ASSIMP_READER_H
#define PT_ASSIMP_READER_H

#include <stdbool.h>

#include "base/error.h"
#include "io/mesh.h"

typedef struct {
    int mesh;         /* index into meshes */
    double world[16]; /* row-major, column vectors */
} AssimpInstance;

typedef enum { ASSIMP_LIGHT_POINT, ASSIMP_LIGHT_SPOT, ASSIMP_LIGHT_DIRECTIONAL } AssimpLightType;

typedef struct {
    AssimpLightType type;
    double position[3], direction[3]; /* world space; direction: where the light travels */
    float color[3];                   /* intensity (point, spot) or irradiance (directional) */
    float cone_angle, falloff_angle;  /* spot: degrees from the axis */
} AssimpLight;

typedef struct {
    double eye[3], target[3], up[3];
    float fov_y;  /* degrees */
    float aspect; /* 0 when the file gives none */
} AssimpCamera;

typedef struct {
    Mesh *meshes; /* each with one material (materials[0]) or none */
    int num_meshes;
    AssimpInstance *instances;
    int num_instances;
    AssimpLight *lights;
    int num_lights;
    AssimpCamera camera;
    bool has_camera;
} AssimpScene;

/* Reads path; a file Assimp cannot read fails with Assimp's reason in one line. format_name
 * names the format in messages ("FBX"). */
bool assimp_read(const char *path, const char *format_name, AssimpScene *out, Error *err);
/* The same from memory; path names it in messages and anchors texture paths; hint is the
 * extension without the dot ("fbx"). */
bool assimp_read_memory(const char *path, const char *hint, const void *data, size_t size,
                        AssimpScene *out, Error *err);
void assimp_scene_free(AssimpScene *s);

#endif
