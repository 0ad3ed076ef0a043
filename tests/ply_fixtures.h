/* SPDX-License-Identifier: MIT */
/* ply_fixtures.h: what the PLY tests (test_io_ply*.c) share: one mesh written as OBJ and as PLY
 * ascii / binary of either byte order, a loader that must succeed, the check of a one-line error,
 * and header fragments for small hand-written files. */
#ifndef PT_TEST_PLY_FIXTURES_H
#define PT_TEST_PLY_FIXTURES_H

#include <stdbool.h>

#include "base/error.h"
#include "io/mesh.h"

#define HEAD "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
#define TRI "0 0 0\n1 0 0\n0 1 0\n"
#define FACE "element face 1\nproperty list uchar int vertex_indices\n"

/* The test mesh written into folder dir; each returns the file's path. */
const char *write_obj(const char *dir);
const char *write_ascii(const char *dir);
const char *write_binary(const char *dir, bool big);
/* Loads path, which must succeed. */
void load_ply_ok(const char *path, Mesh *mesh);
/* Loading must fail with this code and a message holding `mentions` (and the file's name). */
void expect_error_file(const char *path, ErrorCode code, const char *mentions);
/* The same for text written to a temporary bad.ply. */
void expect_error(const char *text, ErrorCode code, const char *mentions);

#endif
