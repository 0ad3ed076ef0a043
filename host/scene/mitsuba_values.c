// SPDX-License-Identifier: MIT
/* mitsuba_values.c: the properties of Mitsuba elements (<float>, <rgb>, <spectrum>, <point>,
 * ...), refs, names, file names and messages, for the importer's other parts
 * (scene/mitsuba_internal.h); <transform> is read in mitsuba_transform.c. */
#include "scene/mitsuba_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"

/* "<bsdf type="diffuse" id="wall">" for messages. */
static void describe(const XmlElement *e, char *out, size_t size)
{
    int n = snprintf(out, size, "<%.32s", e->name);
    static const char *const shown[] = {"type", "name", "id"};
    for (int i = 0; i < 3; i++) {
        const char *v = xml_attribute(e, shown[i]);
        if (v && n >= 0 && (size_t)n < size)
            n += snprintf(out + n, size - (size_t)n, " %s=\"%.48s\"", shown[i], v);
    }
    if (n >= 0 && (size_t)n < size)
        snprintf(out + n, size - (size_t)n, ">");
}

bool mi_fail(Mitsuba *m, const XmlElement *e, const char *fmt, ...)
{
    char what[200], message[600];
    describe(e, what, sizeof what);
    va_list args;
    va_start(args, fmt);
    vsnprintf(message, sizeof message, fmt, args);
    va_end(args);
    error_set(m->err, ERR_JSON_VALUE, m->file, e->line, "%s:%d: %s: %s", m->file, e->line, what, message);
    return false;
}

void mi_warn_once(Mitsuba *m, const XmlElement *e, const char *key, const char *fmt, ...)
{
    for (int i = 0; i < m->num_warned; i++)
        if (strncmp(m->warned[i], key, sizeof m->warned[i] - 1) == 0)
            return;
    char (*grown)[64] = realloc(m->warned, (size_t)(m->num_warned + 1) * sizeof *grown);
    if (grown) {
        m->warned = grown;
        snprintf(m->warned[m->num_warned++], sizeof *grown, "%s", key);
    }
    char what[200], message[600];
    describe(e, what, sizeof what);
    va_list args;
    va_start(args, fmt);
    vsnprintf(message, sizeof message, fmt, args);
    va_end(args);
    warn("%s:%d: %s: %s", m->file, e->line, what, message);
}

XmlElement *mi_prop(Mitsuba *m, const XmlElement *e, const char *name)
{
    (void)m;
    for (int i = 0; i < e->num_children; i++) {
        const char *n = xml_attribute(e->children[i], "name");
        if (n && strcmp(n, name) == 0) {
            e->children[i]->used = true;
            return e->children[i];
        }
    }
    return NULL;
}

bool mi_parse_number(Mitsuba *m, const XmlElement *e, const char *attribute, double *out)
{
    const char *text = xml_attribute(e, attribute);
    if (!text)
        return mi_fail(m, e, "missing %s=\"...\"", attribute);
    char *end;
    double v = strtod(text, &end);
    while (isspace((unsigned char)*end))
        end++;
    if (end == text || *end || !isfinite(v))
        return mi_fail(m, e, "%s=\"%.40s\" is not a number", attribute, text);
    *out = v;
    return true;
}

/* value="a, b, c" or "a b c": n numbers. */
bool mi_parse_list(Mitsuba *m, const XmlElement *e, const char *text, double *out, int n)
{
    const char *s = text;
    for (int i = 0; i < n; i++) {
        while (isspace((unsigned char)*s) || (i > 0 && *s == ','))
            s++;
        char *end;
        out[i] = strtod(s, &end);
        if (end == s || !isfinite(out[i]))
            return mi_fail(m, e, "\"%.60s\" is not %d numbers", text, n);
        s = end;
        while (isspace((unsigned char)*s))
            s++;
    }
    if (*s)
        return mi_fail(m, e, "\"%.60s\" is not %d numbers", text, n);
    return true;
}

bool mi_float(Mitsuba *m, const XmlElement *e, const char *name, double fallback, double *out)
{
    const XmlElement *p = mi_prop(m, e, name);
    *out = fallback;
    if (!p)
        return true;
    if (strcmp(p->name, "float") && strcmp(p->name, "integer"))
        return mi_fail(m, p, "expected <float name=\"%s\" value=...>", name);
    return mi_parse_number(m, p, "value", out);
}

