// SPDX-License-Identifier: MIT
/* material_json.c: the "materials" block: one reader per value kind (colour or texture, scalar or
 * texture, texture name, material name), the keys each type takes, and the mix graph checks. */
#include "scene/material_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/materials.h"

/* What every reader of one material needs. */
typedef struct {
    JsonParser *p;
    const cJSON *e;       /* the material's object */
    const char *prefix;   /* "materials.<name>" */
    const TextureDesc *textures;
    int num_textures;
    const cJSON *all;     /* the whole "materials" object, for mix names */
    Material *m;
} Reader;

static const char *type_names[] = {
#define MATERIAL_TYPE_NAME(name, json) json,
    MATERIAL_TYPES(MATERIAL_TYPE_NAME)
#undef MATERIAL_TYPE_NAME
};

/* Keys per type (after the keys every type takes). */
static const char *const *type_keys(uint32_t type)
{
    static const char *const diffuse[] = {"albedo", NULL};
    static const char *const conductor[] = {"roughness", "eta", "k", "reflectance", "anisotropy", NULL};
    static const char *const dielectric[] = {"ior", "roughness", "tint", "absorption", NULL};
    static const char *const principled[] = {"base_color", "metallic",   "roughness",
                                             "specular",   "specular_color", "ior",
                                             "subsurface", "subsurface_radius", NULL};
    static const char *const mix[] = {"a", "b", "weight", NULL};
    static const char *const interface[] = {NULL};
    static const char *const *const all[MATERIAL_TYPE_COUNT] = {
        [MATERIAL_DIFFUSE] = diffuse, [MATERIAL_CONDUCTOR] = conductor,
        [MATERIAL_DIELECTRIC] = dielectric, [MATERIAL_PRINCIPLED] = principled, [MATERIAL_MIX] = mix,
        [MATERIAL_INTERFACE] = interface};
    return all[type];
}

/* The common keys, except for an interface, which has no parameters: it is only where media meet
 * (nothing to emit, bump or cut out). */
static bool check_keys(Reader *r, uint32_t type)
{
    static const char *const common[] = {"type", "emission", "emission_strength", "normal_map",
                                         "bump_map", "bump_scale", "opacity", "alpha_cutoff"};
    const char *keys[24];
    int n = 0;
    for (size_t i = 0; i < (type == MATERIAL_INTERFACE ? 1 : sizeof common / sizeof *common); i++)
        keys[n++] = common[i];
    for (const char *const *k = type_keys(type); *k; k++)
        keys[n++] = *k;
    keys[n] = NULL;
    return json_check_object(r->p, r->e, r->prefix, keys);
}

static bool find_texture(Reader *r, const char *key, const cJSON *item, uint32_t *slot)
{
    int index = texture_desc_find(r->textures, r->num_textures, item->valuestring);
    if (index < 0)
        return json_fail(r->p, ERR_JSON_VALUE, key, "unknown texture \"%s\" (not in \"textures\")",
                         item->valuestring);
    *slot = (uint32_t)index;
    return true;
}

/* A colour (n = 3) or scalar (n = 1) member: a number, [r, g, b] (n = 3), or, where slot >= 0, a
 * texture's name (the constant is then 1 for a colour, which the texture multiplies). Every
 * component must lie in [lo, hi] (hi excluded when hi_open). Absent: out keeps its default. */
