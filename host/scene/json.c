// SPDX-License-Identifier: MIT
/* json.c: cJSON keeps no positions, so a key's line is found again by searching the text for each
 * component of its path; good enough for messages, and it keeps the parser a plain library. */
#include "scene/json.h"

#include <ctype.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int json_line_at(const char *text, size_t offset)
{
    int line = 1;
    for (size_t i = 0; i < offset && text[i]; i++)
        line += text[i] == '\n';
    return line;
}

cJSON *json_parse_text(const char *file, const char *text, Error *err)
{
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    if (!root) {
        size_t offset = end ? (size_t)(end - text) : 0;
        const char *line_start = text + offset;
        while (line_start > text && line_start[-1] != '\n')
            line_start--;
        int line = json_line_at(text, offset), column = (int)(text + offset - line_start) + 1;
        error_set(err, ERR_JSON_SYNTAX, file, line, "%s:%d:%d: malformed JSON", file, line, column);
    }
    return root;
}

/* Finds `"name"` followed by a colon at or after from; returns its offset or -1. */
static long find_key(const char *text, size_t from, const char *name, size_t name_len)
{
    for (const char *s = strchr(text + from, '"'); s; s = strchr(s + 1, '"')) {
        if (strncmp(s + 1, name, name_len) != 0 || s[1 + name_len] != '"')
            continue;
        const char *after = s + 2 + name_len;
        while (isspace((unsigned char)*after))
            after++;
        if (*after == ':')
            return (long)(s - text);
    }
    return -1;
}

/* The line of a key path such as "camera.fov_y" or "objects[1].obj", found by searching the text
 * for each component in turn. An index [n] skips to the n-th match of the next component. Returns
 * the deepest line found, 0 when none. */
static int key_line(const char *text, const char *path)
{
    if (!text)
        return 0;
    size_t from = 0;
    int line = 0, skip = 0;
    while (*path) {
        size_t len = strcspn(path, ".[");
        long at = -1;
        for (int i = 0; i <= skip; i++) {
            at = find_key(text, from, path, len);
            if (at < 0)
                return line;
            from = (size_t)at + len + 2;
        }
        line = json_line_at(text, (size_t)at);
        path += len;
        skip = 0;
        if (*path == '[') {
            skip = atoi(path + 1);
            path += strcspn(path, "]");
            path += *path == ']';
        }
        path += *path == '.';
    }
    return line;
}

bool json_fail(JsonParser *p, ErrorCode code, const char *key, const char *fmt, ...)
{
    char message[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(message, sizeof message, fmt, ap);
    va_end(ap);
    int line = key_line(p->text, key);
    if (line > 0)
        error_set(p->err, code, p->file, line, "%s:%d: %s: %s", p->file, line, key, message);
    else
        error_set(p->err, code, p->file, 0, "%s: %s: %s", p->file, key, message);
    return false;
}

bool json_read_float(JsonParser *p, const cJSON *item, const char *key, float *out)
{
    if (!cJSON_IsNumber(item))
        return json_fail(p, ERR_JSON_TYPE, key, "expected a number");
    double v = item->valuedouble;
    if (!isfinite(v) || fabs(v) > FLT_MAX)
        return json_fail(p, ERR_JSON_VALUE, key, "%g is not a finite number", v);
    *out = (float)v;
    return true;
}

bool json_read_int(JsonParser *p, const cJSON *item, const char *key, int *out)
{
    if (!cJSON_IsNumber(item) || item->valuedouble != floor(item->valuedouble))
        return json_fail(p, ERR_JSON_TYPE, key, "expected an integer");
    double v = item->valuedouble;
    if (!isfinite(v) || v > INT_MAX || v < INT_MIN)
        return json_fail(p, ERR_JSON_VALUE, key, "%g is out of range", v);
    *out = (int)v;
    return true;
}

bool json_read_vec3(JsonParser *p, const cJSON *item, const char *key, float out[3])
{
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != 3)
        return json_fail(p, ERR_JSON_TYPE, key, "expected an array of 3 numbers");
    for (int i = 0; i < 3; i++) {
        const cJSON *e = cJSON_GetArrayItem(item, i);
        if (!cJSON_IsNumber(e))
            return json_fail(p, ERR_JSON_TYPE, key, "expected an array of 3 numbers");
        if (!isfinite(e->valuedouble) || fabs(e->valuedouble) > FLT_MAX)
            return json_fail(p, ERR_JSON_VALUE, key, "element %d (%g) is not a finite number", i,
                             e->valuedouble);
        out[i] = (float)e->valuedouble;
    }
    return true;
}

