/* SPDX-License-Identifier: MIT */
/* obj_lines.h: a line-level pass over an OBJ file held in memory, for what tinyobjloader does not
 * report: it reads "nan", "inf" or "abc" as 0, accepts out-of-range face indices, and keeps no line
 * numbers. Records are recognised exactly as tinyobjloader does (keyword after leading blanks,
 * followed by a space or tab; lines end at \n, \r\n or \r). */
#ifndef PT_OBJ_LINES_H
#define PT_OBJ_LINES_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

/* tinyobjloader stores corner counts in an unsigned char. */
#define OBJ_MAX_FACE_CORNERS 255
/* A longer line is refused (ERR_TOO_LARGE): no real record needs it, and tinyobjloader copies every
 * line into a string. */
#define OBJ_MAX_LINE_LENGTH (1 << 20)

typedef struct {
    size_t positions, texcoords, normals; /* v, vt, vn records */
    size_t faces;                         /* f records with at least 3 corners */
} ObjRecordCounts;

/* Checks that the file is text (a control byte other than a blank or line end is ERR_OBJ_PARSE
 * "not an OBJ text file (binary data at line N)") with lines of at most OBJ_MAX_LINE_LENGTH
 * bytes, then every v, vt, vn and f record: coordinates are numbers and finite as floats (v and vn need
 * 3, vt at least 1), face corners are i, i/j, i//k or i/j/k with indices in range (negative ones
 * relative to the records before the face, positive ones against the whole file, as tinyobjloader
 * resolves them) and at most OBJ_MAX_FACE_CORNERS corners. A face with fewer than 3 corners gets a
 * warning (tinyobjloader drops it). Errors, naming path and line: ERR_OBJ_PARSE, ERR_OBJ_NONFINITE,
 * ERR_OBJ_INDEX, ERR_TOO_LARGE. */
bool obj_lines_check(const char *text, size_t size, const char *path, ObjRecordCounts *counts,
                     Error *err);

/* 1-based line of the record number `ordinal` (0-based) with this keyword ("v", "vt", "vn" or "f";
 * faces with fewer than 3 corners are not counted, as tinyobjloader drops them); 0 when none. */
int obj_lines_find_record(const char *text, size_t size, const char *keyword, size_t ordinal);

#endif
