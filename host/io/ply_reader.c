/* SPDX-License-Identifier: MIT */
/* ply_reader.c: PLY meshes, read by our own code: the header is parsed into elements and
 * properties by ply_header.c, which also checks every element count against the bytes that follow
 * (a 1 KB file claiming 10^12 vertices is refused, not allocated); then the body is read
 * value by value (ascii tokens or binary scalars of either byte order). Faces are kept until every
 * element is read (PLY lets the face element come first) and then triangulated like OBJ n-gons.
 * Element items in messages count from 0, like PLY's vertex indices. */
#include "io/ply_reader.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_file.h"
#include "io/ply_header.h"
#include "io/triangulate.h"

#define PLY_MAX_FACE_CORNERS 255 /* as OBJ (tinyobjloader's limit); ear clipping is quadratic */

static bool g_quiet;

/* The vertex properties read, in the order of a vertex's values. */
enum { ROLE_X, ROLE_Y, ROLE_Z, ROLE_NX, ROLE_NY, ROLE_NZ, ROLE_U, ROLE_V, NUM_ROLES };

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

static bool fail(Ply *p, ErrorCode code, int line, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static bool fail(Ply *p, ErrorCode code, int line, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    ply_failv(p->path, p->err, code, line, fmt, args);
    va_end(args);
    return false;
}

/* The line to name for an error in the body: ascii has lines, binary does not. */
static int body_line(const Ply *p)
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
            fail(p, ERR_OBJ_PARSE, p->line, "bad number '%.*s'", (int)(len < 40 ? len : 40), start);
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
static bool read_item_value(Ply *p, int type, const PlyElement *e, uint64_t item, double *out)
{
    ReadStatus status = read_value(p, type, out);
    if (status == READ_END)
        return fail(p, ERR_OBJ_PARSE, 0, "%s (%s %llu of %llu)",
                    p->h.format == PLY_ASCII ? "unexpected end of data" : "truncated binary data",
                    e->name, (unsigned long long)item, (unsigned long long)e->count);
    return status == READ_OK;
}

/* Reads a list's count: a whole number the rest of the data can hold. */
static bool read_list_count(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t item,
                            size_t *count)
{
    double value;
    if (!read_item_value(p, prop->count_type, e, item, &value))
        return false;
    uint64_t least = p->h.format == PLY_ASCII ? 1u : PLY_TYPES[prop->type].size;
    if (!(value >= 0.0) || value != floor(value) || value > (double)((p->size - p->pos) / least))
        return fail(p, ERR_OBJ_PARSE, body_line(p), "%s %llu: list '%s' has a bad length %g",
                    e->name, (unsigned long long)item, prop->name, value);
    *count = (size_t)value;
    return true;
}

static bool grow(void **array, size_t *capacity, size_t needed, size_t element_size)
{
    if (needed <= *capacity)
        return true;
    size_t wanted = *capacity ? 2 * *capacity : 256;
    while (wanted < needed)
        wanted *= 2;
    void *grown = realloc(*array, wanted * element_size);
    if (!grown)
        return false;
    *array = grown;
    *capacity = wanted;
    return true;
}

/* Appends one face of n corners, which the caller fills: face_corners[num_corners - n, ...).
 * (n may be 0: a face PLY allows, skipped later with a warning.) */
static bool add_face(Ply *p, size_t n)
{
    if (!grow((void **)&p->face_sizes, &p->faces_capacity, p->num_faces + 1, sizeof *p->face_sizes) ||
        !grow((void **)&p->face_corners, &p->corners_capacity, p->num_corners + n,
              sizeof *p->face_corners))
        return fail(p, ERR_TOO_LARGE, 0, "out of memory reading faces");
    p->face_sizes[p->num_faces++] = (uint16_t)n;
    p->num_corners += n;
    return true;
}

/* One face's vertex_indices list, every index checked against the vertex count. */
static bool read_face_list(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t face,
                           uint64_t num_vertices)
{
    size_t n;
    if (!read_list_count(p, prop, e, face, &n))
        return false;
    if (n > PLY_MAX_FACE_CORNERS)
        return fail(p, ERR_TOO_LARGE, body_line(p), "face %llu has %zu vertices (the limit is %d)",
                    (unsigned long long)face, n, PLY_MAX_FACE_CORNERS);
    size_t first = p->num_corners;
    if (!add_face(p, n))
        return false;
    for (size_t k = 0; k < n; k++) {
        double index;
        if (!read_item_value(p, prop->type, e, face, &index))
            return false;
        if (!(index >= 0.0) || index != floor(index) || index >= (double)num_vertices)
            return fail(p, ERR_OBJ_INDEX, body_line(p),
                        "face %llu: vertex index %g out of range (%llu vertices)",
                        (unsigned long long)face, index, (unsigned long long)num_vertices);
        p->face_corners[first + k] = (int32_t)index;
    }
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

/* One tristrips item (Cyberware scans): a list of vertex indices where -1 restarts the strip;
 * each index after the first two makes a triangle with the two before it, every other one with
 * its first two corners swapped so that all keep the strip's winding. Triangles with a repeated
 * corner (used to turn a strip) are not emitted. */
static bool read_strip_list(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t item,
                            uint64_t num_vertices)
{
    size_t n, have = 0, parity = 0;
    if (!read_list_count(p, prop, e, item, &n))
        return false;
    int32_t a = -1, b = -1;
    for (size_t k = 0; k < n; k++) {
        double index;
        if (!read_item_value(p, prop->type, e, item, &index))
            return false;
        if (index == -1.0) {
            have = parity = 0;
            continue;
        }
        if (!(index >= 0.0) || index != floor(index) || index >= (double)num_vertices)
            return fail(p, ERR_OBJ_INDEX, body_line(p),
                        "tristrips %llu: vertex index %g out of range (%llu vertices; -1 restarts)",
                        (unsigned long long)item, index, (unsigned long long)num_vertices);
        int32_t c = (int32_t)index;
        if (have >= 2) {
            if (a != b && b != c && a != c) {
                if (!add_face(p, 3))
                    return false;
                int32_t *t = p->face_corners + p->num_corners - 3;
                t[0] = parity ? b : a;
                t[1] = parity ? a : b;
                t[2] = c;
            }
            parity ^= 1;
        }
        a = b;
        b = c;
        have++;
    }
    return true;
}

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
        return fail(p, ERR_OBJ_PARSE, 0, "the %s element lacks a vertex_indices list", f->name);
    if (PLY_TYPES[f->properties[*list].type].kind == PLY_FLOAT)
        return fail(p, ERR_OBJ_PARSE, 0, "%s: vertex_indices has a float index type", f->name);
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
            return fail(p, ERR_OBJ_PARSE, 0, "two '%s' elements", name);
        if (slot)
            *slot = i;
    }
    if (m->vertex_element < 0)
        return fail(p, ERR_OBJ_PARSE, 0, "no 'vertex' element");
    const PlyElement *v = &p->h.elements[m->vertex_element];
    if (v->count > INT32_MAX)
        return fail(p, ERR_TOO_LARGE, 0, "%llu vertices (the limit is %d)",
                    (unsigned long long)v->count, INT32_MAX);
    bool seen[NUM_ROLES] = {false};
    for (int k = 0; k < v->num_properties; k++) {
        m->roles[k] = vertex_role(&v->properties[k]);
        if (m->roles[k] >= 0)
            seen[m->roles[k]] = true;
    }
    if (!seen[ROLE_X] || !seen[ROLE_Y] || !seen[ROLE_Z])
        return fail(p, ERR_OBJ_PARSE, 0, "the vertex element lacks property x, y or z");
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
        if (prop->count_type >= 0 && !read_list_count(p, prop, e, i, &n))
            return false;
        for (size_t j = 0; j < n; j++) {
            double value;
            if (!read_item_value(p, prop->type, e, i, &value))
                return false;
            if (m->roles[k] >= 0) {
                values[m->roles[k]] = (float)value;
                if (!isfinite(values[m->roles[k]]))
                    return fail(p, ERR_OBJ_NONFINITE, body_line(p),
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
                if (!read_face_list(p, prop, e, i, num_vertices))
                    return false;
                continue;
            }
            if (e_index == m->strip_element && k == m->strip_list) {
                if (!read_strip_list(p, prop, e, i, num_vertices))
                    return false;
                continue;
            }
            size_t n = 1;
            if (prop->count_type >= 0 && !read_list_count(p, prop, e, i, &n))
                return false;
            for (size_t j = 0; j < n; j++) {
                double skipped;
                if (!read_item_value(p, prop->type, e, i, &skipped))
                    return false;
            }
        }
    }
    return true;
}