static bool read_value(Reader *r, const char *name, int n, float *out, int slot, float lo, float hi,
                       bool hi_open)
{
    const cJSON *item = json_member(r->e, name);
    if (!item)
        return true;
    char key[300];
    snprintf(key, sizeof key, "%s.%s", r->prefix, name);
    if (cJSON_IsString(item) && slot >= 0) {
        for (int i = 0; i < n && n == 3; i++)
            out[i] = 1.0f;
        return find_texture(r, key, item, &r->m->tex[slot]);
    }
    if (cJSON_IsNumber(item)) {
        if (!json_read_float(r->p, item, key, &out[0]))
            return false;
        for (int i = 1; i < n; i++)
            out[i] = out[0];
    } else if (n == 3 && cJSON_IsArray(item)) {
        if (!json_read_vec3(r->p, item, key, out))
            return false;
    } else {
        return json_fail(r->p, ERR_JSON_TYPE, key, "expected %s%s", n == 3 ? "[r, g, b] or a number" : "a number",
                         slot >= 0 ? " or a texture name" : "");
    }
    for (int i = 0; i < n; i++) {
        if (!(out[i] >= lo) || (hi_open ? !(out[i] < hi) : !(out[i] <= hi))) {
            char range[64];
            if (isinf(hi))
                snprintf(range, sizeof range, "must be finite and >= %g", lo);
            else
                snprintf(range, sizeof range, "is out of range [%g, %g%s", lo, hi, hi_open ? ")" : "]");
            if (n == 1)
                return json_fail(r->p, ERR_JSON_VALUE, key, "%g %s", out[0], range);
            return json_fail(r->p, ERR_JSON_VALUE, key, "[%g, %g, %g] %s", out[0], out[1], out[2],
                             range);
        }
    }
    return true;
}

/* normal_map, bump_map: a texture's name. */
static bool read_texture_name(Reader *r, const char *name, int slot)
{
    const cJSON *item = json_member(r->e, name);
    if (!item)
        return true;
    char key[300];
    snprintf(key, sizeof key, "%s.%s", r->prefix, name);
    if (!cJSON_IsString(item))
        return json_fail(r->p, ERR_JSON_TYPE, key, "expected a texture name (string)");
    return find_texture(r, key, item, &r->m->tex[slot]);
}

/* mix a, b: another JSON material's name (not this one). */
static bool read_material_name(Reader *r, const char *name, const char *self, uint32_t *out)
{
    char key[300];
    snprintf(key, sizeof key, "%s.%s", r->prefix, name);
    const cJSON *item = json_member(r->e, name);
    if (!item)
        return json_fail(r->p, ERR_JSON_VALUE, key, "missing (a mix names two materials)");
    if (!cJSON_IsString(item))
        return json_fail(r->p, ERR_JSON_TYPE, key, "expected a material name (string)");
    if (strcmp(item->valuestring, self) == 0)
        return json_fail(r->p, ERR_JSON_VALUE, key, "\"%s\" is the mix itself (a cycle)", self);
    int index = 0;
    for (const cJSON *m = r->all->child; m; m = m->next, index++) {
        if (strcmp(m->string, item->valuestring) == 0) {
            *out = (uint32_t)index;
            return true;
        }
    }
    return json_fail(r->p, ERR_JSON_VALUE, key, "unknown material \"%s\" (not in \"materials\")",
                     item->valuestring);
}

static bool read_type(Reader *r, uint32_t *type)
{
    char key[300];
    snprintf(key, sizeof key, "%s.type", r->prefix);
    const cJSON *item = json_member(r->e, "type");
    if (!item)
        return json_fail(r->p, ERR_JSON_VALUE, key, "missing (diffuse, conductor, dielectric, "
                                                    "principled, mix or interface)");
    if (!cJSON_IsString(item))
        return json_fail(r->p, ERR_JSON_TYPE, key, "expected a string");
    for (uint32_t t = 0; t < MATERIAL_TYPE_COUNT; t++) {
        if (strcmp(item->valuestring, type_names[t]) == 0) {
            *type = t;
            return true;
        }
    }
    return json_fail(r->p, ERR_JSON_VALUE, key,
                     "\"%s\" is not a material type (diffuse, conductor, dielectric, principled, "
                     "mix, interface)",
                     item->valuestring);
}

/* principled subsurface (weight in [0, 1]) and subsurface_radius (mean free paths per channel,
 * > 0: the walk's sigma_t is their inverse; default Blender's [1, 0.2, 0.1] x 0.05). */
