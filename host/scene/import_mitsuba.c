// SPDX-License-Identifier: MIT
/* import_mitsuba.c: a Mitsuba 3 XML scene as a pt scene (scene/import_mitsuba.h): the document
 * and its <include>s, <default> parameters and $name substitution, ids, then each top-level
 * element: shapes and emitters (mitsuba_shapes.c), the sensor with its film and sampler, the
 * integrator (mitsuba_sensor.c). BSDFs and textures are mapped when a shape uses them
 * (mitsuba_bsdf.c, mitsuba_texture.c). */
#include "scene/import_mitsuba.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"
#include "scene/mitsuba_internal.h"

#define MITSUBA_FILE_LIMIT ((size_t)64 << 20)
#define INCLUDE_DEPTH_LIMIT 16

/* ---- Parameters (-D NAME=VALUE, <default>) ----------------------------------------------------- */

static char **cli_defines; /* "NAME=VALUE" */
static int num_cli_defines;

/* The length of the parameter name at s: a letter or _, then letters, digits and _. */
static size_t name_length(const char *s)
{
    size_t n = 0;
    if (!isalpha((unsigned char)s[0]) && s[0] != '_')
        return 0;
    while (isalnum((unsigned char)s[n]) || s[n] == '_')
        n++;
    return n;
}

bool mitsuba_import_define(const char *name_value, Error *err)
{
    size_t n = name_length(name_value);
    if (n == 0 || name_value[n] != '=') {
        error_set(err, ERR_USAGE, NULL, 0, "-D: '%s' is not NAME=VALUE (NAME: a letter or _, then letters, digits, _)", name_value);
        return false;
    }
    char **grown = realloc(cli_defines, (size_t)(num_cli_defines + 1) * sizeof *grown);
    char *copy = strdup(name_value);
    if (!grown || !copy) {
        free(copy);
        if (grown)
            cli_defines = grown;
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "-D: out of memory");
        return false;
    }
    cli_defines = grown;
    cli_defines[num_cli_defines++] = copy;
    return true;
}

void mitsuba_import_clear_defines(void)
{
    for (int i = 0; i < num_cli_defines; i++)
        free(cli_defines[i]);
    free(cli_defines);
    cli_defines = NULL;
    num_cli_defines = 0;
}

static const char *define_value(const Mitsuba *m, const char *name, size_t length)
{
    for (int i = 0; i < m->num_defines; i++)
        if (strlen(m->define_names[i]) == length && strncmp(m->define_names[i], name, length) == 0)
            return m->define_values[i];
    return NULL;
}

/* Adds NAME = VALUE unless NAME has a value already (-D wins over <default>). */
static bool add_define(Mitsuba *m, const char *name, size_t length, const char *value)
{
    if (define_value(m, name, length))
        return true;
    char **names = realloc(m->define_names, (size_t)(m->num_defines + 1) * sizeof *names);
    if (names)
        m->define_names = names;
    char **values = realloc(m->define_values, (size_t)(m->num_defines + 1) * sizeof *values);
    if (values)
        m->define_values = values;
    char *n = strndup(name, length), *v = strdup(value);
    if (!names || !values || !n || !v) {
        free(n);
        free(v);
        return false;
    }
    m->define_names[m->num_defines] = n;
    m->define_values[m->num_defines++] = v;
    return true;
}

/* One attribute with every $name replaced by its value (\$ is a literal $). */
static bool substitute(Mitsuba *m, XmlElement *e, int attribute)
{
    const char *text = e->attributes[2 * attribute + 1];
    if (!strchr(text, '$'))
        return true;
    size_t size = 256, used = 0;
    char *out = malloc(size);
    for (const char *s = text; out && *s;) {
        const char *piece = s;
        size_t length = 1;
        if (s[0] == '\\' && s[1] == '$') {
            piece = s + 1;
            s += 2;
        } else if (s[0] == '$') {
            size_t n = name_length(s + 1);
            piece = n ? define_value(m, s + 1, n) : NULL;
            if (!piece) {
                free(out);
                return mi_fail(m, e, "undefined parameter $%.*s (give <default name=\"%.*s\" value=...> or "
                                     "pt -D %.*s=VALUE)", (int)n, s + 1, (int)n, s + 1, (int)n, s + 1);
            }
            length = strlen(piece);
            s += 1 + n;
        } else {
            s++;
        }
        if (used + length + 1 > size) {
            size = 2 * (used + length + 1);
            char *grown = size > ((size_t)1 << 24) ? NULL : realloc(out, size);
            if (!grown)
                free(out);
            out = grown;
        }
        if (out) {
            memcpy(out + used, piece, length);
            used += length;
        }
    }
    if (!out || (out[used] = '\0', !xml_set_attribute(e, attribute, out))) {
        free(out);
        return mi_fail(m, e, "out of memory (or a parameter expanding past 16 MB)");
    }
    free(out);
    return true;
}

