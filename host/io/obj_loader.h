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
#include "io/mesh.h"

/* Loads an OBJ and its MTL files. Errors: ERR_FILE_MISSING, ERR_FILE_READ, ERR_OBJ_PARSE,
 * ERR_OBJ_INDEX (face index out of range: names the file, line and index), ERR_OBJ_NONFINITE
 * (names file and line), ERR_TOO_LARGE (a face with more than 255 corners, tinyobjloader's limit).
 * A missing MTL or an unknown material name is a warning (default material); so is a face with
 * fewer than 3 corners (skipped). Faces with a repeated corner may give fewer than n - 2
 * triangles (zero-area ones are dropped). On failure *out is left empty. */
bool obj_load(const char *path, Mesh *out, Error *err);
/* MTL statements and texture options pt does not use are warned about once per name per file;
 * quiet (pt render --quiet) silences those warnings. */
void obj_loader_set_quiet(bool quiet);

#endif
