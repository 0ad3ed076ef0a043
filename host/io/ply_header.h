/* SPDX-License-Identifier: MIT */
/* ply_header.h: a PLY header (the text up to end_header) parsed into its format, elements and
 * properties, for ply_reader.c. */
#ifndef PT_PLY_HEADER_H
#define PT_PLY_HEADER_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"

#define PLY_MAX_ELEMENTS 32
#define PLY_MAX_PROPERTIES 64

typedef enum { PLY_INT, PLY_UINT, PLY_FLOAT } PlyScalarKind;
typedef struct {
    const char *name;
    uint8_t size; /* bytes in binary */
    uint8_t kind; /* PlyScalarKind */
} PlyScalarType;

/* Every scalar type by both its names (char = int8 ... double = float64). */
extern const PlyScalarType PLY_TYPES[16];

typedef struct {
    char name[32];
    int type;       /* index into PLY_TYPES: the scalar's type, or a list's item type */
    int count_type; /* a list's count type (an integer type), -1 for a scalar */
} PlyProperty;

typedef struct {
    char name[32];
    uint64_t count;
    PlyProperty properties[PLY_MAX_PROPERTIES];
    int num_properties;
} PlyElement;

typedef enum { PLY_ASCII, PLY_LITTLE_ENDIAN, PLY_BIG_ENDIAN } PlyFormat;

typedef struct {
    PlyFormat format;
    PlyElement elements[PLY_MAX_ELEMENTS];
    int num_elements;
    size_t body;   /* offset of the first byte after end_header's line */
    int body_line; /* the line number of that byte (ascii) */
    /* Lines of no PLY keyword (Blender 2.47 writes "Created by ..."), ignored: the reader warns
     * once, naming the first. */
    int unknown_lines, first_unknown_line;
    char first_unknown[64];
} PlyHeader;

/* Parses the header of the PLY text data[0..size) (NUL-terminated). comment and obj_info lines are
 * ignored, and so are lines of no PLY keyword (counted in unknown_lines). Also refuses element counts the body cannot hold (an item takes at least a byte per
 * property in ascii, its scalars and list counts in binary), so nothing sized by a count is
 * allocated for a file too small for it. Errors (ERR_OBJ_PARSE, ERR_TOO_LARGE) name the path and
 * the header line. */
bool ply_header_parse(const char *path, const char *data, size_t size, PlyHeader *out, Error *err);

/* Sets err to "path: line L: message" (line 0: "path: message") with code; returns false. The
 * header's and the body's error reporting. */
bool ply_failv(const char *path, Error *err, ErrorCode code, int line, const char *fmt,
               va_list args);

#endif
