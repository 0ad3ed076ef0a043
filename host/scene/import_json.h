/* SPDX-License-Identifier: MIT */
/* import_json.h: what the importers of scene/scene_import.h share when they write pt's JSON
 * scene: vectors, matrix transforms, the world bounds of what they placed and a camera framing
 * them (as pt frames a bare OBJ: from +z, 1.5 diagonals away). */
#ifndef PT_IMPORT_JSON_H
#define PT_IMPORT_JSON_H

#include <stdbool.h>

#include "io/mesh.h"
#include "scene/json.h"

typedef struct {
    double min[3], max[3];
    bool any;
} ImportBounds;

cJSON *import_json_vec3(const double v[3]);
cJSON *import_json_colour(const float c[3]);
/* [{"matrix": m}] (row-major, column vectors). */
cJSON *import_json_matrix_transform(const double m[16]);
/* Adds the mesh's points under world matrix m (row-major) to b. */
void import_bounds_add_mesh(ImportBounds *b, const Mesh *mesh, const double m[16]);
/* The bounds' centre and diagonal (1 when empty or flat to a point). */
double import_bounds_centre(const ImportBounds *b, double centre[3]);
/* {"eye", "target", "up", "fov_y"} looking at b's centre from +z at 1.5 diagonals. */
cJSON *import_json_framing_camera(const ImportBounds *b, double fov_y);

#endif
