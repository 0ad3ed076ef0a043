/* SPDX-License-Identifier: MIT */
/* obj_loader.h: C API over tinyobjloader (host/io/obj_loader.cc). tinyobjloader's own triangulation
 * is off: every n-gon is triangulated here by ear clipping (triangulate.h), which is correct for
 * concave planar polygons where tinyobjloader's fan is not. */
#ifndef PT_OBJ_LOADER_H
#define PT_OBJ_LOADER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"

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
} ObjMesh;

/* Loads an OBJ and its MTL files. Errors: ERR_FILE_MISSING, ERR_FILE_READ, ERR_OBJ_PARSE,
 * ERR_OBJ_INDEX (face index out of range: names the file, line and index), ERR_OBJ_NONFINITE
 * (names file and line), ERR_TOO_LARGE (a face with more than 255 corners, tinyobjloader's limit).
 * A missing MTL or an unknown material name is a warning (default material); so is a face with
 * fewer than 3 corners (skipped). Faces with a repeated corner may give fewer than n - 2
 * triangles (zero-area ones are dropped). On failure *out is left empty. */
bool obj_load(const char *path, ObjMesh *out, Error *err);
/* MTL statements and texture options pt does not use are warned about once per name per file;
 * quiet (pt render --quiet) silences those warnings. */
void obj_loader_set_quiet(bool quiet);
void obj_free(ObjMesh *mesh);

#endif