static bool read_subsurface(Reader *r, float radius[3])
{
    static const float blender[3] = {1.0f, 0.2f, 0.1f};
    for (int i = 0; i < 3; i++)
        radius[i] = blender[i] * 0.05f;
    if (!read_value(r, "subsurface", 1, &r->m->subsurface, -1, 0, 1, false) ||
        !read_value(r, "subsurface_radius", 3, radius, -1, 0, INFINITY, false))
        return false;
    if (radius[0] > 0.0f && radius[1] > 0.0f && radius[2] > 0.0f)
        return true;
    char key[300];
    snprintf(key, sizeof key, "%s.subsurface_radius", r->prefix);
    return json_fail(r->p, ERR_JSON_VALUE, key, "[%g, %g, %g] must be > 0 (a mean free path)",
                     radius[0], radius[1], radius[2]);
}

/* The keys of each type; see shared/DESIGN.md "Materials" for their meaning and defaults. */
static bool read_type_keys(Reader *r, const char *self, float subsurface_radius[3])
{
    Material *m = r->m;
    float *base = m->base.s;
    switch (m->type) {
    case MATERIAL_DIFFUSE:
        base[0] = base[1] = base[2] = 0.8f;
        return read_value(r, "albedo", 3, base, MATERIAL_TEX_BASE, 0.0f, 1.0f, false);
    case MATERIAL_CONDUCTOR: {
        bool has_eta = json_member(r->e, "eta"), has_k = json_member(r->e, "k");
        if (has_k && !has_eta) {
            char key[300];
            snprintf(key, sizeof key, "%s.k", r->prefix);
            return json_fail(r->p, ERR_JSON_VALUE, key, "given without \"eta\"");
        }
        if (!has_eta)
            m->flags |= MATERIAL_FLAG_FRESNEL_ONE;
        return read_value(r, "roughness", 1, &m->roughness, MATERIAL_TEX_ROUGHNESS, 0, 1, false) &&
               read_value(r, "eta", 3, m->eta.s, -1, 0, INFINITY, false) &&
               read_value(r, "k", 3, m->k.s, -1, 0, INFINITY, false) &&
               read_value(r, "reflectance", 3, base, MATERIAL_TEX_BASE, 0, 1, false) &&
               read_value(r, "anisotropy", 1, &m->anisotropy, -1, 0, 1, true);
    }
    case MATERIAL_DIELECTRIC:
        return read_value(r, "ior", 1, &m->ior, -1, 0, INFINITY, false) &&
               read_value(r, "roughness", 1, &m->roughness, MATERIAL_TEX_ROUGHNESS, 0, 1, false) &&
               read_value(r, "tint", 3, base, MATERIAL_TEX_BASE, 0, 1, false) &&
               read_value(r, "absorption", 3, m->absorption.s, -1, 0, INFINITY, false);
    case MATERIAL_PRINCIPLED:
        m->roughness = 0.5f; /* glTF's factors default to 1; 0.5 is Blender's and pbrt's default */
        return read_value(r, "base_color", 3, base, MATERIAL_TEX_BASE, 0, 1, false) &&
               read_value(r, "metallic", 1, &m->metallic, MATERIAL_TEX_METALLIC, 0, 1, false) &&
               read_value(r, "roughness", 1, &m->roughness, MATERIAL_TEX_ROUGHNESS, 0, 1, false) &&
               read_value(r, "specular", 1, &m->specular, -1, 0, 1, false) &&
               read_value(r, "specular_color", 3, m->specular_color.s, -1, 0, INFINITY, false) &&
               read_value(r, "ior", 1, &m->ior, -1, 0, INFINITY, false) &&
               read_subsurface(r, subsurface_radius);
    case MATERIAL_MIX:
        return read_material_name(r, "a", self, &m->mix_a) &&
               read_material_name(r, "b", self, &m->mix_b) &&
               read_value(r, "weight", 1, &m->weight, MATERIAL_TEX_WEIGHT, 0, 1, false);
    case MATERIAL_INTERFACE:
        return true;
    }
    return false;
}

