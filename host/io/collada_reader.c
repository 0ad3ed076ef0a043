// SPDX-License-Identifier: MIT
/* collada_reader.c: COLLADA over libxml2's tree API (io/collada_reader.h). The document is parsed
 * without network access and without entity substitution (no external or billion-laughs
 * expansions); every id the file refers to is looked up in one sorted table. */
#include "io/collada_reader.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"
#include "base/transform.h"
#include "io/input_file.h"
#include "io/triangulate.h"

#define COLLADA_FILE_LIMIT ((size_t)2 << 30)
#define NODE_DEPTH_LIMIT 64 /* nested nodes and instance_node chains; also stops cycles */
#define POLYGON_CORNER_LIMIT 4096
#define PI 3.14159265358979323846

typedef struct {
    const char *id;
    xmlNode *node;
} IdEntry;

typedef struct {
    const char *path;
    Error *err;
    ColladaDoc *doc;
    IdEntry *ids;
    size_t num_ids, cap_ids;
    unsigned warned; /* one bit per Drop: each kind of dropped thing is warned about once */
} Reader;

typedef enum { DROP_CONTROLLER, DROP_SKEW, DROP_HOLES, DROP_PRIMITIVE, DROP_GEOMETRY, DROP_CGL,
               DROP_TEXTURE, DROP_ORTHO, DROP_LINES, DROP_REFRACTION } Drop;

static void warn_once(Reader *r, Drop what, const char *fmt, const char *detail)
{
    if (r->warned & (1u << what))
        return;
    r->warned |= 1u << what;
    char message[512];
    snprintf(message, sizeof message, fmt, detail);
    warn("%s: %s", r->path, message);
}

static bool fail(Reader *r, const xmlNode *at, ErrorCode code, const char *fmt, const char *a,
                 const char *b)
{
    int line = at ? (int)xmlGetLineNo(at) : 0;
    char message[768];
    snprintf(message, sizeof message, fmt, a ? a : "", b ? b : "");
    error_set(r->err, code, r->path, line, "%s:%d: <%s>: %s", r->path, line,
              at ? (const char *)at->name : "COLLADA", message);
    return false;
}

static bool is(const xmlNode *n, const char *name)
{
    return n && n->type == XML_ELEMENT_NODE && strcmp((const char *)n->name, name) == 0;
}

static xmlNode *child(const xmlNode *n, const char *name)
{
    for (xmlNode *c = n ? n->children : NULL; c; c = c->next)
        if (is(c, name))
            return c;
    return NULL;
}

static xmlNode *next_named(xmlNode *c, const char *name)
{
    for (c = c ? c->next : NULL; c; c = c->next)
        if (is(c, name))
            return c;
    return NULL;
}

/* child(child(...)) along a path "a/b/c". */
static xmlNode *path_child(const xmlNode *n, const char *path)
{
    char part[64];
    while (n && *path) {
        size_t len = strcspn(path, "/");
        if (len >= sizeof part)
            return NULL;
        memcpy(part, path, len);
        part[len] = '\0';
        n = child(n, part);
        path += len + (path[len] == '/');
    }
    return (xmlNode *)n;
}

/* An attribute's value (libxml2 owns the memory through the node), NULL when absent. */
static const char *attr(const xmlNode *n, const char *name)
{
    for (xmlAttr *a = n ? n->properties : NULL; a; a = a->next)
        if (strcmp((const char *)a->name, name) == 0 && a->children &&
            a->children->type == XML_TEXT_NODE)
            return (const char *)a->children->content;
    return NULL;
}

/* The first text child's content ("" when none): COLLADA's values are plain text. */
static const char *text(const xmlNode *n)
{
    for (xmlNode *c = n ? n->children : NULL; c; c = c->next)
        if (c->type == XML_TEXT_NODE || c->type == XML_CDATA_SECTION_NODE)
            return c->content ? (const char *)c->content : "";
    return "";
}

static int compare_ids(const void *a, const void *b)
{
    return strcmp(((const IdEntry *)a)->id, ((const IdEntry *)b)->id);
}

