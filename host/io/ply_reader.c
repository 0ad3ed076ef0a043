/* SPDX-License-Identifier: MIT */
/* ply_reader.c: PLY meshes, read by our own code: the header is parsed into elements and
 * properties by ply_header.c, which also checks every element count against the bytes that follow
 * (a 1 KB file claiming 10^12 vertices is refused, not allocated); then the body is read
 * value by value (ascii tokens or binary scalars of either byte order). Faces are kept until every
 * element is read (PLY lets the face element come first) and then triangulated like OBJ n-gons.
 * Element items in messages count from 0, like PLY's vertex indices. This file reads values,
 * vertices and the layout; ply_faces.c keeps the face and tristrips lists and triangulates them. */
#include "io/ply_reader.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_file.h"
#include "io/ply_header.h"
#include "io/ply_internal.h"

static bool g_quiet;

/* The vertex properties read, in the order of a vertex's values. */
enum { ROLE_X, ROLE_Y, ROLE_Z, ROLE_NX, ROLE_NY, ROLE_NZ, ROLE_U, ROLE_V, NUM_ROLES };

bool ply_fail(Ply *p, ErrorCode code, int line, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    ply_failv(p->path, p->err, code, line, fmt, args);
    va_end(args);
    return false;
}

/* The line to name for an error in the body: ascii has lines, binary does not. */
int ply_body_line(const Ply *p)
{
    return p->h.format == PLY_ASCII ? p->line : 0;
}

typedef enum { READ_OK, READ_END, READ_BAD } ReadStatus;

/* Reads one scalar of PLY_TYPES[type] as a double. */
static ReadStatus read_value(Ply *p, int type, double *out)
{
    const PlyScalarType *t = &PLY_TYPES[type];
    if (p->h.format == PLY_ASCII) {
        while (p->pos < p->size && strchr(" \t\r\n\v\f", p->data[p->pos]) && p->data[p->pos])
            p->line += p->data[p->pos++] == '\n';
        if (p->pos >= p->size)
            return READ_END;
        const char *start = p->data + p->pos;
        size_t len = 0;
        while (p->pos + len < p->size && start[len] && !strchr(" \t\r\n\v\f", start[len]))
            len++;
        char *end;
        *out = strtod(start, &end);
        if (len == 0 || end != start + len) {
            ply_fail(p, ERR_OBJ_PARSE, p->line, "bad number '%.*s'", (int)(len < 40 ? len : 40), start);
            return READ_BAD;
        }
        p->pos += len;
        return READ_OK;
    }
    if (p->size - p->pos < t->size)
        return READ_END;
    const unsigned char *bytes = (const unsigned char *)p->data + p->pos;
    uint64_t bits = 0;
    for (int i = 0; i < t->size; i++) {
        int from = p->h.format == PLY_LITTLE_ENDIAN ? t->size - 1 - i : i;
        bits = bits << 8 | bytes[from];
    }
    p->pos += t->size;
    if (t->kind == PLY_FLOAT && t->size == 4) {
        uint32_t b32 = (uint32_t)bits;
        float f;
        memcpy(&f, &b32, sizeof f);
        *out = f;
    } else if (t->kind == PLY_FLOAT) {
        memcpy(out, &bits, sizeof *out);
    } else if (t->kind == PLY_UINT) {
        *out = (double)bits;
    } else {
        uint64_t sign = (uint64_t)1 << (8 * t->size - 1);
        *out = (bits & sign) ? -(double)((sign << 1) - bits) : (double)bits;
    }
    return READ_OK;
}

/* Reads a value of an element item, naming the item when the data ends. */
bool ply_read_item_value(Ply *p, int type, const PlyElement *e, uint64_t item, double *out)
{
    ReadStatus status = read_value(p, type, out);
    if (status == READ_END)
        return ply_fail(p, ERR_OBJ_PARSE, 0, "%s (%s %llu of %llu)",
                    p->h.format == PLY_ASCII ? "unexpected end of data" : "truncated binary data",
                    e->name, (unsigned long long)item, (unsigned long long)e->count);
    return status == READ_OK;
}

/* Reads a list's count: a whole number the rest of the data can hold. */
bool ply_read_list_count(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t item,
                            size_t *count)
{
    double value;
    if (!ply_read_item_value(p, prop->count_type, e, item, &value))
        return false;
    uint64_t least = p->h.format == PLY_ASCII ? 1u : PLY_TYPES[prop->type].size;
    if (!(value >= 0.0) || value != floor(value) || value > (double)((p->size - p->pos) / least))
        return ply_fail(p, ERR_OBJ_PARSE, ply_body_line(p), "%s %llu: list '%s' has a bad length %g",
                    e->name, (unsigned long long)item, prop->name, value);
    *count = (size_t)value;
    return true;
}

