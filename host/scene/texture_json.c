// SPDX-License-Identifier: MIT
/* texture_json.c: the "textures" block: checking each entry and loading it. */
#include "scene/texture_json.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


static bool read_noise_colour(JsonParser *p, const cJSON *e, const char *name, const char *prefix,
                              float out[3])
{
    char key[300];
    snprintf(key, sizeof key, "%s.%s", prefix, name);
    const cJSON *item = json_member(e, name);
    return !item || json_read_colour(p, item, key, out);
}

/* type "noise": color0 (default 0), color1 (default 1), frequency > 0 (default 1), octaves in
 * 1..16 (default 4), seed >= 0 (default 0). */
static bool read_noise(JsonParser *p, const cJSON *e, const char *prefix, TextureDesc *t)
{
    static const char *const keys[] = {"type", "color0", "color1", "frequency", "octaves", "seed", NULL};
    t->is_noise = true;
    t->noise = (TextureNoise){.color1 = {1.0f, 1.0f, 1.0f}, .frequency = 1.0f, .octaves = 4};
    if (!json_check_object(p, e, prefix, keys) ||
        !read_noise_colour(p, e, "color0", prefix, t->noise.color0) ||
        !read_noise_colour(p, e, "color1", prefix, t->noise.color1))
        return false;
    char key[300];
    const cJSON *item;
    if ((item = json_member(e, "frequency"))) {
        snprintf(key, sizeof key, "%s.frequency", prefix);
        if (!json_read_float(p, item, key, &t->noise.frequency))
            return false;
        if (!(t->noise.frequency > 0.0f))
            return json_fail(p, ERR_JSON_VALUE, key, "%g must be > 0", t->noise.frequency);
    }
    int v;
    if ((item = json_member(e, "octaves"))) {
        snprintf(key, sizeof key, "%s.octaves", prefix);
        if (!json_read_int(p, item, key, &v))
            return false;
        if (v < 1 || v > 16)
            return json_fail(p, ERR_JSON_VALUE, key, "%d is out of range [1, 16]", v);
        t->noise.octaves = (uint32_t)v;
    }
    if ((item = json_member(e, "seed"))) {
        snprintf(key, sizeof key, "%s.seed", prefix);
        if (!json_read_int(p, item, key, &v))
            return false;
        if (v < 0)
            return json_fail(p, ERR_JSON_VALUE, key, "%d must be >= 0", v);
        t->noise.seed = (uint32_t)v;
    }
    return true;
}

/* A name among `names` (NULL-terminated): its index. */
static bool read_name(JsonParser *p, const cJSON *item, const char *key, const char *const *names,
                      const char *expected, uint32_t *out)
{
    for (uint32_t i = 0; cJSON_IsString(item) && names[i]; i++) {
        if (strcmp(item->valuestring, names[i]) == 0) {
            *out = i;
            return true;
        }
    }
    if (!cJSON_IsString(item))
        return json_fail(p, ERR_JSON_TYPE, key, "expected %s", expected);
    return json_fail(p, ERR_JSON_VALUE, key, "\"%s\" is not %s", item->valuestring, expected);
}

/* Two finite numbers. */
static bool read_pair(JsonParser *p, const cJSON *item, const char *key, float out[2])
{
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != 2)
        return json_fail(p, ERR_JSON_TYPE, key, "expected [x, y]");
    for (int i = 0; i < 2; i++)
        if (!json_read_float(p, cJSON_GetArrayItem(item, i), key, &out[i]))
            return false;
    return true;
}

/* "transform": {"offset": [x, y], "rotation": degrees, "scale": [x, y]}: uv' = T R S uv as
 * KHR_texture_transform, in pt's uv frame (v up, so the rotation is counter-clockwise). */
