// SPDX-License-Identifier: MIT
/* mitsuba_texture.c: Mitsuba textures (bitmap; checkerboard as its mean) as pt textures, and the
 * colour and scalar parameters of BSDFs and emitters that take a spectrum or a texture. */
#include "scene/mitsuba_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The texture's mean colour when a parameter cannot take a texture. */
static bool texture_parameter(Mitsuba *m, const XmlElement *p, bool linear, cJSON **out)
{
    char name[SCENE_NAME_LIMIT];
    double mean[3];
    bool is_texture;
    if (!mi_texture(m, p, linear, name, mean, &is_texture))
        return false;
    *out = is_texture ? cJSON_CreateString(name) : mi_rgb_json(mean);
    return true;
}

bool mi_colour(Mitsuba *m, const XmlElement *e, const char *name, double fallback, cJSON **out)
{
    const XmlElement *p = mi_prop(m, e, name);
    double rgb[3] = {fallback, fallback, fallback};
    *out = NULL;
    if (p && (strcmp(p->name, "texture") == 0 || strcmp(p->name, "ref") == 0))
        return texture_parameter(m, p, false, out);
    if (p && !mi_spectrum_rgb(m, p, rgb))
        return false;
    *out = mi_rgb_json(rgb);
    return true;
}

bool mi_scalar(Mitsuba *m, const XmlElement *e, const char *name, double fallback, cJSON **out)
{
    const XmlElement *p = mi_prop(m, e, name);
    double rgb[3] = {fallback, fallback, fallback};
    *out = NULL;
    if (p && (strcmp(p->name, "texture") == 0 || strcmp(p->name, "ref") == 0)) {
        if (!texture_parameter(m, p, true, out))
            return false;
        if (cJSON_IsArray(*out)) { /* a mean colour: its luminance-free average */
            double v = 0.0;
            for (int i = 0; i < 3; i++)
                v += cJSON_GetArrayItem(*out, i)->valuedouble / 3.0;
            cJSON_Delete(*out);
            *out = cJSON_CreateNumber(v);
        }
        return true;
    }
    if (p && !mi_spectrum_rgb(m, p, rgb))
        return false;
    *out = cJSON_CreateNumber(rgb[0]);
    return true;
}

/* ---- Textures -------------------------------------------------------------------------------- */

const MitsubaNamed *mi_find_mapped(const Mitsuba *m, const XmlElement *e)
{
    for (int i = 0; i < m->num_mapped; i++)
        if (m->mapped[i].element == e)
            return &m->mapped[i];
    return NULL;
}

bool mi_follow(Mitsuba *m, const XmlElement *e, const char *tag,
               bool (*map)(Mitsuba *, const XmlElement *, char[SCENE_NAME_LIMIT]),
               char out[SCENE_NAME_LIMIT], bool *done)
{
    *done = true;
    if (strcmp(e->name, "ref") == 0) {
        const MitsubaNamed *named = mi_find_id(m, e);
        if (!named)
            return *done = false;
        if (strcmp(named->element->name, tag))
            return *done = mi_fail(m, e, "names a <%s>, not a <%s>", named->element->name, tag);
        const char *saved = m->file;
        m->file = named->file;
        *done = map(m, named->element, out);
        m->file = saved;
        return *done;
    }
    const MitsubaNamed *mapped = mi_find_mapped(m, e);
    if (mapped)
        snprintf(out, SCENE_NAME_LIMIT, "%s", mapped->name);
    *done = mapped != NULL;
    return true;
}

bool mi_remember(Mitsuba *m, const XmlElement *e, const char *name)
{
    MitsubaNamed *grown = realloc(m->mapped, (size_t)(m->num_mapped + 1) * sizeof *grown);
    if (!grown)
        return mi_fail(m, e, "out of memory");
    m->mapped = grown;
    m->mapped[m->num_mapped] = (MitsubaNamed){.element = e, .file = m->file};
    snprintf(m->mapped[m->num_mapped++].name, SCENE_NAME_LIMIT, "%s", name);
    return true;
}

/* to_uv: scale and translation only (pt's texture transform also rotates, but Mitsuba's
 * arbitrary matrix may shear). Mitsuba reads rows from the image's top at v, pt from its bottom
 * at v' = 1 - v: scale (su, sv), offset (tu, -sv - tv). */