/* The vertex property's role (ROLE_*), or -1 for one that is skipped. */
static int vertex_role(const PlyProperty *prop)
{
    static const char *const names[][3] = {{"x"}, {"y"}, {"z"}, {"nx"}, {"ny"}, {"nz"},
                                           {"u", "s", "texture_u"}, {"v", "t", "texture_v"}};
    if (prop->count_type >= 0)
        return -1;
    for (int role = 0; role < NUM_ROLES; role++)
        for (int a = 0; a < 3 && names[role][a]; a++)
            if (strcmp(prop->name, names[role][a]) == 0)
                return role;
    return -1;
}

/* Which properties a mesh needs, found once from the header. */
typedef struct {
    int vertex_element, face_element, strip_element;
    int roles[PLY_MAX_PROPERTIES]; /* vertex property -> ROLE_*, -1 skipped */
    int face_list, strip_list;     /* the face / tristrips element's vertex_indices property */
    bool has_normals, has_uvs;
} MeshLayout;

/* The vertex_indices (or vertex_index) list of element e (face or tristrips), when present. */
static bool find_index_list(Ply *p, int e, int *list)
{
    if (e < 0)
        return true;
    const PlyElement *f = &p->h.elements[e];
    for (int k = 0; k < f->num_properties && *list < 0; k++) {
        const char *name = f->properties[k].name;
        if (f->properties[k].count_type >= 0 &&
            (strcmp(name, "vertex_indices") == 0 || strcmp(name, "vertex_index") == 0))
            *list = k;
    }
    if (*list < 0)
        return ply_fail(p, ERR_OBJ_PARSE, 0, "the %s element lacks a vertex_indices list", f->name);
    if (PLY_TYPES[f->properties[*list].type].kind == PLY_FLOAT)
        return ply_fail(p, ERR_OBJ_PARSE, 0, "%s: vertex_indices has a float index type", f->name);
    return true;
}

static bool find_layout(Ply *p, MeshLayout *m)
{
    m->vertex_element = m->face_element = m->face_list = m->strip_element = m->strip_list = -1;
    for (int i = 0; i < p->h.num_elements; i++) {
        const char *name = p->h.elements[i].name;
        int *slot = strcmp(name, "vertex") == 0 ? &m->vertex_element
                    : strcmp(name, "face") == 0 ? &m->face_element
                    : strcmp(name, "tristrips") == 0 ? &m->strip_element : NULL;
        if (slot && *slot >= 0)
            return ply_fail(p, ERR_OBJ_PARSE, 0, "two '%s' elements", name);
        if (slot)
            *slot = i;
    }
    if (m->vertex_element < 0)
        return ply_fail(p, ERR_OBJ_PARSE, 0, "no 'vertex' element");
    const PlyElement *v = &p->h.elements[m->vertex_element];
    if (v->count > INT32_MAX)
        return ply_fail(p, ERR_TOO_LARGE, 0, "%llu vertices (the limit is %d)",
                    (unsigned long long)v->count, INT32_MAX);
    bool seen[NUM_ROLES] = {false};
    for (int k = 0; k < v->num_properties; k++) {
        m->roles[k] = vertex_role(&v->properties[k]);
        if (m->roles[k] >= 0)
            seen[m->roles[k]] = true;
    }
    if (!seen[ROLE_X] || !seen[ROLE_Y] || !seen[ROLE_Z])
        return ply_fail(p, ERR_OBJ_PARSE, 0, "the vertex element lacks property x, y or z");
    m->has_normals = seen[ROLE_NX] && seen[ROLE_NY] && seen[ROLE_NZ];
    m->has_uvs = seen[ROLE_U] && seen[ROLE_V];
    return find_index_list(p, m->face_element, &m->face_list) &&
           find_index_list(p, m->strip_element, &m->strip_list);
}