bool mi_int(Mitsuba *m, const XmlElement *e, const char *name, int fallback, int *out)
{
    double v;
    if (!mi_float(m, e, name, fallback, &v))
        return false;
    if (v != floor(v) || v < -1e9 || v > 1e9)
        return mi_fail(m, e, "%s: %g is not an integer", name, v);
    *out = (int)v;
    return true;
}

bool mi_bool(Mitsuba *m, const XmlElement *e, const char *name, bool fallback, bool *out)
{
    const XmlElement *p = mi_prop(m, e, name);
    *out = fallback;
    if (!p)
        return true;
    const char *v = xml_attribute(p, "value");
    if (!v || (strcmp(v, "true") && strcmp(v, "false")))
        return mi_fail(m, p, "expected value=\"true\" or \"false\"");
    *out = strcmp(v, "true") == 0;
    return true;
}

const char *mi_string(Mitsuba *m, const XmlElement *e, const char *name, const char *fallback)
{
    const XmlElement *p = mi_prop(m, e, name);
    const char *v = p ? xml_attribute(p, "value") : NULL;
    return v ? v : fallback;
}

/* A sampled spectrum "400:0.1, 500:0.5, ..." as RGB: the mean over three bands (blue 400-500 nm,
 * green 500-600, red 600-700) of the piecewise-linear spectrum. An approximation (no CIE
 * matching), for the reflectances and radiances people write by hand. */
static bool sampled_spectrum_rgb(Mitsuba *m, const XmlElement *e, const char *text, double rgb[3])
{
    double wavelengths[64], values[64];
    int n = 0;
    const char *s = text;
    while (*s) {
        char *end;
        if (n == 64)
            return mi_fail(m, e, "more than 64 samples in a spectrum");
        wavelengths[n] = strtod(s, &end);
        if (end == s || *end != ':')
            return mi_fail(m, e, "\"%.60s\" is not a spectrum (wavelength:value, ...)", text);
        s = end + 1;
        values[n] = strtod(s, &end);
        if (end == s || !isfinite(values[n]) || !isfinite(wavelengths[n]) ||
            (n > 0 && !(wavelengths[n] > wavelengths[n - 1])))
            return mi_fail(m, e, "\"%.60s\" is not a spectrum (increasing wavelengths)", text);
        n++;
        s = end;
        while (isspace((unsigned char)*s) || *s == ',')
            s++;
    }
    if (n == 0)
        return mi_fail(m, e, "an empty spectrum");
    for (int band = 0; band < 3; band++) {
        double lo = 600.0 - 100.0 * band, sum = 0.0;
        for (int k = 0; k < 100; k++) { /* 1 nm steps, clamped at the ends */
            double w = lo + k + 0.5, v = values[0];
            for (int i = 1; i < n && w > wavelengths[i - 1]; i++)
                v = w >= wavelengths[i] ? values[i]
                                        : values[i - 1] + (values[i] - values[i - 1]) *
                                                              (w - wavelengths[i - 1]) /
                                                              (wavelengths[i] - wavelengths[i - 1]);
            sum += v;
        }
        rgb[band] = sum / 100.0;
    }
    return true;
}

/* value="v": the grey (v, v, v). */
static bool grey(Mitsuba *m, const XmlElement *e, double rgb[3])
{
    if (!mi_parse_number(m, e, "value", &rgb[0]))
        return false;
    rgb[1] = rgb[2] = rgb[0];
    return true;
}

bool mi_spectrum_rgb(Mitsuba *m, const XmlElement *e, double rgb[3])
{
    const char *value = xml_attribute(e, "value");
    if (strcmp(e->name, "rgb") == 0) {
        if (!value)
            return mi_fail(m, e, "missing value=\"r, g, b\"");
        if (strchr(value, ',') || strchr(value, ' '))
            return mi_parse_list(m, e, value, rgb, 3);
        return grey(m, e, rgb);
    }
    if (strcmp(e->name, "float") == 0 || strcmp(e->name, "integer") == 0) {
        return grey(m, e, rgb);
    }
    if (strcmp(e->name, "spectrum") != 0)
        return mi_fail(m, e, "expected <rgb>, <spectrum> or <float>");
    if (xml_attribute(e, "filename") || xml_attribute(e, "type")) {
        mi_warn_once(m, e, "spectrum-file", "spectra from files and spectrum plugins are not read: white");
        rgb[0] = rgb[1] = rgb[2] = 1.0;
        return true;
    }
    if (!value)
        return mi_fail(m, e, "missing value=\"...\"");
    if (strchr(value, ':'))
        return sampled_spectrum_rgb(m, e, value, rgb);
    return grey(m, e, rgb);
}