static bool uv_transform(Mitsuba *m, const XmlElement *e, cJSON *texture)
{
    if (!mi_prop(m, e, "to_uv"))
        return true;
    Affine a;
    if (!mi_transform(m, e, "to_uv", &a))
        return false;
    if (fabs(a.m[0][1]) > 1e-9 || fabs(a.m[1][0]) > 1e-9) {
        mi_warn_once(m, e, "to_uv", "to_uv with rotation or shear: ignored (pt keeps scale and offset)");
        return true;
    }
    double scale[2] = {a.m[0][0], a.m[1][1]}, offset[2] = {a.m[0][3], -a.m[1][1] - a.m[1][3]};
    cJSON *t = cJSON_AddObjectToObject(texture, "transform");
    cJSON_AddItemToObject(t, "scale", cJSON_CreateDoubleArray(scale, 2));
    cJSON_AddItemToObject(t, "offset", cJSON_CreateDoubleArray(offset, 2));
    return true;
}

static bool bitmap_texture(Mitsuba *m, const XmlElement *e, bool linear, cJSON *t)
{
    char file[1024];
    if (!mi_file(m, e, mi_string(m, e, "filename", NULL), file, sizeof file))
        return false;
    cJSON_AddStringToObject(t, "file", file);
    bool raw;
    if (!mi_bool(m, e, "raw", false, &raw))
        return false;
    if (raw || linear)
        cJSON_AddStringToObject(t, "encoding", "linear");
    const char *filter = mi_string(m, e, "filter_type", "bilinear");
    const char *wrap = mi_string(m, e, "wrap_mode", "repeat");
    if (strcmp(filter, "bilinear") && strcmp(filter, "nearest"))
        return mi_fail(m, e, "filter_type \"%.40s\" is not bilinear or nearest", filter);
    if (strcmp(wrap, "repeat") && strcmp(wrap, "mirror") && strcmp(wrap, "clamp"))
        return mi_fail(m, e, "wrap_mode \"%.40s\" is not repeat, mirror or clamp", wrap);
    cJSON_AddStringToObject(t, "filter", filter);
    cJSON_AddStringToObject(t, "wrap", wrap);
    mi_prop(m, e, "format"); /* Mitsuba's storage precision: nothing to map */
    return uv_transform(m, e, t);
}

bool mi_texture(Mitsuba *m, const XmlElement *e, bool linear, char out[SCENE_NAME_LIMIT], double mean[3],
                bool *is_texture)
{
    const char *saved_file = m->file;
    if (strcmp(e->name, "ref") == 0) {
        const MitsubaNamed *named = mi_find_id(m, e);
        if (!named)
            return false;
        if (strcmp(named->element->name, "texture"))
            return mi_fail(m, e, "names a <%s>, not a <texture>", named->element->name);
        m->file = named->file;
        bool ok = mi_texture(m, named->element, linear, out, mean, is_texture);
        m->file = saved_file;
        return ok;
    }
    const char *type = xml_attribute(e, "type");
    *is_texture = false;
    mean[0] = mean[1] = mean[2] = 0.5;
    if (!type)
        return mi_fail(m, e, "missing type=\"...\"");
    if (strcmp(type, "checkerboard") == 0) {
        /* pt has no procedural checkerboard: its mean colour (what the checks average to). */
        double c0[3] = {0.4, 0.4, 0.4}, c1[3] = {0.2, 0.2, 0.2};
        const XmlElement *p;
        if (((p = mi_prop(m, e, "color0")) && !mi_spectrum_rgb(m, p, c0)) ||
            ((p = mi_prop(m, e, "color1")) && !mi_spectrum_rgb(m, p, c1)))
            return false;
        mi_prop(m, e, "to_uv");
        for (int i = 0; i < 3; i++)
            mean[i] = 0.5 * (c0[i] + c1[i]);
        mi_warn_once(m, e, "checkerboard", "pt has no checkerboard texture: its mean colour");
        mi_warn_unused(m, e);
        return true;
    }
    if (strcmp(type, "bitmap") != 0) {
        char key[64];
        snprintf(key, sizeof key, "texture.%.40s", type);
        mi_warn_once(m, e, key, "texture type not read by pt: grey 0.5");
        return true;
    }
    const MitsubaNamed *done = mi_find_mapped(m, e);
    *is_texture = true;
    if (done) {
        snprintf(out, SCENE_NAME_LIMIT, "%s", done->name);
        if (linear) { /* a normal map that Mitsuba reads raw: pt must too */
            cJSON *t = cJSON_GetObjectItemCaseSensitive(m->textures, out);
            if (t && !cJSON_GetObjectItemCaseSensitive(t, "encoding"))
                cJSON_AddStringToObject(t, "encoding", "linear");
        }
        return true;
    }
    cJSON *t = cJSON_CreateObject();
    mi_new_name(m, e, "texture", out);
    cJSON_AddItemToObject(m->textures, out, t);
    if (!bitmap_texture(m, e, linear, t))
        return false;
    mi_warn_unused(m, e);
    return mi_remember(m, e, out);
}

