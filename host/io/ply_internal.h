/* SPDX-License-Identifier: MIT */
/* ply_internal.h: what ply_reader.c (values, vertices, layout) and ply_faces.c (face and
 * tristrips lists, triangulation) share: the reader's state and its value readers. */
#ifndef PT_PLY_INTERNAL_H
#define PT_PLY_INTERNAL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "io/mesh.h"
#include "io/ply_header.h"

#define PLY_MAX_FACE_CORNERS 255 /* as OBJ (tinyobjloader's limit); ear clipping is quadratic */

typedef struct {
    const char *path;
    Error *err;
    const char *data;
    size_t size, pos; /* pos: the next byte to read */
    int line;         /* ascii: the line of pos */
    PlyHeader h;
    /* Faces as read: corner counts, and their vertex indices one after another. */
    uint16_t *face_sizes;
    int32_t *face_corners;
    size_t num_faces, faces_capacity, num_corners, corners_capacity;
} Ply;

/* Sets err (via ply_failv) and returns false. */
bool ply_fail(Ply *p, ErrorCode code, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
/* The line to name for an error in the body: ascii has lines, binary does not. */
int ply_body_line(const Ply *p);
/* Reads a value of an element item, naming the item when the data ends. */
bool ply_read_item_value(Ply *p, int type, const PlyElement *e, uint64_t item, double *out);
/* Reads a list's count: a whole number the rest of the data can hold. */
bool ply_read_list_count(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t item,
                         size_t *count);

/* ply_faces.c: one face's vertex_indices list / one tristrips item, appended to p's faces. */
bool ply_read_face_list(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t face,
                        uint64_t num_vertices);
bool ply_read_strip_list(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t item,
                         uint64_t num_vertices);
/* Triangulates the faces read, in file order, like OBJ n-gons. */
bool ply_emit_triangles(Ply *p, Mesh *out);

#endif