/* Mitsuba 0.x/1.x property names are camelCase; Mitsuba upgrades them to snake_case. */
static bool upgrade_name(Mitsuba *m, XmlElement *e, int attribute)
{
    const char *name = e->attributes[2 * attribute + 1];
    char out[256];
    size_t n = 0;
    for (size_t i = 0; name[i] && n + 2 < sizeof out; i++) {
        if (i > 0 && islower((unsigned char)name[i - 1]) && isupper((unsigned char)name[i]))
            out[n++] = '_';
        out[n++] = (char)tolower((unsigned char)name[i]);
    }
    out[n] = '\0';
    return xml_set_attribute(e, attribute, out) || mi_fail(m, e, "out of memory");
}

static bool substitute_tree(Mitsuba *m, XmlElement *e)
{
    for (int i = 0; i < e->num_attributes; i++) {
        if (!substitute(m, e, i))
            return false;
        if (m->old_version && strcmp(e->attributes[2 * i], "name") == 0 && !upgrade_name(m, e, i))
            return false;
    }
    for (int i = 0; i < e->num_children; i++)
        if (!substitute_tree(m, e->children[i]))
            return false;
    return true;
}

/* ---- Ids ------------------------------------------------------------------------------------- */

static bool register_ids(Mitsuba *m, const XmlElement *e)
{
    const char *id = xml_attribute(e, "id");
    if (id && strcmp(e->name, "ref")) {
        for (int i = 0; i < m->num_ids; i++)
            if (strcmp(xml_attribute(m->ids[i].element, "id"), id) == 0)
                return mi_fail(m, e, "a second element with id \"%.60s\"", id);
        MitsubaNamed *grown = realloc(m->ids, (size_t)(m->num_ids + 1) * sizeof *grown);
        if (!grown)
            return mi_fail(m, e, "out of memory");
        m->ids = grown;
        m->ids[m->num_ids++] = (MitsubaNamed){.element = e, .file = m->file};
    }
    for (int i = 0; i < e->num_children; i++)
        if (!register_ids(m, e->children[i]))
            return false;
    return true;
}

/* ---- Documents --------------------------------------------------------------------------------- */

static bool read_document(Mitsuba *m, const char *path);

static bool include(Mitsuba *m, const XmlElement *e)
{
    const char *file = xml_attribute(e, "filename");
    char resolved[1024];
    if (!file)
        return mi_fail(m, e, "missing filename=\"...\"");
    if (m->include_depth >= INCLUDE_DEPTH_LIMIT)
        return mi_fail(m, e, "includes nested more than %d deep (a cycle?)", INCLUDE_DEPTH_LIMIT);
    Error inner = {0};
    if (!fs_resolve_inside(m->file, file, "<include filename>", resolved, sizeof resolved, &inner))
        return mi_fail(m, e, "filename \"%.200s\" leaves the scene's folder", file);
    const char *saved = m->file;
    m->include_depth++;
    bool ok = read_document(m, resolved);
    m->include_depth--;
    m->file = saved;
    return ok;
}

