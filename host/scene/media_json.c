// SPDX-License-Identifier: MIT
/* media_json.c: the "media" block (media_json.h). Each type has its keys and defaults as DESIGN
 * "Media" lists them; every coefficient is finite and >= 0 (so is its product with the scale: a
 * scale of 1e30 times a sigma of 1e30 would reach the kernels as inf), g lies in (-1, 1) (|g| = 1
 * is a delta phase function HG sampling cannot represent) and a grid's albedo in [0, 1] (above
 * 1 its sigma_a would be negative). */
#include "scene/media_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/transform_json.h"

static const char *const type_names[] = {
#define MEDIUM_TYPE_NAME(name, json) json,
    MEDIUM_TYPES(MEDIUM_TYPE_NAME)
#undef MEDIUM_TYPE_NAME
};

/* What every reader of one medium needs. */
typedef struct {
    JsonParser *p;
    const cJSON *e;     /* the medium's object */
    const char *prefix; /* "media.<name>" */
} Reader;

static const char *key_of(const Reader *r, const char *name, char key[300])
{
    snprintf(key, 300, "%s.%s", r->prefix, name);
    return key;
}

/* A colour member (absent: out keeps its default): finite and >= 0, at most `hi` per channel. */
static bool read_colour(const Reader *r, const char *name, float hi, float out[3])
{
    const cJSON *item = json_member(r->e, name);
    char key[300];
    if (!item)
        return true;
    if (!json_read_colour(r->p, item, key_of(r, name, key), out))
        return false;
    for (int i = 0; i < 3; i++)
        if (!(out[i] <= hi))
            return json_fail(r->p, ERR_JSON_VALUE, key, "[%g, %g, %g] is outside [0, %g]", out[0],
                             out[1], out[2], hi);
    return true;
}

/* A scalar member >= 0 (absent: out keeps its default). */
static bool read_scale(const Reader *r, const char *name, float *out)
{
    const cJSON *item = json_member(r->e, name);
    char key[300];
    if (!item)
        return true;
    if (!json_read_float(r->p, item, key_of(r, name, key), out))
        return false;
    if (!(*out >= 0.0f))
        return json_fail(r->p, ERR_JSON_VALUE, key, "%g must be >= 0", *out);
    return true;
}

/* g, the Henyey-Greenstein asymmetry, in (-1, 1). */
static bool read_g(const Reader *r, float *g)
{
    const cJSON *item = json_member(r->e, "g");
    char key[300];
    *g = 0.0f;
    if (!item)
        return true;
    if (!json_read_float(r->p, item, key_of(r, "g", key), g))
        return false;
    if (!(*g > -1.0f && *g < 1.0f))
        return json_fail(r->p, ERR_JSON_VALUE, key, "%g is outside (-1, 1)", *g);
    return true;
}

/* out = a * s per channel, which must stay finite (each factor is). */
static bool scaled(const Reader *r, const char *name, const float a[3], float s, float4 *out)
{
    for (int i = 0; i < 3; i++) {
        out->s[i] = a[i] * s;
        if (!isfinite(out->s[i])) {
            char key[300];
            return json_fail(r->p, ERR_JSON_VALUE, key_of(r, name, key),
                             "[%g, %g, %g] times the scale %g is not finite", a[0], a[1], a[2], s);
        }
    }
    return true;
}

static bool read_type(const Reader *r, uint32_t *type)
{
    char key[300];
    const cJSON *item = json_member(r->e, "type");
    key_of(r, "type", key);
    if (!item)
        return json_fail(r->p, ERR_JSON_VALUE, key, "missing (homogeneous or grid)");
    if (!cJSON_IsString(item))
        return json_fail(r->p, ERR_JSON_TYPE, key, "expected a string (homogeneous or grid)");
    for (uint32_t t = 0; t < MEDIUM_TYPE_COUNT; t++)
        if (strcmp(item->valuestring, type_names[t]) == 0) {
            *type = t;
            return true;
        }
    return json_fail(r->p, ERR_JSON_VALUE, key, "\"%s\" is not a medium type (homogeneous or grid)",
                     item->valuestring);
}

/* {"type": "homogeneous", "sigma_a", "sigma_s", "scale", "g", "emission"}. */
static bool read_homogeneous(const Reader *r, MediumDesc *d)
{
    static const char *const keys[] = {"type", "sigma_a", "sigma_s", "scale", "g", "emission", NULL};
    float sigma_a[3] = {0}, sigma_s[3] = {0}, scale = 1.0f, g;
    if (!json_check_object(r->p, r->e, r->prefix, keys) ||
        !read_colour(r, "sigma_a", INFINITY, sigma_a) ||
        !read_colour(r, "sigma_s", INFINITY, sigma_s) || !read_scale(r, "scale", &scale) ||
        !read_g(r, &g) || !read_colour(r, "emission", INFINITY, d->m.emission.s) ||
        !scaled(r, "sigma_a", sigma_a, scale, &d->m.sigma_a) ||
        !scaled(r, "sigma_s", sigma_s, scale, &d->m.sigma_s))
        return false;
    d->m.sigma_a.s[3] = g;
    return true;
}