/* An ior of 0 would divide by zero in the Fresnel terms. */
static bool check_ior(Reader *r)
{
    if (r->m->ior > 0.0f)
        return true;
    char key[300];
    snprintf(key, sizeof key, "%s.ior", r->prefix);
    return json_fail(r->p, ERR_JSON_VALUE, key, "%g must be > 0", r->m->ior);
}

/* Keys every type takes: emission (times emission_strength), normal and bump maps, opacity and
 * its alpha_cutoff (opacity 1 where it reaches the cutoff, else 0: glTF's alphaMode MASK). */
static bool read_common_keys(Reader *r)
{
    Material *m = r->m;
    float strength = 1.0f, cutoff = -1.0f;
    if (!read_value(r, "emission", 3, m->emission.s, MATERIAL_TEX_EMISSION, 0, INFINITY, false) ||
        !read_value(r, "emission_strength", 1, &strength, -1, 0, INFINITY, false) ||
        !read_texture_name(r, "normal_map", MATERIAL_TEX_NORMAL) ||
        !read_texture_name(r, "bump_map", MATERIAL_TEX_BUMP) ||
        !read_value(r, "bump_scale", 1, &m->bump_scale, -1, -INFINITY, INFINITY, false) ||
        !read_value(r, "opacity", 1, &m->opacity, MATERIAL_TEX_OPACITY, 0, 1, false) ||
        !read_value(r, "alpha_cutoff", 1, &cutoff, -1, 0, 1, false))
        return false;
    for (int i = 0; i < 3; i++)
        m->emission.s[i] *= strength;
    if (m->opacity < 1.0f || m->tex[MATERIAL_TEX_OPACITY] != NO_TEXTURE)
        m->flags |= MATERIAL_FLAG_CUTOUT;
    if (cutoff >= 0.0f) {
        m->flags |= MATERIAL_FLAG_ALPHA_MASK | MATERIAL_FLAG_CUTOUT;
        m->base.s[3] = cutoff;
    }
    return true;
}

/* Mix depth (levels of mix above a leaf), refusing cycles: state 0 unseen, 1 on the path, 2 done. */
static bool check_mix(JsonParser *p, const MaterialDesc *descs, int i, unsigned char *state,
                      unsigned *depth)
{
    const Material *m = &descs[i].m;
    if (state[i] == 2 || m->type != MATERIAL_MIX) {
        state[i] = 2;
        return true;
    }
    char key[300];
    snprintf(key, sizeof key, "materials.%s", descs[i].name);
    if (state[i] == 1)
        return json_fail(p, ERR_JSON_VALUE, key, "mix cycle: \"%s\" contains itself", descs[i].name);
    state[i] = 1;
    uint32_t child[2] = {m->mix_a, m->mix_b};
    depth[i] = 1;
    for (int c = 0; c < 2; c++) {
        /* A mix picks one of its materials per hit; an interface is no surface to pick (a ray
         * passes it without a bounce), so "half invisible" has no meaning here. */
        if (descs[child[c]].m.type == MATERIAL_INTERFACE) {
            snprintf(key, sizeof key, "materials.%s.%s", descs[i].name, c ? "b" : "a");
            return json_fail(p, ERR_JSON_VALUE, key,
                             "\"%s\" is an interface, which cannot be mixed (it is no surface)",
                             descs[child[c]].name);
        }
        if (!check_mix(p, descs, (int)child[c], state, depth))
            return false;
        if (depth[child[c]] + 1 > depth[i])
            depth[i] = depth[child[c]] + 1;
    }
    state[i] = 2;
    if (depth[i] > MATERIAL_MIX_DEPTH_LIMIT)
        return json_fail(p, ERR_JSON_VALUE, key, "mixes nest %u deep; at most %u are allowed",
                         depth[i], MATERIAL_MIX_DEPTH_LIMIT);
    return true;
}

