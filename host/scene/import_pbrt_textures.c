// SPDX-License-Identifier: MIT
/* import_pbrt_textures.c: pbrt-v4 named textures as pt can use them (PbrtTexture): imagemap -> a
 * file texture in the JSON (uscale / vscale / udelta / vdelta as its transform, pbrt's encoding
 * defaults); constant -> its value; scale of a texture by a grey constant -> a copy of the texture
 * with that "scale"; mix / checkerboard of constants -> their mean (of textures: the first, warned);
 * any other type -> a warned constant 0.5. pbrt keeps float and spectrum textures apart, so a name
 * is looked up in the kind the parameter wants first. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/import_pbrt_internal.h"

/* A file texture in the JSON; its name into out. */
PbrtTexture *pbrt_find_texture(PbrtImport *imp, const char *name, bool want_float)
{
    PbrtTexture *other = NULL;
    for (int i = 0; i < imp->num_pbrt_textures; i++)
        if (strcmp(imp->pbrt_textures[i].name, name) == 0) {
            if (imp->pbrt_textures[i].is_float == want_float)
                return &imp->pbrt_textures[i];
            other = &imp->pbrt_textures[i];
        }
    return other;
}

bool pbrt_add_file_texture(PbrtImport *imp, const char *file, const char *encoding, int line, char out[SCENE_NAME_LIMIT])
{
    if (!pbrt_check_path(imp, file, "\"filename\"", line))
        return false;
    snprintf(out, SCENE_NAME_LIMIT, "texture%d", imp->num_pt_textures++);
    cJSON *t = cJSON_AddObjectToObject(imp->textures, out);
    cJSON_AddStringToObject(t, "file", file);
    if (encoding)
        cJSON_AddStringToObject(t, "encoding", encoding);
    return true;
}

static bool texture_operand(PbrtImport *imp, PbrtParams *p, const char *name, float fallback,
                            bool is_float, PbrtTexture *out)
{
    memset(out, 0, sizeof *out);
    out->value[0] = out->value[1] = out->value[2] = fallback;
    PbrtParam *q = pbrt_param(p, name);
    if (!q)
        return true;
    if (q->type == PBRT_TEXTURE) {
        PbrtTexture *t = q->count == 1 ? pbrt_find_texture(imp, q->strings[0], is_float) : NULL;
        if (!t)
            return pbrt_fail(imp, q->line, "Texture: \"%s\": no texture \"%s\"", name, q->count ? q->strings[0] : "");
        *out = *t;
        return true;
    }
    return pbrt_spectrum_rgb(imp, q, "reflectance", out->value);
}

static bool imagemap(PbrtImport *imp, PbrtParams *p, PbrtTexture *t)
{
    bool ok = true;
    const char *file = pbrt_string(imp, p, "filename", &ok);
    const char *encoding = ok ? pbrt_string(imp, p, "encoding", &ok) : NULL;
    const char *wrap = ok ? pbrt_string(imp, p, "wrap", &ok) : NULL;
    float scale, su, sv, du, dv;
    bool invert;
    if (!ok || !pbrt_float(imp, p, "scale", 1.0f, &scale) || !pbrt_bool(imp, p, "invert", false, &invert) ||
        !pbrt_float(imp, p, "uscale", 1.0f, &su) || !pbrt_float(imp, p, "vscale", 1.0f, &sv) ||
        !pbrt_float(imp, p, "udelta", 0.0f, &du) || !pbrt_float(imp, p, "vdelta", 0.0f, &dv))
        return false;
    if (!file)
        return pbrt_fail(imp, imp->line, "Texture \"imagemap\": no \"string filename\"");
    /* pbrt-v4's default: sRGB for PNG, linear for every other file (JPEG and TGA included). */
    const char *pt_encoding = NULL;
    if ((encoding && strcmp(encoding, "linear") == 0) || (!encoding && !fs_has_suffix(file, ".png")))
        pt_encoding = "linear";
    else if (encoding && strcmp(encoding, "sRGB") != 0)
        pbrt_warn_once(imp, "encoding", "Texture \"imagemap\": encoding \"%s\" read as sRGB", encoding);
    if (invert)
        pbrt_warn_once(imp, "invert", "Texture \"imagemap\": \"invert\" is not imported");
    (void)pbrt_param(p, "filter");
    (void)pbrt_param(p, "maxanisotropy");
    if (!pbrt_add_file_texture(imp, file, pt_encoding, imp->line, t->pt_texture))
        return false;
    cJSON *json = cJSON_GetObjectItemCaseSensitive(imp->textures, t->pt_texture);
    if (scale != 1.0f)
        cJSON_AddNumberToObject(json, "scale", scale);
    if (wrap && (strcmp(wrap, "clamp") == 0 || strcmp(wrap, "black") == 0))
        cJSON_AddStringToObject(json, "wrap", "clamp");
    if (su != 1.0f || sv != 1.0f || du != 0.0f || dv != 0.0f) {
        cJSON *tr = cJSON_AddObjectToObject(json, "transform");
        cJSON_AddItemToObject(tr, "scale", cJSON_CreateDoubleArray((double[]){su, sv}, 2));
        cJSON_AddItemToObject(tr, "offset", cJSON_CreateDoubleArray((double[]){du, dv}, 2));
    }
    return true;
}