/* Reads one vertex's values into out (positions, normals, uvs as the mesh has them). */
static bool read_vertex(Ply *p, const MeshLayout *m, uint64_t i, Mesh *out)
{
    const PlyElement *e = &p->h.elements[m->vertex_element];
    float values[NUM_ROLES] = {0};
    for (int k = 0; k < e->num_properties; k++) {
        const PlyProperty *prop = &e->properties[k];
        size_t n = 1;
        if (prop->count_type >= 0 && !ply_read_list_count(p, prop, e, i, &n))
            return false;
        for (size_t j = 0; j < n; j++) {
            double value;
            if (!ply_read_item_value(p, prop->type, e, i, &value))
                return false;
            if (m->roles[k] >= 0) {
                values[m->roles[k]] = (float)value;
                if (!isfinite(values[m->roles[k]]))
                    return ply_fail(p, ERR_OBJ_NONFINITE, ply_body_line(p),
                                "vertex %llu: property %s is not finite (%g)",
                                (unsigned long long)i, prop->name, value);
            }
        }
    }
    memcpy(out->positions + 3 * i, values + ROLE_X, 3 * sizeof(float));
    if (out->normals)
        memcpy(out->normals + 3 * i, values + ROLE_NX, 3 * sizeof(float));
    if (out->texcoords)
        memcpy(out->texcoords + 2 * i, values + ROLE_U, 2 * sizeof(float));
    return true;
}

/* Reads or skips every item of element e. */
static bool read_element(Ply *p, const MeshLayout *m, int e_index, Mesh *out)
{
    const PlyElement *e = &p->h.elements[e_index];
    if (e->num_properties == 0)
        return true;
    uint64_t num_vertices = p->h.elements[m->vertex_element].count;
    for (uint64_t i = 0; i < e->count; i++) {
        if (e_index == m->vertex_element) {
            if (!read_vertex(p, m, i, out))
                return false;
            continue;
        }
        for (int k = 0; k < e->num_properties; k++) {
            const PlyProperty *prop = &e->properties[k];
            if (e_index == m->face_element && k == m->face_list) {
                if (!ply_read_face_list(p, prop, e, i, num_vertices))
                    return false;
                continue;
            }
            if (e_index == m->strip_element && k == m->strip_list) {
                if (!ply_read_strip_list(p, prop, e, i, num_vertices))
                    return false;
                continue;
            }
            size_t n = 1;
            if (prop->count_type >= 0 && !ply_read_list_count(p, prop, e, i, &n))
                return false;
            for (size_t j = 0; j < n; j++) {
                double skipped;
                if (!ply_read_item_value(p, prop->type, e, i, &skipped))
                    return false;
            }
        }
    }
    return true;
}

static bool load(Ply *p, Mesh *out)
{
    MeshLayout m;
    if (!ply_header_parse(p->path, p->data, p->size, &p->h, p->err))
        return false;
    p->pos = p->h.body;
    p->line = p->h.body_line;
    if (p->h.unknown_lines && !g_quiet)
        warn("%s: line %d: %d header line%s of no PLY keyword ignored (the first: '%s')", p->path,
             p->h.first_unknown_line, p->h.unknown_lines, p->h.unknown_lines == 1 ? "" : "s",
             p->h.first_unknown);
    if (!find_layout(p, &m))
        return false;
    size_t n = (size_t)p->h.elements[m.vertex_element].count;
    out->num_positions = n;
    out->positions = calloc(n ? 3 * n : 1, sizeof(float));
    if (m.has_normals) {
        out->num_normals = n;
        out->normals = calloc(n ? 3 * n : 1, sizeof(float));
    }
    if (m.has_uvs) {
        out->num_texcoords = n;
        out->texcoords = calloc(n ? 2 * n : 1, sizeof(float));
    }
    if (!out->positions || (m.has_normals && !out->normals) || (m.has_uvs && !out->texcoords))
        return ply_fail(p, ERR_TOO_LARGE, 0, "out of memory for %zu vertices", n);
    for (int e = 0; e < p->h.num_elements; e++)
        if (!read_element(p, &m, e, out))
            return false;
    return ply_emit_triangles(p, out);
}

void ply_reader_set_quiet(bool quiet)
{
    g_quiet = quiet;
}

bool ply_load(const char *path, Mesh *out, Error *err)
{
    memset(out, 0, sizeof *out);
    Ply *p = calloc(1, sizeof *p);
    if (!p) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
        return false;
    }
    p->path = path;
    p->err = err;
    char *data = NULL;
    bool ok = input_file_read(path, "a PLY file", INPUT_LIMIT_OBJ, &data, &p->size, err);
    if (ok) {
        p->data = data;
        ok = load(p, out);
    }
    free(data);
    free(p->face_sizes);
    free(p->face_corners);
    free(p);
    if (!ok)
        mesh_free(out);
    return ok;
}
