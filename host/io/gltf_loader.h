/* SPDX-License-Identifier: MIT */
/* gltf_loader.h: C API over tinygltf (Debian's libtinygltf, host/io/gltf_loader.cc) for the
 * geometry of a glTF 2.0 file (.gltf with .bin or data URIs, or .glb): the default scene's node
 * hierarchy flattened to world matrices, each placed mesh's primitives decoded once into the
 * Mesh that OBJ files load to, the first perspective camera and KHR_lights_punctual lights.
 * Materials and images are read from the parsed model by scene/gltf_material_read.cc.
 * glTF is +Y up, metres, right-handed, counter-clockwise fronts: pt's own conventions, so nothing
 * is converted but texture coordinates, whose v is flipped (v_pt = 1 - v_gltf: glTF's v = 0 is
 * the image's top row, pt's the bottom row as in OBJ). */
#ifndef PT_GLTF_LOADER_H
#define PT_GLTF_LOADER_H

#include <stdbool.h>

#include "base/error.h"
#include "base/transform.h"
#include "io/mesh.h"

/* One primitive of a mesh, decoded: positions, normals when given (else none: pt shades flat, as
 * the glTF specification asks), TEXCOORD_0 when given; TANGENT is checked but not kept (pt builds
 * tangent frames from the uv parameterisation, DESIGN "Conventions"). Strips and fans are
 * converted to triangle lists; degenerate triangles (repeated indices) are dropped. */
typedef struct {
    Mesh mesh;    /* material_ids -1, no materials */
    int material;    /* glTF material index; -1: the glTF default material */
    int mesh_index, primitive_index;
    bool placed;     /* a node of the scene places its mesh: only those are decoded */
    bool skipped;    /* POINTS or LINES (one warning; pt renders triangles): not decoded */
} GltfPrimitive;

/* A node of the scene that places a mesh, with its world matrix (parents' matrices applied). */
typedef struct {
    Affine world;
    int mesh, node;
} GltfPlacement;

enum { GLTF_LIGHT_POINT, GLTF_LIGHT_SPOT, GLTF_LIGHT_DIRECTIONAL };

/* A KHR_lights_punctual light as placed by its node (position, direction = -Z of the node). */
typedef struct {
    int type;            /* GLTF_LIGHT_* */
    float color[3];      /* linear, default 1 1 1 */
    float intensity;     /* candela (point, spot) or lux (directional), default 1 */
    float range;         /* 0: infinite (pt ignores range) */
    float inner_cone, outer_cone; /* radians, default 0 and pi / 4 */
    double position[3], direction[3];
    int light, node;
} GltfLight;

/* The first perspective camera met walking the scene's nodes depth-first. */
typedef struct {
    bool present;
    float yfov;          /* radians */
    double eye[3], forward[3], up[3]; /* node origin, its -Z and +Y in world space (unit) */
    int camera, node;
} GltfCamera;

typedef struct {
    char path[1024];
    GltfPrimitive *primitives; /* every primitive of every mesh, mesh by mesh */
    int num_primitives;
    int *mesh_first;           /* mesh m's primitives: [mesh_first[m], mesh_first[m + 1]) */
    int num_meshes;
    GltfPlacement *placements;
    int num_placements;
    GltfLight *lights;
    int num_lights;
    GltfCamera camera;
    void *model; /* the tinygltf::Model, for scene/gltf_material_read.cc */
} GltfFile;

/* Loads path (".glb" by its magic bytes, else glTF JSON). Errors name the file and the JSON path:
 * ERR_FILE_MISSING / ERR_FILE_READ (the file, a .bin: "buffers[0].uri"), ERR_OBJ_PARSE (JSON,
 * truncated GLB, a reference out of range, an accessor or buffer view outside its buffer, an
 * unsupported primitive mode or required extension), ERR_OBJ_INDEX (an index beyond the vertices:
 * "meshes[2].primitives[0].indices"), ERR_OBJ_NONFINITE (a position, node matrix or TRS),
 * ERR_TOO_LARGE. Unknown extensionsUsed are one warning naming them. On failure *out is empty. */
bool gltf_load(const char *path, GltfFile *out, Error *err);
void gltf_free(GltfFile *file);
/* Warnings of gltf_load (unknown extensions, ignored attributes) silenced (pt render --quiet). */
void gltf_loader_set_quiet(bool quiet);

#endif