static bool collect_ids(Reader *r, xmlNode *n)
{
    /* Iterative walk: a hostile file may nest elements deeper than the stack allows. */
    while (n) {
        if (n->type == XML_ELEMENT_NODE) {
            const char *id = attr(n, "id");
            if (id) {
                if (r->num_ids == r->cap_ids) {
                    size_t cap = r->cap_ids ? 2 * r->cap_ids : 256;
                    IdEntry *grown = realloc(r->ids, cap * sizeof *grown);
                    if (!grown)
                        return fail(r, n, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
                    r->ids = grown, r->cap_ids = cap;
                }
                r->ids[r->num_ids++] = (IdEntry){id, n};
            }
            if (n->children) {
                n = n->children;
                continue;
            }
        }
        while (n && !n->next)
            n = n->parent && n->parent->type == XML_ELEMENT_NODE ? n->parent : NULL;
        if (n)
            n = n->next;
    }
    if (r->num_ids > 0) /* qsort and bsearch take no NULL array, even empty */
        qsort(r->ids, r->num_ids, sizeof *r->ids, compare_ids);
    return true;
}

/* The element a "#id" URL (or a bare id) names, NULL when none. */
static xmlNode *lookup(const Reader *r, const char *url)
{
    if (!url || r->num_ids == 0)
        return NULL;
    IdEntry key = {url[0] == '#' ? url + 1 : url, NULL};
    IdEntry *hit = bsearch(&key, r->ids, r->num_ids, sizeof *r->ids, compare_ids);
    return hit ? hit->node : NULL;
}

/* Reads up to n numbers of a node's text; returns how many it read (fewer: the text ended or a
 * word is not a number, which *bad reports). */
static size_t read_numbers(const char *s, double *out, size_t n, bool *bad)
{
    size_t i = 0;
    *bad = false;
    while (i < n) {
        while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
            s++;
        if (!*s)
            break;
        char *end;
        double v = strtod(s, &end);
        if (end == s || !isfinite(v)) {
            *bad = true;
            break;
        }
        out[i++] = v;
        s = end;
    }
    return i;
}

static bool read_exact(Reader *r, const xmlNode *n, double *out, size_t count)
{
    bool bad;
    if (read_numbers(text(n), out, count, &bad) == count)
        return true;
    char expected[16];
    snprintf(expected, sizeof expected, "%zu", count);
    return fail(r, n, ERR_OBJ_PARSE, bad ? "a value is not a finite number%s" : "expected %s numbers",
                bad ? "" : expected, NULL);
}

static void color_of(const xmlNode *n, float rgb[3], float *alpha)
{
    double v[4] = {0, 0, 0, 1};
    bool bad;
    size_t got = read_numbers(text(n), v, 4, &bad);
    if (got >= 3 && !bad) {
        for (int c = 0; c < 3; c++)
            rgb[c] = (float)v[c];
        if (alpha)
            *alpha = (float)v[3];
    }
}

/* ---------------------------------------------------------------- transforms */

static void mat_identity(double m[16])
{
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1.0;
}

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0)
        v[0] /= l, v[1] /= l, v[2] /= l;
}

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* One transform element as a matrix; false when it is not one (or is dropped). */
static bool transform_element(Reader *r, const xmlNode *e, double m[16], bool *ok)
{
    double v[16];
    *ok = true;
    mat_identity(m);
    if (is(e, "matrix")) {
        if (!(*ok = read_exact(r, e, v, 16)))
            return false;
        memcpy(m, v, sizeof v);
    } else if (is(e, "translate")) {
        if (!(*ok = read_exact(r, e, v, 3)))
            return false;
        m[3] = v[0], m[7] = v[1], m[11] = v[2];
    } else if (is(e, "scale")) {
        if (!(*ok = read_exact(r, e, v, 3)))
            return false;
        m[0] = v[0], m[5] = v[1], m[10] = v[2];
    } else if (is(e, "rotate")) {
        if (!(*ok = read_exact(r, e, v, 4)))
            return false;
        double a[3] = {v[0], v[1], v[2]};
        normalize3(a);
        double t = v[3] * PI / 180.0, c = cos(t), s = sin(t), k = 1 - c;
        double x = a[0], y = a[1], z = a[2];
        double rot[16] = {k * x * x + c,     k * x * y - s * z, k * x * z + s * y, 0,
                          k * x * y + s * z, k * y * y + c,     k * y * z - s * x, 0,
                          k * x * z - s * y, k * y * z + s * x, k * z * z + c,     0,
                          0,                 0,                 0,                 1};
        memcpy(m, rot, sizeof rot);
    } else if (is(e, "lookat")) {
        /* eye, interest, up: the frame of a camera at eye looking at interest (local -z). */
        if (!(*ok = read_exact(r, e, v, 9)))
            return false;
        double f[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]}, up[3] = {v[6], v[7], v[8]};
        normalize3(f);
        double x[3], y[3];
        cross3(f, up, x);
        normalize3(x);
        cross3(x, f, y);
        double look[16] = {x[0], y[0], -f[0], v[0], x[1], y[1], -f[1], v[1],
                           x[2], y[2], -f[2], v[2], 0,    0,    0,     1};
        memcpy(m, look, sizeof look);
    } else if (is(e, "skew")) {
        warn_once(r, DROP_SKEW, "<skew> transforms dropped%s", "");
        return false;
    } else {
        return false;
    }
    return true;
}

/* ---------------------------------------------------------------- geometry */

/* Where a <source>'s values went in the mesh: sources shared by several primitives are copied
 * once. */
typedef struct {
    const xmlNode *source;
    size_t base, count;
} SourceSlot;

typedef struct {
    SourceSlot slots[3][16]; /* position, normal, texcoord */
    int num_slots[3];
} SourceTable;

enum { ATTR_POSITION, ATTR_NORMAL, ATTR_TEXCOORD };

static bool grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return true;
    size_t cap2 = *cap ? *cap : 64;
    while (cap2 < need) {
        if (cap2 > SIZE_MAX / 4 / elem)
            return false;
        cap2 *= 2;
    }
    void *grown = realloc(*p, cap2 * elem);
    if (!grown)
        return false;
    *p = grown, *cap = cap2;
    return true;
}

typedef struct {
    Mesh *m;
    size_t cap_pos, cap_nrm, cap_uv, cap_tri;
} MeshBuilder;

/* The source's values appended to the mesh's array for attr (3 or 2 floats each); *base and
 * *count say where. */