/* The grid's file (required) and grid name. */
static bool read_grid_file(const Reader *r, MediumDesc *d)
{
    char key[300];
    const cJSON *file = json_member(r->e, "file"), *grid = json_member(r->e, "grid");
    key_of(r, "file", key);
    if (!file)
        return json_fail(r->p, ERR_JSON_VALUE, key, "missing (a .nvdb or .vol file)");
    if (!cJSON_IsString(file))
        return json_fail(r->p, ERR_JSON_TYPE, key, "expected a file name (string)");
    if (!file->valuestring[0])
        return json_fail(r->p, ERR_JSON_VALUE, key, "empty file name");
    if (!json_path_resolve(r->p, key, file->valuestring, d->file))
        return false;
    if (!grid)
        return true;
    key_of(r, "grid", key);
    if (!cJSON_IsString(grid))
        return json_fail(r->p, ERR_JSON_TYPE, key, "expected a grid name (string)");
    if (strlen(grid->valuestring) >= sizeof d->grid)
        return json_fail(r->p, ERR_JSON_VALUE, key, "a grid name has at most %zu characters",
                         sizeof d->grid - 1);
    snprintf(d->grid, sizeof d->grid, "%s", grid->valuestring);
    return true;
}

/* {"type": "grid", "file", "grid", "density_scale", "sigma_t", "albedo", "g", "emission",
 * "transform"}: per unit of density, sigma_s = albedo sigma_t density_scale and sigma_a =
 * (1 - albedo) sigma_t density_scale. */
static bool read_grid(const Reader *r, MediumDesc *d)
{
    static const char *const keys[] = {"type",   "file", "grid",     "density_scale", "sigma_t",
                                       "albedo", "g",    "emission", "transform",     NULL};
    float density_scale = 1.0f, sigma_t[3] = {1, 1, 1}, albedo[3] = {1, 1, 1}, g;
    char key[300];
    const cJSON *transform = json_member(r->e, "transform");
    d->transform = affine_identity();
    if (!json_check_object(r->p, r->e, r->prefix, keys) || !read_grid_file(r, d) ||
        !read_scale(r, "density_scale", &density_scale) ||
        !read_colour(r, "sigma_t", INFINITY, sigma_t) || !read_colour(r, "albedo", 1.0f, albedo) ||
        !read_g(r, &g) || !read_colour(r, "emission", INFINITY, d->m.emission.s) ||
        (transform && !transform_from_json(r->p, transform, key_of(r, "transform", key),
                                           &d->transform)))
        return false;
    float4 t;
    if (!scaled(r, "sigma_t", sigma_t, density_scale, &t))
        return false;
    for (int i = 0; i < 3; i++) {
        d->m.sigma_s.s[i] = albedo[i] * t.s[i];
        d->m.sigma_a.s[i] = (1.0f - albedo[i]) * t.s[i];
    }
    d->m.sigma_a.s[3] = g;
    return true;
}

bool media_from_json(JsonParser *p, const cJSON *obj, MediumDesc **out, int *count)
{
    *out = NULL;
    *count = 0;
    if (!cJSON_IsObject(obj))
        return json_fail(p, ERR_JSON_TYPE, "media", "expected an object of named media");
    int n = cJSON_GetArraySize(obj);
    if ((unsigned)n > MEDIUM_COUNT_LIMIT)
        return json_fail(p, ERR_TOO_LARGE, "media", "%d media; at most %u are allowed", n,
                         MEDIUM_COUNT_LIMIT);
    MediumDesc *descs = calloc(n ? (size_t)n : 1, sizeof *descs);
    *out = descs;
    if (!descs)
        return json_fail(p, ERR_TOO_LARGE, "media", "out of memory");
    for (const cJSON *e = obj->child; e; e = e->next) {
        char prefix[256];
        snprintf(prefix, sizeof prefix, "media.%s", e->string);
        if (!e->string[0] || strlen(e->string) >= SCENE_NAME_LIMIT)
            return json_fail(p, ERR_JSON_VALUE, prefix, "a name must have 1 to %d characters",
                             SCENE_NAME_LIMIT - 1);
        if (medium_desc_slot(descs, *count, e->string))
            return json_fail(p, ERR_JSON_SYNTAX, prefix, "duplicate medium name");
        if (!cJSON_IsObject(e))
            return json_fail(p, ERR_JSON_TYPE, prefix, "expected an object");
        MediumDesc *d = &descs[*count];
        snprintf(d->name, sizeof d->name, "%s", e->string);
        Reader r = {p, e, prefix};
        uint32_t type = 0;
        if (!read_type(&r, &type))
            return false;
        d->m.type = type;
        if (!(type == MEDIUM_GRID ? read_grid(&r, d) : read_homogeneous(&r, d)))
            return false;
        (*count)++;
    }
    return true;
}

uint32_t medium_desc_slot(const MediumDesc *descs, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (strcmp(descs[i].name, name) == 0)
            return (uint32_t)i + 1;
    return 0;
}

bool media_read_slot(JsonParser *p, const cJSON *item, const char *key, const MediumDesc *descs,
                     int count, uint32_t *slot)
{
    if (!item)
        return true;
    if (!cJSON_IsString(item))
        return json_fail(p, ERR_JSON_TYPE, key, "expected a medium name (string)");
    uint32_t found = medium_desc_slot(descs, count, item->valuestring);
    if (!found)
        return json_fail(p, ERR_JSON_VALUE, key, "unknown medium \"%s\" (not in \"media\")",
                         item->valuestring);
    *slot = found;
    return true;
}
