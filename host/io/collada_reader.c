// SPDX-License-Identifier: MIT
/* collada_reader.c: COLLADA over libxml2's tree API (io/collada_reader.h). The document is parsed
 * without network access and without entity substitution (no external or billion-laughs
 * expansions); every id the file refers to is looked up in one sorted table. */
#include "io/collada_reader.h"
#include "io/collada_internal.h"

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
    if (collada_is(e, "matrix")) {
        if (!(*ok = collada_read_exact(r, e, v, 16)))
            return false;
        memcpy(m, v, sizeof v);
    } else if (collada_is(e, "translate")) {
        if (!(*ok = collada_read_exact(r, e, v, 3)))
            return false;
        m[3] = v[0], m[7] = v[1], m[11] = v[2];
    } else if (collada_is(e, "scale")) {
        if (!(*ok = collada_read_exact(r, e, v, 3)))
            return false;
        m[0] = v[0], m[5] = v[1], m[10] = v[2];
    } else if (collada_is(e, "rotate")) {
        if (!(*ok = collada_read_exact(r, e, v, 4)))
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
    } else if (collada_is(e, "lookat")) {
        /* eye, interest, up: the frame of a camera at eye looking at interest (local -z). */
        if (!(*ok = collada_read_exact(r, e, v, 9)))
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
    } else if (collada_is(e, "skew")) {
        collada_warn_once(r, DROP_SKEW, "<skew> transforms dropped%s", "");
        return false;
    } else {
        return false;
    }
    return true;
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
        return collada_fail(r, at, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    }
    d->instances = grown;
    d->instances[d->num_instances++] = *inst;
    return true;
}