static bool load_source(Reader *r, MeshBuilder *b, SourceTable *t, int attr_kind,
                        const xmlNode *source, size_t *base, size_t *count)
{
    for (int i = 0; i < t->num_slots[attr_kind]; i++)
        if (t->slots[attr_kind][i].source == source) {
            *base = t->slots[attr_kind][i].base, *count = t->slots[attr_kind][i].count;
            return true;
        }
    if (t->num_slots[attr_kind] == 16)
        return fail(r, source, ERR_TOO_LARGE, "more than 16 sources of one kind in a mesh", NULL, NULL);
    xmlNode *array = child(source, "float_array");
    xmlNode *accessor = path_child(source, "technique_common/accessor");
    if (!array || !accessor)
        return fail(r, source, ERR_OBJ_PARSE, "a source without <float_array> and <accessor>", NULL, NULL);
    long n = attr(accessor, "count") ? strtol(attr(accessor, "count"), NULL, 10) : -1;
    long stride = attr(accessor, "stride") ? strtol(attr(accessor, "stride"), NULL, 10) : 1;
    long offset = attr(accessor, "offset") ? strtol(attr(accessor, "offset"), NULL, 10) : 0;
    long declared = attr(array, "count") ? strtol(attr(array, "count"), NULL, 10) : -1;
    int width = attr_kind == ATTR_TEXCOORD ? 2 : 3;
    if (n < 0 || declared < 0 || stride < 1 || offset < 0 || n > (1L << 28) || stride > 64 ||
        declared > (1L << 30) || (long)width > stride || offset + (n ? (n - 1) * stride + width : 0) > declared)
        return fail(r, accessor, ERR_OBJ_PARSE, "count, stride or offset out of range of its array%s",
                    "", NULL);
    /* Each number takes at least two characters ("0 "): a count its text cannot hold is refused
     * before memory is taken for it. */
    if ((size_t)declared > strlen(text(array)) / 2 + 1)
        return fail(r, array, ERR_OBJ_PARSE, "count %s is more numbers than its text holds",
                    attr(array, "count"), NULL);
    double *values = malloc((size_t)(declared ? declared : 1) * sizeof *values);
    if (!values)
        return fail(r, array, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    bool bad;
    size_t got = read_numbers(text(array), values, (size_t)declared, &bad);
    if (got != (size_t)declared) {
        free(values);
        return fail(r, array, ERR_OBJ_PARSE, bad ? "a value is not a finite number" :
                    "fewer values than its count says%s", "", NULL);
    }
    Mesh *m = b->m;
    float **dst = attr_kind == ATTR_POSITION ? &m->positions : attr_kind == ATTR_NORMAL ? &m->normals : &m->texcoords;
    size_t *num = attr_kind == ATTR_POSITION ? &m->num_positions : attr_kind == ATTR_NORMAL ? &m->num_normals : &m->num_texcoords;
    size_t *cap = attr_kind == ATTR_POSITION ? &b->cap_pos : attr_kind == ATTR_NORMAL ? &b->cap_nrm : &b->cap_uv;
    if (!grow((void **)dst, cap, (*num + (size_t)n) * (size_t)width, sizeof(float))) {
        free(values);
        return fail(r, array, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    }
    for (long i = 0; i < n; i++)
        for (int c = 0; c < width; c++)
            (*dst)[(*num + (size_t)i) * (size_t)width + (size_t)c] = (float)values[offset + i * stride + c];
    free(values);
    *base = *num, *count = (size_t)n;
    *num += (size_t)n;
    t->slots[attr_kind][t->num_slots[attr_kind]++] = (SourceSlot){source, *base, *count};
    return true;
}

typedef struct {
    long offset[3]; /* per attribute: its offset in <p>, -1 when absent */
    size_t base[3], count[3];
    long stride;    /* indices per corner */
} PrimitiveInputs;

/* The <input>s of a primitive: VERTEX (through <vertices>), NORMAL, TEXCOORD (the lowest set). */
static bool read_inputs(Reader *r, MeshBuilder *b, SourceTable *t, const xmlNode *prim,
                        PrimitiveInputs *in)
{
    for (int k = 0; k < 3; k++)
        in->offset[k] = -1;
    in->stride = 0;
    long best_set = 1L << 30;
    for (xmlNode *i = child(prim, "input"); i; i = next_named(i, "input")) {
        const char *semantic = attr(i, "semantic");
        const char *off = attr(i, "offset");
        long offset = off ? strtol(off, NULL, 10) : 0;
        if (offset < 0 || offset > 64)
            return fail(r, i, ERR_OBJ_PARSE, "offset \"%s\" out of range", off, NULL);
        if (offset + 1 > in->stride)
            in->stride = offset + 1;
        xmlNode *src = lookup(r, attr(i, "source"));
        if (!semantic)
            continue;
        if (strcmp(semantic, "VERTEX") == 0) {
            if (!is(src, "vertices"))
                return fail(r, i, ERR_OBJ_PARSE, "VERTEX source \"%s\" is not a <vertices>",
                            attr(i, "source"), NULL);
            for (xmlNode *v = child(src, "input"); v; v = next_named(v, "input")) {
                const char *vs = attr(v, "semantic");
                int k = !vs ? -1 : strcmp(vs, "POSITION") == 0 ? ATTR_POSITION :
                        strcmp(vs, "NORMAL") == 0 ? ATTR_NORMAL : strcmp(vs, "TEXCOORD") == 0 ? ATTR_TEXCOORD : -1;
                if (k < 0 || in->offset[k] >= 0)
                    continue;
                xmlNode *s = lookup(r, attr(v, "source"));
                if (!is(s, "source"))
                    return fail(r, v, ERR_OBJ_PARSE, "no <source> \"%s\"", attr(v, "source"), NULL);
                if (!load_source(r, b, t, k, s, &in->base[k], &in->count[k]))
                    return false;
                in->offset[k] = offset;
            }
        } else if (strcmp(semantic, "NORMAL") == 0 || strcmp(semantic, "TEXCOORD") == 0) {
            int k = semantic[0] == 'N' ? ATTR_NORMAL : ATTR_TEXCOORD;
            long set = attr(i, "set") ? strtol(attr(i, "set"), NULL, 10) : 0;
            if (k == ATTR_TEXCOORD && set >= best_set)
                continue;
            if (k == ATTR_NORMAL && in->offset[k] >= 0)
                continue;
            if (!is(src, "source"))
                return fail(r, i, ERR_OBJ_PARSE, "no <source> \"%s\"", attr(i, "source"), NULL);
            if (!load_source(r, b, t, k, src, &in->base[k], &in->count[k]))
                return false;
            in->offset[k] = offset;
            if (k == ATTR_TEXCOORD)
                best_set = set;
        }
    }
    if (in->offset[ATTR_POSITION] < 0)
        return fail(r, prim, ERR_OBJ_PARSE, "no VERTEX input with POSITION%s", "", NULL);
    return true;
}

/* Appends one polygon of n corners (indices into <p> at corner stride) as triangles. */
static bool add_polygon(Reader *r, MeshBuilder *b, const xmlNode *prim, const PrimitiveInputs *in,
                        const long *p, size_t n, int32_t material)
{
    Mesh *m = b->m;
    int32_t corner[POLYGON_CORNER_LIMIT][3];
    if (n > POLYGON_CORNER_LIMIT)
        return fail(r, prim, ERR_TOO_LARGE, "a polygon of more than 4096 corners%s", "", NULL);
    for (size_t c = 0; c < n; c++)
        for (int k = 0; k < 3; k++) {
            corner[c][k] = -1;
            if (in->offset[k] < 0)
                continue;
            long idx = p[c * (size_t)in->stride + (size_t)in->offset[k]];
            if (idx < 0 || (size_t)idx >= in->count[k]) {
                char number[32];
                snprintf(number, sizeof number, "%ld", idx);
                return fail(r, prim, ERR_OBJ_INDEX, "index %s out of range of its %s source", number,
                            k == ATTR_POSITION ? "VERTEX" : k == ATTR_NORMAL ? "NORMAL" : "TEXCOORD");
            }
            corner[c][k] = (int32_t)(in->base[k] + (size_t)idx);
        }
    m->num_faces++;
    uint32_t local[3 * (POLYGON_CORNER_LIMIT - 2)];
    size_t tris;
    if (n == 3) {
        local[0] = 0, local[1] = 1, local[2] = 2;
        tris = 1;
    } else if (n < 3) {
        return true;
    } else {
        float pts[3 * POLYGON_CORNER_LIMIT];
        for (size_t c = 0; c < n; c++)
            memcpy(&pts[3 * c], &m->positions[3 * (size_t)corner[c][ATTR_POSITION]], 3 * sizeof(float));
        tris = triangulate_polygon(pts, n, local);
    }
    if (!grow((void **)&m->corners, &b->cap_tri, (m->num_triangles + tris) * 9, sizeof(int32_t)))
        return fail(r, prim, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    size_t cap_ids = b->cap_tri / 9;
    int32_t *ids = realloc(m->material_ids, (cap_ids ? cap_ids : 1) * sizeof *ids);
    if (!ids)
        return fail(r, prim, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    m->material_ids = ids;
    for (size_t t = 0; t < tris; t++) {
        int32_t *k = m->corners + 9 * m->num_triangles;
        for (int v = 0; v < 3; v++) {
            const int32_t *c = corner[local[3 * t + (size_t)v]];
            k[3 * v] = c[ATTR_POSITION], k[3 * v + 1] = c[ATTR_TEXCOORD], k[3 * v + 2] = c[ATTR_NORMAL];
        }
        m->material_ids[m->num_triangles++] = material;
    }
    return true;
}

/* The integers of a <p> or <vcount>; *n how many. */
static long *read_indices(Reader *r, const xmlNode *n, size_t *count)
{
    const char *s = text(n);
    size_t cap = 0, len = 0;
    long *out = NULL;
    for (;;) {
        while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
            s++;
        if (!*s)
            break;
        char *end;
        long v = strtol(s, &end, 10);
        if (end == s || (*end && *end != ' ' && *end != '\t' && *end != '\n' && *end != '\r')) {
            free(out);
            fail(r, n, ERR_OBJ_PARSE, "\"%.20s\" is not an integer", s, NULL);
            return NULL;
        }
        if (!grow((void **)&out, &cap, len + 1, sizeof *out)) {
            free(out);
            fail(r, n, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
            return NULL;
        }
        out[len++] = v;
        s = end;
    }
    *count = len;
    if (!out)
        out = malloc(sizeof *out);
    if (!out)
        fail(r, n, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    return out;
}

static int32_t symbol_index(Reader *r, ColladaGeometry *g, const xmlNode *prim)
{
    const char *sym = attr(prim, "material");
    if (!sym)
        return -1;
    for (int i = 0; i < g->num_symbols; i++)
        if (strcmp(g->symbols[i], sym) == 0)
            return i;
    void *grown = realloc(g->symbols, (size_t)(g->num_symbols + 1) * sizeof *g->symbols);
    if (!grown) {
        fail(r, prim, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
        return -2;
    }
    g->symbols = grown;
    snprintf(g->symbols[g->num_symbols], COLLADA_ID_LIMIT, "%s", sym);
    return g->num_symbols++;
}

static bool read_primitive(Reader *r, MeshBuilder *b, SourceTable *t, ColladaGeometry *g,
                           const xmlNode *prim)
{
    PrimitiveInputs in;
    if (!read_inputs(r, b, t, prim, &in))
        return false;
    int32_t material = symbol_index(r, g, prim);
    if (material == -2)
        return false;
    bool ok = true;
    if (is(prim, "polygons")) {
        if (child(prim, "ph"))
            warn_once(r, DROP_HOLES, "<polygons> with holes (<ph>): the holes are dropped%s", "");
        for (xmlNode *pe = child(prim, "p"); ok && pe; pe = next_named(pe, "p")) {
            size_t n;
            long *p = read_indices(r, pe, &n);
            if (!p)
                return false;
            if (n % (size_t)in.stride)
                ok = fail(r, pe, ERR_OBJ_PARSE, "index count not a multiple of the inputs%s", "", NULL);
            else
                ok = add_polygon(r, b, pe, &in, p, n / (size_t)in.stride, material);
            free(p);
        }
        return ok;
    }
    xmlNode *pe = child(prim, "p");
    if (!pe)
        return true; /* an empty primitive */
    size_t n;
    long *p = read_indices(r, pe, &n);
    if (!p)
        return false;
    size_t corners = n / (size_t)in.stride;
    if (n % (size_t)in.stride) {
        ok = fail(r, pe, ERR_OBJ_PARSE, "index count not a multiple of the inputs%s", "", NULL);
    } else if (is(prim, "triangles")) {
        if (corners % 3)
            ok = fail(r, pe, ERR_OBJ_PARSE, "corner count not a multiple of 3%s", "", NULL);
        for (size_t c = 0; ok && c + 3 <= corners; c += 3)
            ok = add_polygon(r, b, pe, &in, p + c * (size_t)in.stride, 3, material);
    } else { /* polylist */
        size_t nv;
        xmlNode *vc = child(prim, "vcount");
        long *vcount = vc ? read_indices(r, vc, &nv) : NULL;
        if (!vcount) {
            free(p);
            return vc ? false : fail(r, prim, ERR_OBJ_PARSE, "a <polylist> without <vcount>%s", "", NULL);
        }
        size_t at = 0;
        for (size_t f = 0; ok && f < nv; f++) {
            if (vcount[f] < 0 || (size_t)vcount[f] > corners - at)
                ok = fail(r, vc, ERR_OBJ_PARSE, "vcount runs past the end of <p>%s", "", NULL);
            else
                ok = add_polygon(r, b, pe, &in, p + at * (size_t)in.stride, (size_t)vcount[f], material);
            at += ok ? (size_t)vcount[f] : 0;
        }
        free(vcount);
    }
    free(p);
    return ok;
}

/* The first <technique> with profile CGL (CS184) or CMU462 (CMU 15-462, the same scenes) below
 * n, depth-first. */
static xmlNode *cgl_technique(Reader *r, const xmlNode *n, int depth)
{
    for (xmlNode *c = n ? n->children : NULL; c && depth < 8; c = c->next) {
        if (is(c, "technique")) {
            const char *profile = attr(c, "profile");
            if (profile && (strcmp(profile, "CGL") == 0 || strcmp(profile, "CMU462") == 0)) {
                r->doc->has_cgl = true;
                return c;
            }
        }
        if (c->type == XML_ELEMENT_NODE && !is(c, "mesh")) {
            xmlNode *hit = cgl_technique(r, c, depth + 1);
            if (hit)
                return hit;
        }
    }
    return NULL;
}

static bool read_geometry(Reader *r, const xmlNode *geo, ColladaGeometry *g)
{
    snprintf(g->id, sizeof g->id, "%s", attr(geo, "id") ? attr(geo, "id") : "");
    xmlNode *mesh = child(geo, "mesh");
    if (!mesh) {
        xmlNode *sphere = path_child(cgl_technique(r, geo, 0), "sphere");
        if (sphere) {
            xmlNode *radius = child(sphere, "radius");
            double v = 1.0;
            if (radius && !read_exact(r, radius, &v, 1))
                return false;
            if (!(v > 0))
                return fail(r, radius, ERR_OBJ_PARSE, "sphere radius must be positive%s", "", NULL);
            g->is_sphere = true, g->radius = (float)v;
            return true;
        }
        warn_once(r, DROP_GEOMETRY, "geometry \"%s\" (no <mesh>: splines, convex meshes...) dropped",
                  g->id);
        return true;
    }
    MeshBuilder b = {.m = &g->mesh};
    SourceTable t = {0};
    for (xmlNode *prim = mesh->children; prim; prim = prim->next) {
        if (is(prim, "triangles") || is(prim, "polylist") || is(prim, "polygons")) {
            if (!read_primitive(r, &b, &t, g, prim))
                return false;
        } else if (is(prim, "lines") || is(prim, "linestrips")) {
            warn_once(r, DROP_LINES, "<lines>/<linestrips> dropped (pt renders surfaces)%s", "");
        } else if (is(prim, "trifans") || is(prim, "tristrips")) {
            warn_once(r, DROP_PRIMITIVE, "<trifans>/<tristrips> dropped%s", "");
        }
    }
    return true;
}

/* ---------------------------------------------------------------- materials */

static void default_material(ObjMaterial *m, const char *name)
{
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    m->kd[0] = m->kd[1] = m->kd[2] = 0.8f;
    m->tf[0] = m->tf[1] = m->tf[2] = 1.0f;
    m->ni = 1.0f, m->d = 1.0f, m->illum = -1, m->bump_scale = 1.0f;
}

/* A <texture texture="..."> of an effect: its image's file, through COLLADA 1.4's
 * sampler2D -> surface -> image chain or straight to an image. */
static bool texture_file(Reader *r, const xmlNode *effect, const xmlNode *tex, char *out, size_t size)
{
    const char *name = attr(tex, "texture");
    const xmlNode *image = NULL;
    for (int hops = 0; name && hops < 4 && !image; hops++) {
        const xmlNode *param = NULL;
        for (xmlNode *profile = effect->children; profile && !param; profile = profile->next)
            for (xmlNode *np = child(profile, "newparam"); np && !param; np = next_named(np, "newparam"))
                if (attr(np, "sid") && strcmp(attr(np, "sid"), name) == 0)
                    param = np;
        if (!param) {
            xmlNode *hit = lookup(r, name);
            image = is(hit, "image") ? hit : NULL;
            break;
        }
        xmlNode *sampler = child(param, "sampler2D"), *surface = child(param, "surface");
        name = sampler ? text(child(sampler, "source")) : surface ? text(child(surface, "init_from")) : NULL;
        if (sampler && child(sampler, "instance_image")) { /* COLLADA 1.5 */
            xmlNode *hit = lookup(r, attr(child(sampler, "instance_image"), "url"));
            image = is(hit, "image") ? hit : NULL;
        }
    }
    const xmlNode *init = child(image, "init_from");
    const char *file = child(init, "ref") ? text(child(init, "ref")) : init ? text(init) : NULL;
    if (!file || !*file) {
        warn_once(r, DROP_TEXTURE, "a texture whose image cannot be found (\"%s\") dropped",
                  attr(tex, "texture") ? attr(tex, "texture") : "");
        return true;
    }
    if (strncmp(file, "file://", 7) == 0)
        file += 7;
    char decoded[1024];
    size_t k = 0;
    for (const char *s = file; *s && k + 1 < sizeof decoded; s++) {
        unsigned hex;
        if (s[0] == '%' && sscanf(s + 1, "%2x", &hex) == 1 && s[1] && s[2])
            decoded[k++] = (char)hex, s += 2;
        else
            decoded[k++] = *s;
    }
    decoded[k] = '\0';
    return fs_resolve_inside(r->path, decoded, "<image><init_from>", out, size, r->err);
}

static void read_cgl(Reader *r, const xmlNode *tech, ColladaMaterial *m)
{
    xmlNode *bsdf = NULL;
    for (xmlNode *c = tech ? tech->children : NULL; c && !bsdf; c = c->next)
        if (c->type == XML_ELEMENT_NODE)
            bsdf = c;
    if (!bsdf)
        return;
    float alpha_unused;
    for (int c = 0; c < 3; c++)
        m->reflectance[c] = m->transmittance[c] = 1.0f;
    m->ior = 1.5f;
    if (is(bsdf, "emission")) {
        m->cgl = CGL_EMISSION;
        color_of(child(bsdf, "radiance"), m->radiance, &alpha_unused);
    } else if (is(bsdf, "mirror")) {
        m->cgl = CGL_MIRROR;
        color_of(child(bsdf, "reflectance"), m->reflectance, &alpha_unused);
    } else if (is(bsdf, "diffuse")) {
        m->cgl = CGL_DIFFUSE;
        color_of(child(bsdf, "reflectance"), m->reflectance, &alpha_unused);
    } else if (is(bsdf, "microfacet")) {
        m->cgl = CGL_MICROFACET;
        double a = 0.5;
        bool bad;
        if (child(bsdf, "alpha") && read_numbers(text(child(bsdf, "alpha")), &a, 1, &bad) == 1 && a >= 0)
            m->alpha = (float)a;
        else
            m->alpha = 0.5f;
        color_of(child(bsdf, "eta"), m->eta, &alpha_unused);
        color_of(child(bsdf, "k"), m->k, &alpha_unused);
    } else if (is(bsdf, "glass") || is(bsdf, "refraction")) {
        if (is(bsdf, "refraction"))
            warn_once(r, DROP_REFRACTION, "CGL <refraction> (transmission only) read as glass%s", "");
        m->cgl = CGL_GLASS;
        double v;
        bool bad;
        if (read_numbers(text(child(bsdf, "ior")), &v, 1, &bad) == 1 && v > 0)
            m->ior = (float)v;
        if (read_numbers(text(child(bsdf, "roughness")), &v, 1, &bad) == 1 && v >= 0)
            m->roughness = (float)v;
        color_of(child(bsdf, "reflectance"), m->reflectance, &alpha_unused);
        color_of(child(bsdf, "transmittance"), m->transmittance, &alpha_unused);
    } else {
        warn_once(r, DROP_CGL, "CGL technique <%s> not known: the common profile is used",
                  (const char *)bsdf->name);
    }
}

static bool read_material(Reader *r, const xmlNode *mat, ColladaMaterial *m)
{
    const char *id = attr(mat, "id") ? attr(mat, "id") : "";
    snprintf(m->id, sizeof m->id, "%s", id);
    default_material(&m->common, id);
    xmlNode *effect = lookup(r, attr(child(mat, "instance_effect"), "url"));
    if (!is(effect, "effect"))
        return true; /* COLLADA's default: a grey surface */
    xmlNode *tech = path_child(effect, "profile_COMMON/technique");
    xmlNode *model = NULL;
    for (xmlNode *c = tech ? tech->children : NULL; c && !model; c = c->next)
        if (is(c, "constant") || is(c, "lambert") || is(c, "phong") || is(c, "blinn"))
            model = c;
    ObjMaterial *o = &m->common;
    if (model) {
        bool specular = is(model, "phong") || is(model, "blinn");
        o->illum = specular ? 2 : 1;
        float a;
        xmlNode *e;
        if ((e = child(model, "diffuse"))) {
            if (child(e, "color"))
                color_of(child(e, "color"), o->kd, &a);
            else if (child(e, "texture")) {
                if (!texture_file(r, effect, child(e, "texture"), o->map_kd, sizeof o->map_kd))
                    return false;
                o->kd[0] = o->kd[1] = o->kd[2] = 1.0f;
            }
        }
        if (is(model, "constant")) /* unlit: its emission is the colour seen */
            o->kd[0] = o->kd[1] = o->kd[2] = 0.0f;
        if ((e = child(child(model, "emission"), "color")))
            color_of(e, o->ke, &a);
        if (specular && (e = child(child(model, "specular"), "color")))
            color_of(e, o->ks, &a);
        double v;
        bool bad;
        if (specular && read_numbers(text(path_child(model, "shininess/float")), &v, 1, &bad) == 1)
            o->ns = (float)v, o->has_ns = true;
        if (read_numbers(text(path_child(model, "index_of_refraction/float")), &v, 1, &bad) == 1 && v > 0)
            o->ni = (float)v;
        /* Opacity (COLLADA 1.4.1 spec 7-16): A_ONE (default) uses the transparent colour's
         * alpha times transparency; RGB_ZERO one minus their luminance. */
        xmlNode *transparent = child(model, "transparent");
        double t = 1.0;
        read_numbers(text(path_child(model, "transparency/float")), &t, 1, &bad);
        if (transparent && child(transparent, "color")) {
            float rgb[3] = {0, 0, 0}, alpha = 1.0f;
            color_of(child(transparent, "color"), rgb, &alpha);
            const char *mode = attr(transparent, "opaque");
            double opacity = mode && strcmp(mode, "RGB_ZERO") == 0
                                 ? 1.0 - t * (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2])
                                 : alpha * t;
            o->d = (float)fmin(1.0, fmax(0.0, opacity));
        }
    }
    read_cgl(r, cgl_technique(r, effect, 0), m);
    return true;
}

/* ---------------------------------------------------------------- cameras, lights */

static void read_camera(Reader *r, const xmlNode *cam, ColladaCamera *c)
{
    snprintf(c->id, sizeof c->id, "%s", attr(cam, "id") ? attr(cam, "id") : "");
    xmlNode *tech = path_child(cam, "optics/technique_common");
    xmlNode *persp = child(tech, "perspective");
    double v;
    bool bad;
    if (!persp) {
        c->orthographic = child(tech, "orthographic") != NULL;
        warn_once(r, DROP_ORTHO, "orthographic camera \"%s\" read as a perspective one", c->id);
        return;
    }
    if (read_numbers(text(child(persp, "xfov")), &v, 1, &bad) == 1 && v > 0 && v < 180)
        c->xfov = (float)v;
    if (read_numbers(text(child(persp, "yfov")), &v, 1, &bad) == 1 && v > 0 && v < 180)
        c->yfov = (float)v;
    if (read_numbers(text(child(persp, "aspect_ratio")), &v, 1, &bad) == 1 && v > 0 && v < 1e4)
        c->aspect = (float)v;
}

static void read_light(Reader *r, const xmlNode *light, ColladaLight *l)
{
    snprintf(l->id, sizeof l->id, "%s", attr(light, "id") ? attr(light, "id") : "");
    l->falloff_angle = 180.0f;
    xmlNode *area = path_child(cgl_technique(r, light, 0), "area");
    float a;
    if (area) { /* CS184 reads the CGL technique before technique_common */
        l->type = COLLADA_LIGHT_AREA;
        color_of(child(area, "color"), l->color, &a);
        return;
    }
    xmlNode *tech = path_child(light, "technique_common"), *kind = NULL;
    for (xmlNode *c = tech ? tech->children : NULL; c && !kind; c = c->next)
        if (c->type == XML_ELEMENT_NODE)
            kind = c;
    l->type = is(kind, "spot") ? COLLADA_LIGHT_SPOT : is(kind, "directional") ? COLLADA_LIGHT_DIRECTIONAL :
              is(kind, "ambient") ? COLLADA_LIGHT_AMBIENT : COLLADA_LIGHT_POINT;
    color_of(child(kind, "color"), l->color, &a);
    double v;
    bool bad;
    if (read_numbers(text(child(kind, "falloff_angle")), &v, 1, &bad) == 1 && v > 0 && v <= 360)
        l->falloff_angle = (float)v;
    double lin = 0, quad = 0;
    read_numbers(text(child(kind, "linear_attenuation")), &lin, 1, &bad);
    read_numbers(text(child(kind, "quadratic_attenuation")), &quad, 1, &bad);
    l->attenuated = lin != 0 || quad != 0;
}

/* ---------------------------------------------------------------- the visual scene */

/* The index in `list` (of `count` items of `size` bytes, id first) of the element a URL names,
 * reading it into the list the first time. */
static int find_id(const char *ids, size_t size, int count, const char *id)
{
    for (int i = 0; i < count; i++)
        if (strcmp(ids + (size_t)i * size, id) == 0)
            return i;
    return -1;
}

static bool add_instance(Reader *r, const xmlNode *at, ColladaInstance *inst)
{
    ColladaDoc *d = r->doc;
    ColladaInstance *grown = realloc(d->instances, (size_t)(d->num_instances + 1) * sizeof *grown);
    if (!grown) {
        free(inst->bindings);
        return fail(r, at, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    }
    d->instances = grown;
    d->instances[d->num_instances++] = *inst;
    return true;
}

static bool instance_geometry(Reader *r, const xmlNode *e, const double world[16], const char *node)
{
    ColladaDoc *d = r->doc;
    const char *url = attr(e, "url");
    int g = url ? find_id(d->geometries[0].id, sizeof d->geometries[0], d->num_geometries,
                          url[0] == '#' ? url + 1 : url) : -1;
    if (d->num_geometries == 0 || g < 0)
        return fail(r, e, ERR_OBJ_PARSE, "no geometry \"%s\"", url ? url : "(no url)", NULL);
    ColladaGeometry *geo = &d->geometries[g];
    ColladaInstance inst = {.kind = COLLADA_GEOMETRY, .index = g};
    memcpy(inst.world, world, sizeof inst.world);
    snprintf(inst.node, sizeof inst.node, "%s", node);
    int n = geo->num_symbols > 0 ? geo->num_symbols : 1;
    inst.bindings = malloc((size_t)n * sizeof *inst.bindings);
    if (!inst.bindings)
        return fail(r, e, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    for (int i = 0; i < n; i++)
        inst.bindings[i] = -1;
    xmlNode *tc = path_child(e, "bind_material/technique_common");
    for (xmlNode *im = child(tc, "instance_material"); im; im = next_named(im, "instance_material")) {
        const char *sym = attr(im, "symbol"), *target = attr(im, "target");
        if (!sym || !target)
            continue;
        int mat = d->num_materials ? find_id(d->materials[0].id, sizeof d->materials[0],
                                             d->num_materials, target[0] == '#' ? target + 1 : target) : -1;
        if (mat < 0) {
            free(inst.bindings);
            return fail(r, im, ERR_OBJ_PARSE, "no material \"%s\"", target, NULL);
        }
        if (geo->num_symbols == 0 || geo->is_sphere) /* spheres and symbol-less meshes take it */
            inst.bindings[0] = mat;
        for (int s = 0; s < geo->num_symbols; s++)
            if (strcmp(geo->symbols[s], sym) == 0)
                inst.bindings[s] = mat;
    }
    return add_instance(r, e, &inst);
}

static bool instance_of(Reader *r, const xmlNode *e, ColladaInstanceKind kind, const double world[16],
                        const char *node)
{
    ColladaDoc *d = r->doc;
    const char *url = attr(e, "url");
    const char *id = url ? (url[0] == '#' ? url + 1 : url) : "";
    int i = kind == COLLADA_CAMERA
                ? (d->num_cameras ? find_id(d->cameras[0].id, sizeof d->cameras[0], d->num_cameras, id) : -1)
                : (d->num_lights ? find_id(d->lights[0].id, sizeof d->lights[0], d->num_lights, id) : -1);
    if (i < 0)
        return fail(r, e, ERR_OBJ_PARSE, "no %s \"%s\"", kind == COLLADA_CAMERA ? "camera" : "light", id);
    ColladaInstance inst = {.kind = kind, .index = i};
    memcpy(inst.world, world, sizeof inst.world);
    snprintf(inst.node, sizeof inst.node, "%s", node);
    return add_instance(r, e, &inst);
}

static bool visit_node(Reader *r, const xmlNode *node, const double parent[16], int depth)
{
    if (depth > NODE_DEPTH_LIMIT)
        return fail(r, node, ERR_TOO_LARGE, "nodes nested deeper than 64 (or an instance_node cycle)%s",
                    "", NULL);
    double world[16], m[16];
    memcpy(world, parent, sizeof world);
    const char *name = attr(node, "id") ? attr(node, "id") : attr(node, "name") ? attr(node, "name") : "";
    for (xmlNode *e = node->children; e; e = e->next) {
        bool ok;
        if (transform_element(r, e, m, &ok))
            rows16_mul(world, m, world);
        else if (!ok)
            return false;
    }
    for (xmlNode *e = node->children; e; e = e->next) {
        bool ok = true;
        if (is(e, "instance_geometry"))
            ok = instance_geometry(r, e, world, name);
        else if (is(e, "instance_camera"))
            ok = instance_of(r, e, COLLADA_CAMERA, world, name);
        else if (is(e, "instance_light"))
            ok = instance_of(r, e, COLLADA_LIGHT, world, name);
        else if (is(e, "instance_controller"))
            warn_once(r, DROP_CONTROLLER, "skinned/morphed geometry (<instance_controller>) dropped, "
                      "first in node \"%s\"", name);
        else if (is(e, "node"))
            ok = visit_node(r, e, world, depth + 1);
        else if (is(e, "instance_node")) {
            xmlNode *target = lookup(r, attr(e, "url"));
            if (!is(target, "node"))
                return fail(r, e, ERR_OBJ_PARSE, "no node \"%s\"", attr(e, "url"), NULL);
            ok = visit_node(r, target, world, depth + 1);
        }
        if (!ok)
            return false;
    }
    return true;
}

/* ---------------------------------------------------------------- the document */

/* Reads every element called `name` under `library` into a growing array. */
#define READ_LIBRARY(r, root, library, name, array, count, reader)                                 \
    do {                                                                                           \
        for (xmlNode *lib = child(root, library); lib; lib = next_named(lib, library))            \
            for (xmlNode *e = child(lib, name); e; e = next_named(e, name)) {                     \
                void *grown_ = realloc(array, (size_t)(count + 1) * sizeof *array);                \
                if (!grown_)                                                                       \
                    return fail(r, e, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);              \
                array = grown_;                                                                    \
                memset(&array[count], 0, sizeof *array);                                           \
                count++;                                                                           \
                reader;                                                                            \
            }                                                                                      \
    } while (0)

static bool read_document(Reader *r, xmlNode *root)
{
    ColladaDoc *d = r->doc;
    if (!is(root, "COLLADA"))
        return fail(r, root, ERR_OBJ_PARSE, "the root element is not <COLLADA>%s", "", NULL);
    if (!collect_ids(r, root))
        return false;
    const char *up = text(path_child(root, "asset/up_axis"));
    while (*up == ' ' || *up == '\n' || *up == '\t')
        up++;
    d->up_axis = strncmp(up, "Z_UP", 4) == 0 ? COLLADA_Z_UP : strncmp(up, "X_UP", 4) == 0 ? COLLADA_X_UP : COLLADA_Y_UP;
    const char *meter = attr(path_child(root, "asset/unit"), "meter");
    d->meter = meter && strtod(meter, NULL) > 0 ? strtod(meter, NULL) : 1.0;
    READ_LIBRARY(r, root, "library_materials", "material", d->materials, d->num_materials,
                 if (!read_material(r, e, &d->materials[d->num_materials - 1])) return false);
    READ_LIBRARY(r, root, "library_geometries", "geometry", d->geometries, d->num_geometries,
                 if (!read_geometry(r, e, &d->geometries[d->num_geometries - 1])) return false);
    READ_LIBRARY(r, root, "library_cameras", "camera", d->cameras, d->num_cameras,
                 read_camera(r, e, &d->cameras[d->num_cameras - 1]));
    READ_LIBRARY(r, root, "library_lights", "light", d->lights, d->num_lights,
                 read_light(r, e, &d->lights[d->num_lights - 1]));
    xmlNode *scene = lookup(r, attr(path_child(root, "scene/instance_visual_scene"), "url"));
    if (!scene) /* no <scene>: the first visual scene, as Blender and Assimp do */
        scene = path_child(root, "library_visual_scenes/visual_scene");
    if (!is(scene, "visual_scene"))
        return fail(r, root, ERR_OBJ_PARSE, "no <visual_scene> to render%s", "", NULL);
    double identity[16];
    mat_identity(identity);
    for (xmlNode *n = child(scene, "node"); n; n = next_named(n, "node"))
        if (!visit_node(r, n, identity, 0))
            return false;
    return true;
}

bool collada_read_memory(const char *path, const char *text_in, size_t size, ColladaDoc *doc,
                         Error *err)
{
    memset(doc, 0, sizeof *doc);
    doc->meter = 1.0;
    if (size > INT32_MAX) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: larger than 2 GiB", path);
        return false;
    }
    /* No network, no entity substitution, no DTD loading; HUGE: a million-triangle mesh's
     * <p> is one text node of tens of megabytes. */
    xmlDoc *x = xmlReadMemory(text_in, (int)size, path, NULL,
                              XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING |
                                  XML_PARSE_HUGE | XML_PARSE_COMPACT);
    if (!x) {
        const xmlError *e = xmlGetLastError();
        char message[256] = "not well-formed XML";
        if (e && e->message) {
            snprintf(message, sizeof message, "%s", e->message);
            message[strcspn(message, "\n")] = '\0';
        }
        error_set(err, ERR_OBJ_PARSE, path, e ? e->line : 0, "%s:%d: malformed XML: %s", path,
                  e ? e->line : 0, message);
        return false;
    }
    Reader r = {.path = path, .err = err, .doc = doc};
    bool ok = read_document(&r, xmlDocGetRootElement(x));
    free(r.ids);
    xmlFreeDoc(x);
    if (!ok)
        collada_free(doc);
    return ok;
}

bool collada_read(const char *path, ColladaDoc *doc, Error *err)
{
    char *data;
    size_t size;
    memset(doc, 0, sizeof *doc);
    if (!input_file_read(path, "a COLLADA file", COLLADA_FILE_LIMIT, &data, &size, err))
        return false;
    bool ok = collada_read_memory(path, data, size, doc, err);
    free(data);
    return ok;
}

void collada_free(ColladaDoc *doc)
{
    for (int i = 0; i < doc->num_geometries; i++) {
        mesh_free(&doc->geometries[i].mesh);
        free(doc->geometries[i].symbols);
    }
    for (int i = 0; i < doc->num_instances; i++)
        free(doc->instances[i].bindings);
    free(doc->materials);
    free(doc->geometries);
    free(doc->cameras);
    free(doc->lights);
    free(doc->instances);
    memset(doc, 0, sizeof *doc);
}
