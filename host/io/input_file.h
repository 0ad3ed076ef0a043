/* SPDX-License-Identifier: MIT */
/* input_file.h: reads one input file (OBJ, MTL, texture) whole into memory, as untrusted input:
 * only a regular file is read (a folder, FIFO or device such as /dev/zero is refused by name before
 * any read, since reading one never ends or means nothing), and never more than a stated limit, so
 * a single input cannot make the renderer allocate without bound. */
#ifndef PT_INPUT_FILE_H
#define PT_INPUT_FILE_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

/* The limits on one file (documented in README "Fuzzing"). OBJ line numbers and tinyobjloader's
 * indices are int, which a 1 GiB file cannot overflow. */
#define INPUT_LIMIT_OBJ ((size_t)1 << 30)
#define INPUT_LIMIT_MTL ((size_t)64 << 20)
#define INPUT_LIMIT_TEXTURE ((size_t)1 << 30)

/* On success *data is malloc'ed, size bytes plus a terminating NUL (not counted). `kind` names
 * the file in messages, with its article ("an OBJ file", "a material library", "a texture").
 * Errors, one line naming the path: ERR_FILE_MISSING (no such file), ERR_FILE_READ (not a
 * regular file, unreadable), ERR_TOO_LARGE (over `limit`, or out of memory). */
bool input_file_read(const char *path, const char *kind, size_t limit, char **data, size_t *size,
                     Error *err);

/* The same rule for a reader that streams (a checkpoint): the open descriptor of a regular file
 * and its *size, or -1 with err set as above (nothing read from a FIFO or device). */
int input_file_open(const char *path, const char *kind, long long *size, Error *err);

#endif