static bool instance_geometry(Reader *r, const xmlNode *e, const double world[16], const char *node)
{
    ColladaDoc *d = r->doc;
    const char *url = collada_attr(e, "url");
    int g = url ? find_id(d->geometries[0].id, sizeof d->geometries[0], d->num_geometries,
                          url[0] == '#' ? url + 1 : url) : -1;
    if (d->num_geometries == 0 || g < 0)
        return collada_fail(r, e, ERR_OBJ_PARSE, "no geometry \"%s\"", url ? url : "(no url)", NULL);
    ColladaGeometry *geo = &d->geometries[g];
    ColladaInstance inst = {.kind = COLLADA_GEOMETRY, .index = g};
    memcpy(inst.world, world, sizeof inst.world);
    snprintf(inst.node, sizeof inst.node, "%s", node);
    int n = geo->num_symbols > 0 ? geo->num_symbols : 1;
    inst.bindings = malloc((size_t)n * sizeof *inst.bindings);
    if (!inst.bindings)
        return collada_fail(r, e, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
    for (int i = 0; i < n; i++)
        inst.bindings[i] = -1;
    xmlNode *tc = collada_path_child(e, "bind_material/technique_common");
    for (xmlNode *im = collada_child(tc, "instance_material"); im; im = collada_next_named(im, "instance_material")) {
        const char *sym = collada_attr(im, "symbol"), *target = collada_attr(im, "target");
        if (!sym || !target)
            continue;
        int mat = d->num_materials ? find_id(d->materials[0].id, sizeof d->materials[0],
                                             d->num_materials, target[0] == '#' ? target + 1 : target) : -1;
        if (mat < 0) {
            free(inst.bindings);
            return collada_fail(r, im, ERR_OBJ_PARSE, "no material \"%s\"", target, NULL);
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
    const char *url = collada_attr(e, "url");
    const char *id = url ? (url[0] == '#' ? url + 1 : url) : "";
    int i = kind == COLLADA_CAMERA
                ? (d->num_cameras ? find_id(d->cameras[0].id, sizeof d->cameras[0], d->num_cameras, id) : -1)
                : (d->num_lights ? find_id(d->lights[0].id, sizeof d->lights[0], d->num_lights, id) : -1);
    if (i < 0)
        return collada_fail(r, e, ERR_OBJ_PARSE, "no %s \"%s\"", kind == COLLADA_CAMERA ? "camera" : "light", id);
    ColladaInstance inst = {.kind = kind, .index = i};
    memcpy(inst.world, world, sizeof inst.world);
    snprintf(inst.node, sizeof inst.node, "%s", node);
    return add_instance(r, e, &inst);
}

static bool visit_node(Reader *r, const xmlNode *node, const double parent[16], int depth)
{
    if (depth > NODE_DEPTH_LIMIT)
        return collada_fail(r, node, ERR_TOO_LARGE, "nodes nested deeper than 64 (or an instance_node cycle)%s",
                    "", NULL);
    double world[16], m[16];
    memcpy(world, parent, sizeof world);
    const char *name = collada_attr(node, "id") ? collada_attr(node, "id") : collada_attr(node, "name") ? collada_attr(node, "name") : "";
    for (xmlNode *e = node->children; e; e = e->next) {
        bool ok;
        if (transform_element(r, e, m, &ok))
            rows16_mul(world, m, world);
        else if (!ok)
            return false;
    }
    for (xmlNode *e = node->children; e; e = e->next) {
        bool ok = true;
        if (collada_is(e, "instance_geometry"))
            ok = instance_geometry(r, e, world, name);
        else if (collada_is(e, "instance_camera"))
            ok = instance_of(r, e, COLLADA_CAMERA, world, name);
        else if (collada_is(e, "instance_light"))
            ok = instance_of(r, e, COLLADA_LIGHT, world, name);
        else if (collada_is(e, "instance_controller"))
            collada_warn_once(r, DROP_CONTROLLER, "skinned/morphed geometry (<instance_controller>) dropped, "
                      "first in node \"%s\"", name);
        else if (collada_is(e, "node"))
            ok = visit_node(r, e, world, depth + 1);
        else if (collada_is(e, "instance_node")) {
            xmlNode *target = collada_lookup(r, collada_attr(e, "url"));
            if (!collada_is(target, "node"))
                return collada_fail(r, e, ERR_OBJ_PARSE, "no node \"%s\"", collada_attr(e, "url"), NULL);
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
        for (xmlNode *lib = collada_child(root, library); lib; lib = collada_next_named(lib, library))            \
            for (xmlNode *e = collada_child(lib, name); e; e = collada_next_named(e, name)) {                     \
                void *grown_ = realloc(array, (size_t)(count + 1) * sizeof *array);                \
                if (!grown_)                                                                       \
                    return collada_fail(r, e, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);              \
                array = grown_;                                                                    \
                memset(&array[count], 0, sizeof *array);                                           \
                count++;                                                                           \
                reader;                                                                            \
            }                                                                                      \
    } while (0)

static bool read_document(Reader *r, xmlNode *root)
{
    ColladaDoc *d = r->doc;
    if (!collada_is(root, "COLLADA"))
        return collada_fail(r, root, ERR_OBJ_PARSE, "the root element is not <COLLADA>%s", "", NULL);
    if (!collada_collect_ids(r, root))
        return false;
    const char *up = collada_text(collada_path_child(root, "asset/up_axis"));
    while (*up == ' ' || *up == '\n' || *up == '\t')
        up++;
    d->up_axis = strncmp(up, "Z_UP", 4) == 0 ? COLLADA_Z_UP : strncmp(up, "X_UP", 4) == 0 ? COLLADA_X_UP : COLLADA_Y_UP;
    const char *meter = collada_attr(collada_path_child(root, "asset/unit"), "meter");
    d->meter = meter && strtod(meter, NULL) > 0 ? strtod(meter, NULL) : 1.0;
    READ_LIBRARY(r, root, "library_materials", "material", d->materials, d->num_materials,
                 if (!collada_read_material(r, e, &d->materials[d->num_materials - 1])) return false);
    READ_LIBRARY(r, root, "library_geometries", "geometry", d->geometries, d->num_geometries,
                 if (!collada_read_geometry(r, e, &d->geometries[d->num_geometries - 1])) return false);
    READ_LIBRARY(r, root, "library_cameras", "camera", d->cameras, d->num_cameras,
                 collada_read_camera(r, e, &d->cameras[d->num_cameras - 1]));
    READ_LIBRARY(r, root, "library_lights", "light", d->lights, d->num_lights,
                 collada_read_light(r, e, &d->lights[d->num_lights - 1]));
    xmlNode *scene = collada_lookup(r, collada_attr(collada_path_child(root, "scene/instance_visual_scene"), "url"));
    if (!scene) /* no <scene>: the first visual scene, as Blender and Assimp do */
        scene = collada_path_child(root, "library_visual_scenes/visual_scene");
    if (!collada_is(scene, "visual_scene"))
        return collada_fail(r, root, ERR_OBJ_PARSE, "no <visual_scene> to render%s", "", NULL);
    double identity[16];
    mat_identity(identity);
    for (xmlNode *n = collada_child(scene, "node"); n; n = collada_next_named(n, "node"))
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