static bool read_transform(JsonParser *p, const cJSON *item, const char *prefix, TextureSampling *s)
{
    static const char *const keys[] = {"offset", "rotation", "scale", NULL};
    char key[300];
    snprintf(key, sizeof key, "%s.transform", prefix);
    if (!cJSON_IsObject(item))
        return json_fail(p, ERR_JSON_TYPE, key, "expected {\"offset\", \"rotation\", \"scale\"}");
    float offset[2] = {0.0f, 0.0f}, scale[2] = {1.0f, 1.0f}, degrees = 0.0f;
    const cJSON *v;
    if (!json_check_object(p, item, key, keys) ||
        ((v = json_member(item, "offset")) && !read_pair(p, v, key, offset)) ||
        ((v = json_member(item, "scale")) && !read_pair(p, v, key, scale)) ||
        ((v = json_member(item, "rotation")) && !json_read_float(p, v, key, &degrees)))
        return false;
    double r = degrees * (3.14159265358979323846 / 180.0);
    float c = (float)cos(r), sn = (float)sin(r);
    const float t[6] = {c * scale[0], -sn * scale[1], offset[0], sn * scale[0], c * scale[1], offset[1]};
    memcpy(s->transform, t, sizeof t);
    s->has_transform = true;
    return true;
}

/* The sampling keys of an image texture: channel, scale, wrap, filter, transform. */
static bool read_sampling(JsonParser *p, const cJSON *e, const char *prefix, TextureSampling *s)
{
    static const char *const channels[] = {"r", "g", "b", "a", NULL};
    static const char *const wraps[] = {"repeat", "clamp", "mirror", NULL};
    static const char *const filters[] = {"bilinear", "nearest", NULL};
    const char *const wrap_expected = "\"repeat\", \"clamp\" or \"mirror\"";
    char key[300];
    const cJSON *item;
    if ((item = json_member(e, "channel"))) {
        snprintf(key, sizeof key, "%s.channel", prefix);
        if (!read_name(p, item, key, channels, "\"r\", \"g\", \"b\" or \"a\"", &s->channel))
            return false;
    }
    if ((item = json_member(e, "scale"))) {
        snprintf(key, sizeof key, "%s.scale", prefix);
        if (!json_read_float(p, item, key, &s->scale))
            return false;
        s->has_scale = true;
    }
    if ((item = json_member(e, "wrap"))) {
        snprintf(key, sizeof key, "%s.wrap", prefix);
        bool pair = cJSON_IsArray(item) && cJSON_GetArraySize(item) == 2;
        if (!read_name(p, pair ? cJSON_GetArrayItem(item, 0) : item, key, wraps, wrap_expected,
                       &s->wrap_s) ||
            !read_name(p, pair ? cJSON_GetArrayItem(item, 1) : item, key, wraps, wrap_expected,
                       &s->wrap_t))
            return false;
    }
    if ((item = json_member(e, "filter"))) {
        uint32_t filter = 0;
        snprintf(key, sizeof key, "%s.filter", prefix);
        if (!read_name(p, item, key, filters, "\"bilinear\" or \"nearest\"", &filter))
            return false;
        s->nearest = filter == 1;
    }
    return !(item = json_member(e, "transform")) || read_transform(p, item, prefix, s);
}

static bool read_file_texture(JsonParser *p, const cJSON *e, const char *prefix, TextureDesc *t)
{
    static const char *const keys[] = {"type", "file", "encoding", "channel", "scale", "wrap",
                                       "filter", "transform", NULL};
    if (!json_check_object(p, e, prefix, keys))
        return false;
    char key[300];
    snprintf(key, sizeof key, "%s.file", prefix);
    const cJSON *file = json_member(e, "file");
    if (!file)
        return json_fail(p, ERR_JSON_VALUE, key, "missing");
    if (!cJSON_IsString(file))
        return json_fail(p, ERR_JSON_TYPE, key, "expected a file name (string)");
    if (!file->valuestring[0])
        return json_fail(p, ERR_JSON_VALUE, key, "empty file name");
    if (!json_path_resolve(p, key, file->valuestring, t->path) ||
        !read_sampling(p, e, prefix, &t->sampling))
        return false;
    const cJSON *encoding = json_member(e, "encoding");
    if (!encoding)
        return true;
    snprintf(key, sizeof key, "%s.encoding", prefix);
    if (!cJSON_IsString(encoding))
        return json_fail(p, ERR_JSON_TYPE, key, "expected \"srgb\" or \"linear\"");
    if (strcmp(encoding->valuestring, "srgb") == 0)
        t->encoding = TEXTURE_ENCODING_SRGB;
    else if (strcmp(encoding->valuestring, "linear") == 0)
        t->encoding = TEXTURE_ENCODING_LINEAR;
    else
        return json_fail(p, ERR_JSON_VALUE, key, "\"%s\" is not \"srgb\" or \"linear\"",
                         encoding->valuestring);
    return true;
}

