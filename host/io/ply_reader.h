/* SPDX-License-Identifier: MIT */
/* ply_reader.h: a reader of PLY meshes (the scanned-mesh format: ascii 1.0, binary_little_endian
 * 1.0, binary_big_endian 1.0) into the Mesh that OBJ files load to. Read: the vertex element's
 * x y z, nx ny nz, and u v (or s t, texture_u texture_v); the face element's vertex_indices (or
 * vertex_index) list, and a tristrips element's (Cyberware scans: -1 restarts a strip). Every
 * other property, list or element is skipped by its size; header lines of no PLY keyword are
 * ignored with one warning. */
#ifndef PT_PLY_READER_H
#define PT_PLY_READER_H

#include <stdbool.h>

#include "base/error.h"
#include "io/mesh.h"

/* Fills *out like obj_load: per-vertex normals and uvs become per-corner indices equal to the
 * position index; no materials (material_ids -1). Polygons are triangulated by ear clipping like
 * OBJ n-gons, in file order. A face with fewer than 3 vertices is skipped with a warning. Errors,
 * one line naming the file and the line (header, ascii) or the element item: ERR_FILE_MISSING,
 * ERR_FILE_READ, ERR_OBJ_PARSE (bad header or data, truncated data, element counts the file
 * cannot hold), ERR_OBJ_INDEX, ERR_OBJ_NONFINITE, ERR_TOO_LARGE. On failure *out is left empty. */
bool ply_load(const char *path, Mesh *out, Error *err);
/* The warning about unknown header lines silenced (pt render --quiet). */
void ply_reader_set_quiet(bool quiet);

#endif
