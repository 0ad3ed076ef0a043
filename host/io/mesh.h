/* SPDX-License-Identifier: MIT */
/* mesh.h: the mesh every reader of io/ fills (obj_loader.h, ply_reader.h, gltf_loader.h), in one
 * header below them so that none includes another for it. ObjMaterial is the MTL material of an
 * OBJ's faces (mtl_reader.h reads it). */
#ifndef PT_MESH_H
#define PT_MESH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct {
    char name[128];
    float kd[3], ks[3], ke[3];
    float tf[3];    /* transmission filter (Tf or Kt), 1 1 1 when absent */
    float ni;       /* index of refraction, 1 when absent */
    float d;        /* dissolve, 1 when absent */
    int illum;      /* illumination model, -1 when absent */
    float ns;       /* specular exponent */
    float pr, pm;   /* PBR extension: roughness, metallic */
    bool has_ns, has_pr, has_pm; /* whether Ns, Pr, Pm were given */
    float bump_scale; /* -bm of the normal map, 1 when absent */
    /* Texture paths resolved against the MTL's folder, "" when none. */
    char map_kd[1024];
    char map_ke[1024];
    char map_pr[1024], map_pm[1024];
    char map_d[1024];
    char map_normal[1024]; /* norm, else map_Bump / bump */
    char normal_statement[12]; /* which of them: "norm" or "map_Bump" */
} ObjMaterial;

/* A triangle mesh as a reader found it (OBJ, PLY, a glTF primitive), before the scene unifies its
 * corners (scene/scene_data.h). materials are the OBJ's MTL ones; other formats leave them empty. */

typedef struct {
    float *positions; /* xyz per vertex */
    size_t num_positions;
    float *normals; /* xyz per normal */
    size_t num_normals;
    float *texcoords; /* uv per texture coordinate */
    size_t num_texcoords;
    /* Per triangle, per corner: (position, texcoord, normal) indices, -1 where absent. 9 ints a
     * triangle, corners counter-clockwise as in the file. */
    int32_t *corners;
    int32_t *material_ids; /* per triangle, index into materials, -1 = default material */
    size_t num_triangles;
    size_t num_faces; /* faces in the file, before triangulation */
    ObjMaterial *materials;
    size_t num_materials;
} Mesh;

/* Frees what a reader allocated and empties *mesh (an empty mesh may be freed again). */
void mesh_free(Mesh *mesh);

#endif