bool materials_from_json(JsonParser *p, const cJSON *obj, const TextureDesc *textures,
                         int num_textures, MaterialDesc **out, int *count)
{
    *out = NULL;
    *count = 0;
    if (!cJSON_IsObject(obj))
        return json_fail(p, ERR_JSON_TYPE, "materials", "expected an object of named materials");
    int n = cJSON_GetArraySize(obj);
    MaterialDesc *descs = calloc(n ? (size_t)n : 1, sizeof *descs);
    unsigned char *state = calloc(n ? (size_t)n : 1, 1);
    unsigned *depth = calloc(n ? (size_t)n : 1, sizeof *depth);
    *out = descs;
    bool ok = descs && state && depth;
    if (!ok)
        json_fail(p, ERR_TOO_LARGE, "materials", "out of memory");
    for (const cJSON *e = obj->child; ok && e; e = e->next) {
        char prefix[256];
        snprintf(prefix, sizeof prefix, "materials.%s", e->string);
        if (!e->string[0] || strlen(e->string) >= SCENE_NAME_LIMIT) {
            ok = json_fail(p, ERR_JSON_VALUE, prefix, "a name must have 1 to %d characters",
                           SCENE_NAME_LIMIT - 1);
            break;
        }
        if (material_desc_find(descs, *count, e->string) >= 0) {
            ok = json_fail(p, ERR_JSON_SYNTAX, prefix, "duplicate material name");
            break;
        }
        MaterialDesc *d = &descs[*count];
        snprintf(d->name, sizeof d->name, "%s", e->string);
        Reader r = {p, e, prefix, textures, num_textures, obj, &d->m};
        uint32_t type = 0;
        if (!cJSON_IsObject(e)) {
            ok = json_fail(p, ERR_JSON_TYPE, prefix, "expected an object");
            break;
        }
        ok = read_type(&r, &type) && check_keys(&r, type);
        if (ok) {
            d->m = material_blank(type);
            ok = read_type_keys(&r, d->name, d->subsurface_radius) && check_ior(&r) &&
                 read_common_keys(&r);
        }
        (*count)++;
    }
    for (int i = 0; ok && i < *count; i++)
        ok = check_mix(p, descs, i, state, depth);
    free(state);
    free(depth);
    return ok;
}

int material_desc_find(const MaterialDesc *descs, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (strcmp(descs[i].name, name) == 0)
            return i;
    return -1;
}

static const char *slot_keys[] = {
#define MATERIAL_SLOT_KEY(name, json) json,
    MATERIAL_TEXTURE_SLOTS(MATERIAL_SLOT_KEY)
#undef MATERIAL_SLOT_KEY
};

bool materials_load(const MaterialDesc *descs, int count, const TextureDesc *textures,
                    const TextureSet *set, const uint32_t *texture_indices, uint32_t first, Material *out,
                    const char *scene_path, Error *err)
{
    for (int i = 0; i < count; i++) {
        Material m = descs[i].m;
        for (int s = 0; s < MATERIAL_TEX_COUNT; s++)
            if (m.tex[s] != NO_TEXTURE)
                m.tex[s] = texture_indices[m.tex[s]];
        uint32_t normal = m.tex[MATERIAL_TEX_NORMAL];
        if (normal != NO_TEXTURE && set->stats[normal].channels < 3) {
            error_set(err, ERR_TEXTURE, scene_path, 0,
                      "%s: materials.%s.%s: texture \"%s\" has %d channel%s; a normal map needs rgb",
                      scene_path, descs[i].name, slot_keys[MATERIAL_TEX_NORMAL],
                      textures[descs[i].m.tex[MATERIAL_TEX_NORMAL]].name,
                      set->stats[normal].channels, set->stats[normal].channels == 1 ? "" : "s");
            return false;
        }
        if (m.type == MATERIAL_MIX) {
            m.mix_a += first;
            m.mix_b += first;
        }
        m.emission.s[3] = 0.2126f * m.emission.s[0] + 0.7152f * m.emission.s[1] +
                          0.0722f * m.emission.s[2];
        if (m.tex[MATERIAL_TEX_EMISSION] != NO_TEXTURE)
            m.emission.s[3] *= texture_mean_luminance(set, m.tex[MATERIAL_TEX_EMISSION]);
        out[i] = m;
    }
    return true;
}