/* scale: a texture times a grey constant is the texture with "scale" (a copy of its JSON). */
static bool scale_texture(PbrtImport *imp, PbrtParams *p, bool is_float, PbrtTexture *t)
{
    PbrtTexture a, b;
    if (!texture_operand(imp, p, "tex", 1.0f, is_float, &a) || !texture_operand(imp, p, "scale", 1.0f, is_float, &b))
        return false;
    if (a.pt_texture[0] && b.pt_texture[0]) {
        pbrt_warn_once(imp, "scale2", "Texture \"scale\" of two textures: the second is dropped");
        *t = a;
        return true;
    }
    PbrtTexture *tex = a.pt_texture[0] ? &a : b.pt_texture[0] ? &b : NULL, *c = tex == &a ? &b : &a;
    if (!tex) {
        for (int k = 0; k < 3; k++)
            t->value[k] = a.value[k] * b.value[k];
        return true;
    }
    float grey = (c->value[0] + c->value[1] + c->value[2]) / 3.0f;
    if (c->value[0] != c->value[1] || c->value[1] != c->value[2])
        pbrt_warn_once(imp, "scale rgb", "Texture \"scale\": a coloured scale of a texture is applied as its mean");
    cJSON *copy = cJSON_Duplicate(cJSON_GetObjectItemCaseSensitive(imp->textures, tex->pt_texture), true);
    cJSON *old = cJSON_GetObjectItemCaseSensitive(copy, "scale");
    double s = grey * (old ? old->valuedouble : 1.0);
    cJSON_DeleteItemFromObject(copy, "scale");
    cJSON_AddNumberToObject(copy, "scale", s);
    snprintf(t->pt_texture, sizeof t->pt_texture, "texture%d", imp->num_pt_textures++);
    cJSON_AddItemToObject(imp->textures, t->pt_texture, copy);
    return true;
}

/* mix and checkerboard: two operands pt cannot blend: their mean when constant, else the first. */
static bool blend_texture(PbrtImport *imp, const char *type, PbrtParams *p, bool is_float, PbrtTexture *t)
{
    PbrtTexture a, b;
    float amount;
    bool mix = strcmp(type, "mix") == 0;
    if (!texture_operand(imp, p, "tex1", mix ? 0.0f : 1.0f, is_float, &a) ||
        !texture_operand(imp, p, "tex2", mix ? 1.0f : 0.0f, is_float, &b) ||
        (mix && pbrt_param(p, "amount") && pbrt_param(p, "amount")->type != PBRT_TEXTURE &&
         !pbrt_float(imp, p, "amount", 0.5f, &amount)))
        return false;
    if (!mix || (pbrt_param(p, "amount") && pbrt_param(p, "amount")->type == PBRT_TEXTURE))
        amount = 0.5f;
    else if (!pbrt_float(imp, p, "amount", 0.5f, &amount))
        return false;
    char key[64];
    snprintf(key, sizeof key, "texture %s", type);
    pbrt_warn_once(imp, key, "Texture \"%s\": pt has no %s texture: %s", type, type,
                   a.pt_texture[0] ? "its first texture is used" : "the mean value is used");
    if (a.pt_texture[0]) {
        *t = a;
        return true;
    }
    for (int k = 0; k < 3; k++)
        t->value[k] = (1.0f - amount) * a.value[k] + amount * b.value[k];
    (void)pbrt_param(p, "dimension");
    return true;
}

bool pbrt_texture(PbrtImport *imp, const char *name, const char *value_type, const char *type, PbrtParams *p)
{
    bool is_float = strcmp(value_type, "float") == 0;
    if (!is_float && strcmp(value_type, "spectrum") != 0 && strcmp(value_type, "color") != 0)
        return pbrt_fail(imp, imp->line, "Texture \"%s\": type \"%s\" is not \"float\" or \"spectrum\"",
                         name, value_type);
    PbrtTexture t = {.is_float = is_float, .value = {0.5f, 0.5f, 0.5f}};
    snprintf(t.name, sizeof t.name, "%s", name);
    bool ok;
    if (strcmp(type, "imagemap") == 0) {
        ok = imagemap(imp, p, &t);
    } else if (strcmp(type, "constant") == 0) {
        PbrtTexture v;
        ok = texture_operand(imp, p, "value", 1.0f, is_float, &v);
        memcpy(t.value, v.value, sizeof t.value);
    } else if (strcmp(type, "scale") == 0) {
        ok = scale_texture(imp, p, is_float, &t);
    } else if (strcmp(type, "mix") == 0 || strcmp(type, "checkerboard") == 0) {
        ok = blend_texture(imp, type, p, is_float, &t);
    } else {
        char key[64];
        snprintf(key, sizeof key, "texture %s", type);
        pbrt_warn_once(imp, key, "Texture \"%s\": not imported (constant 0.5 used)", type);
        for (int i = 0; i < p->count; i++)
            p->items[i].used = true;
        ok = true;
    }
    if (!ok)
        return false;
    (void)pbrt_param(p, "mapping");
    pbrt_warn_unused(imp, "Texture", type, p);
    PbrtTexture *grown = realloc(imp->pbrt_textures, (size_t)(imp->num_pbrt_textures + 1) * sizeof *grown);
    if (!grown)
        return pbrt_fail(imp, imp->line, "Texture: out of memory");
    imp->pbrt_textures = grown;
    imp->pbrt_textures[imp->num_pbrt_textures++] = t;
    return true;
}