/* Triangulates the faces read, in file order, like OBJ n-gons. */
static bool emit_triangles(Ply *p, Mesh *out)
{
    size_t max_triangles = 0, short_faces = 0;
    for (size_t f = 0; f < p->num_faces; f++)
        max_triangles += p->face_sizes[f] >= 3 ? p->face_sizes[f] - 2u : 0u;
    out->corners = malloc((max_triangles ? 9 * max_triangles : 1) * sizeof *out->corners);
    out->material_ids = malloc((max_triangles ? max_triangles : 1) * sizeof *out->material_ids);
    if (!out->corners || !out->material_ids)
        return fail(p, ERR_TOO_LARGE, 0, "out of memory for %zu triangles", max_triangles);
    float points[3 * PLY_MAX_FACE_CORNERS];
    uint32_t triangles[3 * PLY_MAX_FACE_CORNERS];
    size_t first = 0; /* the face's first corner in face_corners (NULL when no face has one) */
    for (size_t f = 0; f < p->num_faces; first += p->face_sizes[f++]) {
        size_t n = p->face_sizes[f];
        if (n < 3) {
            short_faces++;
            continue;
        }
        const int32_t *corner = p->face_corners + first;
        out->num_faces++;
        for (size_t k = 0; k < n; k++)
            memcpy(points + 3 * k, out->positions + 3 * (size_t)corner[k], 3 * sizeof(float));
        size_t count = triangulate_polygon(points, n, triangles);
        for (size_t t = 0; t < count; t++) {
            int32_t *emitted = out->corners + 9 * out->num_triangles;
            for (int c = 0; c < 3; c++) {
                int32_t v = corner[triangles[3 * t + c]];
                emitted[3 * c + 0] = v;
                emitted[3 * c + 1] = out->texcoords ? v : -1;
                emitted[3 * c + 2] = out->normals ? v : -1;
            }
            out->material_ids[out->num_triangles++] = -1;
        }
    }
    if (short_faces > 0)
        warn("%s: %zu face%s with fewer than 3 vertices skipped", p->path, short_faces,
             short_faces == 1 ? "" : "s");
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
        return fail(p, ERR_TOO_LARGE, 0, "out of memory for %zu vertices", n);
    for (int e = 0; e < p->h.num_elements; e++)
        if (!read_element(p, &m, e, out))
            return false;
    return emit_triangles(p, out);
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
