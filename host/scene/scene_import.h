/* SPDX-License-Identifier: MIT */
/* scene_import.h: how the readers of other tools' scene files (COLLADA, Mitsuba 3 XML, pbrt-v4,
 * the formats Assimp reads) hand their scene to pt: as the JSON scene of shared/DESIGN.md, built
 * as a cJSON tree, plus meshes held in memory that the tree's objects name with the key "mesh"
 * ({"mesh": NAME, "material": ..., "transform": [{"matrix": [...]}]}). One description, one set
 * of checks and defaults: an imported scene and the same scene written as pt JSON flatten to the
 * same arrays, and objects naming one mesh share it (instancing). The tree's file names ("obj",
 * "ply", texture and environment "file") are relative to the imported file, whose folder is the
 * tree's folder; each importer resolves them with fs_resolve_inside (base/fs.h) first, since a
 * path inside a foreign file may not leave its folder. An importer prints one warning per thing
 * it drops (base/error.h warn) and fails with one line naming the file, the line or element, and
 * what is wrong. */
#ifndef PT_SCENE_IMPORT_H
#define PT_SCENE_IMPORT_H

#include <stdbool.h>

#include "base/error.h"
#include "io/mesh.h"
#include "scene/json.h"
#include "scene/texture_json.h"

typedef struct {
    char name[SCENE_NAME_LIMIT];
    Mesh mesh;
} ImportedMesh;

typedef struct {
    cJSON *root; /* a pt JSON scene; NULL until the importer creates it */
    ImportedMesh *meshes;
    int num_meshes;
    /* Name -> mesh index (open addressing, -1 = empty, a power of two in size): scenes of many
     * thousands of shapes look names up once per shape and once per object. */
    int *name_index;
    int name_index_size;
} ImportedScene;

/* Moves *mesh into s under name (names are unique: the caller makes them so; an existing name is
 * an error) and empties *mesh. Returns false (err set, *mesh freed) when out of memory, the name
 * is taken or too long. */
bool imported_scene_add_mesh(ImportedScene *s, const char *name, Mesh *mesh, Error *err);
/* The index of the mesh called name, or -1. */
int imported_scene_find_mesh(const ImportedScene *s, const char *name);
void imported_scene_free(ImportedScene *s);

/* An importer: reads path (a regular file, io/input_file.h) into *out (empty on entry; freed by
 * the caller whatever the result). */
typedef bool (*SceneImporter)(const char *path, ImportedScene *out, Error *err);

/* The foreign formats by extension (ASCII case ignored): X(extension, importer, format name).
 * An importer of NULL is a format pt recognises but does not read yet: refused in one line that
 * names it and lists what pt reads. The readers' own headers declare the importers. */
#define SCENE_IMPORTERS(X)                                                                         \
    X(".dae", import_collada, "COLLADA")                                                           \
    X(".xml", mitsuba_import, "Mitsuba 3 XML")                                                     \
    X(".pbrt", import_pbrt, "pbrt-v4")                                                             \
    X(".fbx", import_assimp, "FBX")                                                                \
    X(".stl", import_assimp, "STL")                                                                \
    X(".3ds", import_assimp, "3DS")                                                                \
    X(".x3d", import_assimp, "X3D")                                                                \
    X(".blend", import_assimp, "Blender")                                                          \
    X(".off", import_assimp, "OFF")                                                                \
    X(".usd", NULL, "USD")                                                                         \
    X(".usda", NULL, "USD")                                                                        \
    X(".usdc", NULL, "USD")                                                                        \
    X(".usdz", NULL, "USD")                                                                        \
    X(".abc", NULL, "Alembic")                                                                     \
    X(".wrl", NULL, "VRML")                                                                        \
    X(".3mf", NULL, "3MF")                                                                         \
    X(".max", NULL, "3ds Max")                                                                     \
    X(".ma", NULL, "Maya")                                                                         \
    X(".mb", NULL, "Maya")                                                                         \
    X(".c4d", NULL, "Cinema 4D")                                                                   \
    X(".lwo", NULL, "LightWave")                                                                   \
    X(".dxf", NULL, "DXF")                                                                         \
    X(".step", NULL, "STEP")                                                                       \
    X(".stp", NULL, "STEP")                                                                        \
    X(".iges", NULL, "IGES")                                                                       \
    X(".igs", NULL, "IGES")                                                                        \
    X(".ifc", NULL, "IFC")

#endif
