// SPDX-License-Identifier: MIT
/* collada_geometry.c: COLLADA <geometry> meshes (io/collada_internal.h): sources, inputs,
 * triangles, polylists and polygons triangulated into one mesh per geometry. */
#include "io/collada_internal.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/triangulate.h"

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
        return collada_fail(r, source, ERR_TOO_LARGE, "more than 16 sources of one kind in a mesh", NULL, NULL);
    xmlNode *array = collada_child(source, "float_array");
    xmlNode *accessor = collada_path_child(source, "technique_common/accessor");
    if (!array || !accessor)
        return collada_fail(r, source, ERR_OBJ_PARSE, "a source without <float_array> and <accessor>", NULL, NULL);
    long n = collada_attr(accessor, "count") ? strtol(collada_attr(accessor, "count"), NULL, 10) : -1;
    long stride = collada_attr(accessor, "stride") ? strtol(collada_attr(accessor, "stride"), NULL, 10) : 1;
    long offset = collada_attr(accessor, "offset") ? strtol(collada_attr(accessor, "offset"), NULL, 10) : 0;
    long declared = collada_attr(array, "count") ? strtol(collada_attr(array, "count"), NULL, 10) : -1;
    int width = attr_kind == ATTR_TEXCOORD ? 2 : 3;
    if (n < 0 || declared < 0 || stride < 1 || offset < 0 || n > (1L << 28) || stride > 64 ||
        declared > (1L << 30) || (long)width > stride || offset + (n ? (n - 1) * stride + width : 0) > declared)
        return collada_fail(r, accessor, ERR_OBJ_PARSE, "count, stride or offset out of range of its array%s",
                    "", NULL);
    /* Each number takes at least two characters ("0 "): a count its text cannot hold is refused
     * before memory is taken for it. */
    if ((size_t)declared > strlen(collada_text(array)) / 2 + 1)
        return collada_fail(r, array, ERR_OBJ_PARSE, "count %s is more numbers than its text holds",
                    collada_attr(array, "count"), NULL);
    double *values = malloc((size_t)(declared ? declared : 1) * sizeof *values);
    if (!values)
        return collada_fail(r, array, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    bool bad;
    size_t got = collada_read_numbers(collada_text(array), values, (size_t)declared, &bad);
    if (got != (size_t)declared) {
        free(values);
        return collada_fail(r, array, ERR_OBJ_PARSE, bad ? "a value is not a finite number" :
                    "fewer values than its count says%s", "", NULL);
    }
    Mesh *m = b->m;
    float **dst = attr_kind == ATTR_POSITION ? &m->positions : attr_kind == ATTR_NORMAL ? &m->normals : &m->texcoords;
    size_t *num = attr_kind == ATTR_POSITION ? &m->num_positions : attr_kind == ATTR_NORMAL ? &m->num_normals : &m->num_texcoords;
    size_t *cap = attr_kind == ATTR_POSITION ? &b->cap_pos : attr_kind == ATTR_NORMAL ? &b->cap_nrm : &b->cap_uv;
    if (!grow((void **)dst, cap, (*num + (size_t)n) * (size_t)width, sizeof(float))) {
        free(values);
        return collada_fail(r, array, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
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
    for (xmlNode *i = collada_child(prim, "input"); i; i = collada_next_named(i, "input")) {
        const char *semantic = collada_attr(i, "semantic");
        const char *off = collada_attr(i, "offset");
        long offset = off ? strtol(off, NULL, 10) : 0;
        if (offset < 0 || offset > 64)
            return collada_fail(r, i, ERR_OBJ_PARSE, "offset \"%s\" out of range", off, NULL);
        if (offset + 1 > in->stride)
            in->stride = offset + 1;
        xmlNode *src = collada_lookup(r, collada_attr(i, "source"));
        if (!semantic)
            continue;
        if (strcmp(semantic, "VERTEX") == 0) {
            if (!collada_is(src, "vertices"))
                return collada_fail(r, i, ERR_OBJ_PARSE, "VERTEX source \"%s\" is not a <vertices>",
                            collada_attr(i, "source"), NULL);
            for (xmlNode *v = collada_child(src, "input"); v; v = collada_next_named(v, "input")) {
                const char *vs = collada_attr(v, "semantic");
                int k = !vs ? -1 : strcmp(vs, "POSITION") == 0 ? ATTR_POSITION :
                        strcmp(vs, "NORMAL") == 0 ? ATTR_NORMAL : strcmp(vs, "TEXCOORD") == 0 ? ATTR_TEXCOORD : -1;
                if (k < 0 || in->offset[k] >= 0)
                    continue;
                xmlNode *s = collada_lookup(r, collada_attr(v, "source"));
                if (!collada_is(s, "source"))
                    return collada_fail(r, v, ERR_OBJ_PARSE, "no <source> \"%s\"", collada_attr(v, "source"), NULL);
                if (!load_source(r, b, t, k, s, &in->base[k], &in->count[k]))
                    return false;
                in->offset[k] = offset;
            }
        } else if (strcmp(semantic, "NORMAL") == 0 || strcmp(semantic, "TEXCOORD") == 0) {
            int k = semantic[0] == 'N' ? ATTR_NORMAL : ATTR_TEXCOORD;
            long set = collada_attr(i, "set") ? strtol(collada_attr(i, "set"), NULL, 10) : 0;
            if (k == ATTR_TEXCOORD && set >= best_set)
                continue;
            if (k == ATTR_NORMAL && in->offset[k] >= 0)
                continue;
            if (!collada_is(src, "source"))
                return collada_fail(r, i, ERR_OBJ_PARSE, "no <source> \"%s\"", collada_attr(i, "source"), NULL);
            if (!load_source(r, b, t, k, src, &in->base[k], &in->count[k]))
                return false;
            in->offset[k] = offset;
            if (k == ATTR_TEXCOORD)
                best_set = set;
        }
    }
    if (in->offset[ATTR_POSITION] < 0)
        return collada_fail(r, prim, ERR_OBJ_PARSE, "no VERTEX input with POSITION%s", "", NULL);
    return true;
}

/* Appends one polygon of n corners (indices into <p> at corner stride) as triangles. */
static bool add_polygon(Reader *r, MeshBuilder *b, const xmlNode *prim, const PrimitiveInputs *in,
                        const long *p, size_t n, int32_t material)
{
    Mesh *m = b->m;
    int32_t corner[POLYGON_CORNER_LIMIT][3];
    if (n > POLYGON_CORNER_LIMIT)
        return collada_fail(r, prim, ERR_TOO_LARGE, "a polygon of more than 4096 corners%s", "", NULL);
    for (size_t c = 0; c < n; c++)
        for (int k = 0; k < 3; k++) {
            corner[c][k] = -1;
            if (in->offset[k] < 0)
                continue;
            long idx = p[c * (size_t)in->stride + (size_t)in->offset[k]];
            if (idx < 0 || (size_t)idx >= in->count[k]) {
                char number[32];
                snprintf(number, sizeof number, "%ld", idx);
                return collada_fail(r, prim, ERR_OBJ_INDEX, "index %s out of range of its %s source", number,
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
        return collada_fail(r, prim, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    size_t cap_ids = b->cap_tri / 9;
    int32_t *ids = realloc(m->material_ids, (cap_ids ? cap_ids : 1) * sizeof *ids);
    if (!ids)
        return collada_fail(r, prim, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
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
    const char *s = collada_text(n);
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
            collada_fail(r, n, ERR_OBJ_PARSE, "\"%.20s\" is not an integer", s, NULL);
            return NULL;
        }
        if (!grow((void **)&out, &cap, len + 1, sizeof *out)) {
            free(out);
            collada_fail(r, n, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
            return NULL;
        }
        out[len++] = v;
        s = end;
    }
    *count = len;
    if (!out)
        out = malloc(sizeof *out);
    if (!out)
        collada_fail(r, n, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    return out;
}

static int32_t symbol_index(Reader *r, ColladaGeometry *g, const xmlNode *prim)
{
    const char *sym = collada_attr(prim, "material");
    if (!sym)
        return -1;
    for (int i = 0; i < g->num_symbols; i++)
        if (strcmp(g->symbols[i], sym) == 0)
            return i;
    void *grown = realloc(g->symbols, (size_t)(g->num_symbols + 1) * sizeof *g->symbols);
    if (!grown) {
        collada_fail(r, prim, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
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
    if (collada_is(prim, "polygons")) {
        if (collada_child(prim, "ph"))
            collada_warn_once(r, DROP_HOLES, "<polygons> with holes (<ph>): the holes are dropped%s", "");
        for (xmlNode *pe = collada_child(prim, "p"); ok && pe; pe = collada_next_named(pe, "p")) {
            size_t n;
            long *p = read_indices(r, pe, &n);
            if (!p)
                return false;
            if (n % (size_t)in.stride)
                ok = collada_fail(r, pe, ERR_OBJ_PARSE, "index count not a multiple of the inputs%s", "", NULL);
            else
                ok = add_polygon(r, b, pe, &in, p, n / (size_t)in.stride, material);
            free(p);
        }
        return ok;
    }
    xmlNode *pe = collada_child(prim, "p");
    if (!pe)
        return true; /* an empty primitive */
    size_t n;
    long *p = read_indices(r, pe, &n);
    if (!p)
        return false;
    size_t corners = n / (size_t)in.stride;
    if (n % (size_t)in.stride) {
        ok = collada_fail(r, pe, ERR_OBJ_PARSE, "index count not a multiple of the inputs%s", "", NULL);
    } else if (collada_is(prim, "triangles")) {
        if (corners % 3)
            ok = collada_fail(r, pe, ERR_OBJ_PARSE, "corner count not a multiple of 3%s", "", NULL);
        for (size_t c = 0; ok && c + 3 <= corners; c += 3)
            ok = add_polygon(r, b, pe, &in, p + c * (size_t)in.stride, 3, material);
    } else { /* polylist */
        size_t nv;
        xmlNode *vc = collada_child(prim, "vcount");
        long *vcount = vc ? read_indices(r, vc, &nv) : NULL;
        if (!vcount) {
            free(p);
            return vc ? false : collada_fail(r, prim, ERR_OBJ_PARSE, "a <polylist> without <vcount>%s", "", NULL);
        }
        size_t at = 0;
        for (size_t f = 0; ok && f < nv; f++) {
            if (vcount[f] < 0 || (size_t)vcount[f] > corners - at)
                ok = collada_fail(r, vc, ERR_OBJ_PARSE, "vcount runs past the end of <p>%s", "", NULL);
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
xmlNode *collada_cgl_technique(Reader *r, const xmlNode *n, int depth)
{
    for (xmlNode *c = n ? n->children : NULL; c && depth < 8; c = c->next) {
        if (collada_is(c, "technique")) {
            const char *profile = collada_attr(c, "profile");
            if (profile && (strcmp(profile, "CGL") == 0 || strcmp(profile, "CMU462") == 0)) {
                r->doc->has_cgl = true;
                return c;
            }
        }
        if (c->type == XML_ELEMENT_NODE && !collada_is(c, "mesh")) {
            xmlNode *hit = collada_cgl_technique(r, c, depth + 1);
            if (hit)
                return hit;
        }
    }
    return NULL;
}

bool collada_read_geometry(Reader *r, const xmlNode *geo, ColladaGeometry *g)
{
    snprintf(g->id, sizeof g->id, "%s", collada_attr(geo, "id") ? collada_attr(geo, "id") : "");
    xmlNode *mesh = collada_child(geo, "mesh");
    if (!mesh) {
        xmlNode *sphere = collada_path_child(collada_cgl_technique(r, geo, 0), "sphere");
        if (sphere) {
            xmlNode *radius = collada_child(sphere, "radius");
            double v = 1.0;
            if (radius && !collada_read_exact(r, radius, &v, 1))
                return false;
            if (!(v > 0))
                return collada_fail(r, radius, ERR_OBJ_PARSE, "sphere radius must be positive%s", "", NULL);
            g->is_sphere = true, g->radius = (float)v;
            return true;
        }
        collada_warn_once(r, DROP_GEOMETRY, "geometry \"%s\" (no <mesh>: splines, convex meshes...) dropped",
                  g->id);
        return true;
    }
    MeshBuilder b = {.m = &g->mesh};
    SourceTable t = {0};
    for (xmlNode *prim = mesh->children; prim; prim = prim->next) {
        if (collada_is(prim, "triangles") || collada_is(prim, "polylist") || collada_is(prim, "polygons")) {
            if (!read_primitive(r, &b, &t, g, prim))
                return false;
        } else if (collada_is(prim, "lines") || collada_is(prim, "linestrips")) {
            collada_warn_once(r, DROP_LINES, "<lines>/<linestrips> dropped (pt renders surfaces)%s", "");
        } else if (collada_is(prim, "trifans") || collada_is(prim, "tristrips")) {
            collada_warn_once(r, DROP_PRIMITIVE, "<trifans>/<tristrips> dropped%s", "");
        }
    }
    return true;
}