bool mi_point(Mitsuba *m, const XmlElement *e, const char *name, const double fallback[3], double out[3])
{
    const XmlElement *p = mi_prop(m, e, name);
    memcpy(out, fallback, 3 * sizeof *out);
    if (!p)
        return true;
    if (strcmp(p->name, "point") && strcmp(p->name, "vector"))
        return mi_fail(m, p, "expected <point> or <vector>");
    const char *value = xml_attribute(p, "value");
    if (value)
        return mi_parse_list(m, p, value, out, 3);
    static const char *const axes[] = {"x", "y", "z"};
    for (int i = 0; i < 3; i++)
        if (xml_attribute(p, axes[i]) && !mi_parse_number(m, p, axes[i], &out[i]))
            return false;
    return true;
}


void mi_warn_unused(Mitsuba *m, const XmlElement *e)
{
    for (int i = 0; i < e->num_children; i++) {
        const XmlElement *c = e->children[i];
        const char *name = xml_attribute(c, "name");
        /* Nested plugins (a film, an emitter, a bsdf) may carry a name too: only properties. */
        static const char *const properties[] = {"float", "integer", "boolean", "string", "rgb", "spectrum",
                                                  "point", "vector", "transform", "texture", NULL};
        int k = 0;
        while (properties[k] && strcmp(properties[k], c->name))
            k++;
        if (c->used || !name || !properties[k])
            continue;
        char key[64];
        snprintf(key, sizeof key, "%.20s.%.20s.%.20s", xml_attribute(e, "type") ? xml_attribute(e, "type") : e->name,
                 c->name, name);
        mi_warn_once(m, c, key, "ignored (pt has no equivalent)");
    }
}

const MitsubaNamed *mi_find_id(Mitsuba *m, const XmlElement *ref)
{
    const char *id = xml_attribute(ref, "id");
    if (!id) {
        mi_fail(m, ref, "missing id=\"...\"");
        return NULL;
    }
    for (int i = 0; i < m->num_ids; i++)
        if (strcmp(xml_attribute(m->ids[i].element, "id"), id) == 0)
            return &m->ids[i];
    mi_fail(m, ref, "no element with id \"%.60s\" (ids must be defined before they are used)", id);
    return NULL;
}

static bool name_taken(const Mitsuba *m, const char *name)
{
    return cJSON_GetObjectItemCaseSensitive(m->materials, name) ||
           cJSON_GetObjectItemCaseSensitive(m->textures, name);
}

void mi_new_name(Mitsuba *m, const XmlElement *e, const char *prefix, char out[SCENE_NAME_LIMIT])
{
    const char *id = e ? xml_attribute(e, "id") : NULL;
    if (id && strlen(id) < SCENE_NAME_LIMIT - 16 && !name_taken(m, id)) {
        snprintf(out, SCENE_NAME_LIMIT, "%s", id);
        return;
    }
    do
        snprintf(out, SCENE_NAME_LIMIT, "%s_%d", prefix, m->next_name++);
    while (name_taken(m, out));
}

bool mi_file(Mitsuba *m, const XmlElement *e, const char *file, char *out, size_t size)
{
    char resolved[1024];
    if (!file || !file[0])
        return mi_fail(m, e, "missing filename");
    Error inner = {0};
    if (!fs_resolve_inside(m->file, file, "filename", resolved, sizeof resolved, &inner))
        return mi_fail(m, e, "filename \"%.200s\" %s", file,
                       inner.code == ERR_PATH_ESCAPES ? "leaves the scene's folder (pt --allow-outside-paths reads it)"
                                                      : "is not usable");
    /* resolved is relative to the working folder; the tree's paths are relative to the imported
     * file's folder, which the included documents' folders are inside of. */
    const char *slash = strrchr(m->path, '/');
    size_t folder = slash ? (size_t)(slash - m->path) + 1 : 0;
    const char *relative = strncmp(resolved, m->path, folder) == 0 ? resolved + folder : resolved;
    if ((size_t)snprintf(out, size, "%s", relative) >= size)
        return mi_fail(m, e, "filename \"%.60s...\" is too long", file);
    return true;
}

cJSON *mi_rgb_json(const double rgb[3])
{
    double v[3] = {rgb[0], rgb[1], rgb[2]};
    return cJSON_CreateDoubleArray(v, 3);
}