static bool top_level(Mitsuba *m, XmlElement *e, cJSON *render)
{
    static const Affine identity = {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
    const char *type = xml_attribute(e, "type");
    if (strcmp(e->name, "default") == 0 || strcmp(e->name, "bsdf") == 0 || strcmp(e->name, "texture") == 0 ||
        (strcmp(e->name, "medium") == 0 && xml_attribute(e, "id")))
        return true; /* read already, or mapped when a shape (or the sensor) names them */
    if (strcmp(e->name, "medium") == 0) {
        mi_warn_once(m, e, "medium-no-id", "a top-level medium without an id: nothing can name "
                                           "it, skipped");
        return true;
    }
    if (strcmp(e->name, "include") == 0)
        return include(m, e);
    if (strcmp(e->name, "shape") == 0)
        return (type && strcmp(type, "shapegroup") == 0) || mi_shape(m, e, &identity);
    if (strcmp(e->name, "emitter") == 0)
        return mi_emitter(m, e);
    if (strcmp(e->name, "sensor") == 0)
        return mi_sensor(m, e, m->out->root, render);
    if (strcmp(e->name, "integrator") == 0)
        return mi_integrator(m, e, render);
    char key[64];
    snprintf(key, sizeof key, "%.30s.%.30s", e->name, type ? type : "");
    mi_warn_once(m, e, key, "not read by pt: skipped");
    return true;
}

static bool read_document(Mitsuba *m, const char *path)
{
    XmlElement *root;
    char *copy = strdup(path);
    XmlElement **documents = realloc(m->documents, (size_t)(m->num_documents + 1) * sizeof *documents);
    if (documents)
        m->documents = documents;
    const char **paths = realloc(m->document_paths, (size_t)(m->num_documents + 1) * sizeof *paths);
    if (paths)
        m->document_paths = paths;
    if (!copy || !documents || !paths) {
        free(copy);
        error_set(m->err, ERR_OUT_OF_MEMORY, path, 0, "%s: out of memory", path);
        return false;
    }
    if (!xml_tree_read(path, MITSUBA_FILE_LIMIT, &root, m->err)) {
        free(copy);
        return false;
    }
    m->documents[m->num_documents] = root;
    m->document_paths[m->num_documents++] = copy;
    m->file = copy;
    if (strcmp(root->name, "scene"))
        return mi_fail(m, root, "the root element must be <scene version=...>");
    const char *version = xml_attribute(root, "version");
    if (!version)
        return mi_fail(m, root, "missing version=\"...\" (Mitsuba 3 needs it)");
    if (m->include_depth == 0)
        m->old_version = atoi(version) < 2;
    for (int i = 0; i < root->num_children; i++) {
        const XmlElement *c = root->children[i];
        if (strcmp(c->name, "default"))
            continue;
        const char *name = xml_attribute(c, "name"), *value = xml_attribute(c, "value");
        if (!name || !value || name_length(name) != strlen(name) || !name[0])
            return mi_fail(m, c, "needs name=\"NAME\" (letters, digits, _) and value=\"...\"");
        if (!add_define(m, name, strlen(name), value))
            return mi_fail(m, c, "out of memory");
    }
    if (!substitute_tree(m, root) || !register_ids(m, root))
        return false;
    cJSON *render = cJSON_GetObjectItemCaseSensitive(m->out->root, "render");
    for (int i = 0; i < root->num_children; i++) {
        m->file = copy;
        if (!top_level(m, root->children[i], render))
            return false;
    }
    return true;
}

static void free_state(Mitsuba *m)
{
    for (int i = 0; i < m->num_documents; i++) {
        xml_tree_free(m->documents[i]);
        free((void *)m->document_paths[i]);
    }
    free(m->documents);
    free(m->document_paths);
    for (int i = 0; i < m->num_defines; i++) {
        free(m->define_names[i]);
        free(m->define_values[i]);
    }
    free(m->define_names);
    free(m->define_values);
    free(m->ids);
    free(m->mapped);
    free(m->warned);
}

/* Empty blocks the scene reader would refuse ("textures": {} is fine, "lights": [] too). */
static bool finish(Mitsuba *m, cJSON *root, cJSON *render)
{
    if (cJSON_GetArraySize(m->objects) == 0) {
        error_set(m->err, ERR_NO_TRIANGLES, m->path, 0, "%s: no shape pt can read (obj, ply, rectangle, "
                  "disk, cube, sphere, instance): nothing to render", m->path);
        return false;
    }
    if (!m->has_sensor)
        warn("%s: no <sensor>: pt frames the scene's bounds", m->path);
    if (cJSON_GetArraySize(render) == 0)
        cJSON_DeleteItemFromObjectCaseSensitive(root, "render");
    return true;
}

bool mitsuba_import(const char *path, ImportedScene *out, Error *err)
{
    Mitsuba m = {.path = path, .file = path, .err = err, .out = out};
    cJSON *root = out->root = cJSON_CreateObject();
    cJSON *render = root ? cJSON_AddObjectToObject(root, "render") : NULL;
    m.materials = root ? cJSON_AddObjectToObject(root, "materials") : NULL;
    m.textures = root ? cJSON_AddObjectToObject(root, "textures") : NULL;
    m.objects = root ? cJSON_AddArrayToObject(root, "objects") : NULL;
    m.lights = root ? cJSON_AddArrayToObject(root, "lights") : NULL;
    if (!render || !m.materials || !m.textures || !m.objects || !m.lights) {
        error_set(err, ERR_OUT_OF_MEMORY, path, 0, "%s: out of memory", path);
        return false;
    }
    bool ok = true;
    for (int i = 0; ok && i < num_cli_defines; i++) {
        const char *eq = strchr(cli_defines[i], '=');
        ok = add_define(&m, cli_defines[i], (size_t)(eq - cli_defines[i]), eq + 1);
    }
    if (!ok)
        error_set(err, ERR_OUT_OF_MEMORY, path, 0, "%s: out of memory", path);
    ok = ok && read_document(&m, path) && finish(&m, root, render);
    free_state(&m);
    return ok;
}