bool textures_from_json(JsonParser *p, const cJSON *obj, TextureDesc **out, int *count)
{
    *out = NULL;
    *count = 0;
    if (!cJSON_IsObject(obj))
        return json_fail(p, ERR_JSON_TYPE, "textures", "expected an object of named textures");
    int n = cJSON_GetArraySize(obj);
    TextureDesc *descs = calloc(n ? (size_t)n : 1, sizeof *descs);
    if (!descs)
        return json_fail(p, ERR_TOO_LARGE, "textures", "out of memory");
    *out = descs;
    for (const cJSON *e = obj->child; e; e = e->next) {
        char prefix[256];
        snprintf(prefix, sizeof prefix, "textures.%s", e->string);
        if (!e->string[0] || strlen(e->string) >= SCENE_NAME_LIMIT)
            return json_fail(p, ERR_JSON_VALUE, prefix, "a name must have 1 to %d characters",
                             SCENE_NAME_LIMIT - 1);
        if (texture_desc_find(descs, *count, e->string) >= 0)
            return json_fail(p, ERR_JSON_SYNTAX, prefix, "duplicate texture name");
        TextureDesc *t = &descs[*count];
        snprintf(t->name, sizeof t->name, "%s", e->string);
        if (!cJSON_IsObject(e))
            return json_fail(p, ERR_JSON_TYPE, prefix, "expected an object");
        const cJSON *type = json_member(e, "type");
        char key[300];
        snprintf(key, sizeof key, "%s.type", prefix);
        if (type && !cJSON_IsString(type))
            return json_fail(p, ERR_JSON_TYPE, key, "expected \"noise\" or no type (an image file)");
        if (type && strcmp(type->valuestring, "noise") != 0)
            return json_fail(p, ERR_JSON_VALUE, key, "\"%s\" is not a texture type (known: noise)",
                             type->valuestring);
        if (!(type ? read_noise(p, e, prefix, t) : read_file_texture(p, e, prefix, t)))
            return false;
        (*count)++;
    }
    return true;
}

int texture_desc_find(const TextureDesc *descs, int count, const char *name)
{
    for (int i = 0; i < count; i++)
        if (strcmp(descs[i].name, name) == 0)
            return i;
    return -1;
}

bool textures_load(const TextureDesc *descs, int count, TextureSet *set, uint32_t *indices,
                   const char *scene_path, Error *err)
{
    for (int i = 0; i < count; i++) {
        const TextureDesc *t = &descs[i];
        Error load_err = {0};
        if (t->is_noise)
            indices[i] = texture_set_add_noise(set, &t->noise, t->name, &load_err);
        else if (t->bytes)
            indices[i] = texture_set_add_memory(set, t->bytes, t->size, t->path, t->encoding,
                                                &load_err);
        else
            indices[i] = texture_set_add_encoded(set, t->path, t->encoding, &load_err);
        if (indices[i] != NO_TEXTURE && !t->is_noise)
            indices[i] = texture_set_add_sampled(set, indices[i], &t->sampling, &load_err);
        if (indices[i] == NO_TEXTURE && t->label[0]) {
            error_set(err, load_err.code, scene_path, 0, "%s (%s)", load_err.message, t->label);
            return false;
        }
        if (indices[i] == NO_TEXTURE) {
            error_set(err, load_err.code, scene_path, 0, "%s: textures.%s.file: %s", scene_path,
                      t->name, load_err.message);
            return false;
        }
    }
    return true;
}