bool json_path_resolve(JsonParser *p, const char *key, const char *relative, char out[1024])
{
    const char *slash = strrchr(p->file, '/');
    int folder_len = relative[0] == '/' || !slash ? 0 : (int)(slash - p->file) + 1;
    int n = snprintf(out, 1024, "%.*s%s", folder_len, p->file, relative);
    if (n < 0 || n >= 1024)
        return json_fail(p, ERR_JSON_VALUE, key, "path \"%s\" is too long", relative);
    return true;
}

bool json_read_colour(JsonParser *p, const cJSON *item, const char *key, float out[3])
{
    if (cJSON_IsNumber(item)) {
        if (!json_read_float(p, item, key, &out[0]))
            return false;
        out[1] = out[2] = out[0];
    } else if (!json_read_vec3(p, item, key, out)) {
        return false;
    }
    for (int i = 0; i < 3; i++)
        if (!(out[i] >= 0.0f) || !isfinite(out[i]))
            return json_fail(p, ERR_JSON_VALUE, key, "[%g, %g, %g] must be finite and >= 0", out[0],
                             out[1], out[2]);
    return true;
}

bool json_check_object(JsonParser *p, const cJSON *item, const char *path, const char *const *keys)
{
    if (!cJSON_IsObject(item))
        return json_fail(p, ERR_JSON_TYPE, path[0] ? path : "(top level)", "expected an object");
    for (const cJSON *child = item->child; child; child = child->next) {
        char key[256];
        snprintf(key, sizeof key, "%s%s%s", path, path[0] ? "." : "", child->string);
        bool known = false;
        for (int i = 0; keys[i] && !known; i++)
            known = strcmp(child->string, keys[i]) == 0;
        if (!known) {
            char list[256] = "";
            for (int i = 0; keys[i]; i++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "",
                         keys[i]);
            return json_fail(p, ERR_JSON_UNKNOWN_KEY, key, "unknown key (known: %s)", list);
        }
        for (const cJSON *other = item->child; other != child; other = other->next)
            if (strcmp(other->string, child->string) == 0)
                return json_fail(p, ERR_JSON_SYNTAX, key, "duplicate key");
    }
    return true;
}

const cJSON *json_member(const cJSON *object, const char *name)
{
    return cJSON_GetObjectItemCaseSensitive(object, name);
}

bool json_read_member_in_range(JsonParser *p, const cJSON *e, const char *prefix, const char *name,
                               float def, float lo, bool open_lo, float hi, float *out)
{
    char key[256];
    snprintf(key, sizeof key, "%s.%s", prefix, name);
    const cJSON *item = json_member(e, name);
    *out = def;
    if (item && !json_read_float(p, item, key, out))
        return false;
    if (!(open_lo ? *out > lo : *out >= lo) || !(*out <= hi))
        return json_fail(p, ERR_JSON_VALUE, key, "%g is out of range %c%g, %g]", *out,
                         open_lo ? '(' : '[', lo, hi);
    return true;
}

bool json_read_unit_vector(JsonParser *p, const cJSON *item, const char *key, float out[3])
{
    if (!json_read_vec3(p, item, key, out))
        return false;
    double len = sqrt((double)out[0] * out[0] + (double)out[1] * out[1] + (double)out[2] * out[2]);
    if (!(len > 0.0) || !isfinite(len))
        return json_fail(p, ERR_JSON_VALUE, key, "[%g, %g, %g] is not a usable direction (zero length)",
                         out[0], out[1], out[2]);
    for (int i = 0; i < 3; i++)
        out[i] = (float)(out[i] / len);
    return true;
}
