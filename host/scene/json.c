// SPDX-License-Identifier: MIT
/* json.c: cJSON keeps no positions, so a key's line is found again by walking the text along the
 * key's path (key_line); it keeps the parser a plain library. */
#include "scene/json.h"

#include "base/json_depth.h"

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
    if (!json_depth_check(file, text, strlen(text), err)) /* else cJSON's "malformed" at the limit */
        return NULL;
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

/* ---- Finding a key's line -------------------------------------------------------------------
 * The text has parsed (cJSON accepted it), so a small walker over its structure can follow a key
 * path member by member and element by element: the key found is the one the path means, not
 * the first text that looks like it (an unknown key in objects[2] is not searched for in
 * objects[0]). */

static const char *skip_space(const char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    return s;
}

/* s at a string's opening quote: the character after its closing quote. */
static const char *skip_string(const char *s)
{
    for (s++; *s && *s != '"'; s++)
        if (*s == '\\' && s[1])
            s++;
    return *s ? s + 1 : s;
}

/* s at a value: the character after it. */
static const char *skip_value(const char *s)
{
    if (*s == '"')
        return skip_string(s);
    if (*s != '{' && *s != '[') {
        while (*s && *s != ',' && *s != '}' && *s != ']' && !isspace((unsigned char)*s))
            s++;
        return s;
    }
    int depth = 0;
    do {
        if (*s == '"') {
            s = skip_string(s);
            continue;
        }
        depth += (*s == '{' || *s == '[') - (*s == '}' || *s == ']');
        s++;
    } while (*s && depth > 0);
    return s;
}

/* The object at value: the opening quote of its member `name` (the last one, so that a duplicate
 * key's message points at the duplicate), *member_value its value; NULL when absent. */
static const char *find_member(const char *value, const char *name, size_t len,
                               const char **member_value)
{
    const char *s = skip_space(value), *found = NULL;
    if (*s != '{')
        return NULL;
    for (s = skip_space(s + 1); *s == '"'; s = skip_space(s + 1)) {
        const char *key = s;
        s = skip_space(skip_string(s));
        if (*s != ':')
            return found;
        s = skip_space(s + 1);
        if ((size_t)(s - key) >= len + 2 && strncmp(key + 1, name, len) == 0 && key[1 + len] == '"')
            found = key, *member_value = s;
        s = skip_space(skip_value(s));
        if (*s != ',')
            break;
    }
    return found;
}

/* The array at value: its element `index`, NULL when absent. */
static const char *find_element(const char *value, long index)
{
    const char *s = skip_space(value);
    if (*s != '[')
        return NULL;
    for (s = skip_space(s + 1); *s && *s != ']'; s = skip_space(s + 1)) {
        if (index-- == 0)
            return s;
        s = skip_space(skip_value(s));
        if (*s != ',')
            break;
    }
    return NULL;
}

/* The line of a key path such as "camera.fov_y", "objects[1].obj" or "materials.my.gold.ior" (a
 * name with dots: the longest run of components that is a member). Returns the line of the
 * deepest component found, 0 when none (or no text). */
static int key_line(const char *text, const char *path)
{
    if (!text)
        return 0;
    const char *value = skip_space(text);
    int line = 0;
    while (*path) {
        size_t len = strcspn(path, "[."), try_len = len;
        const char *key = NULL, *member_value = NULL;
        while (try_len && !(key = find_member(value, path, try_len, &member_value)) &&
               path[try_len] == '.')
            try_len += 1 + strcspn(path + try_len + 1, "[.");
        if (len && !key)
            return line;
        if (key) {
            line = json_line_at(text, (size_t)(key - text));
            value = member_value;
            path += try_len;
        }
        while (*path == '[') {
            value = find_element(value, strtol(path + 1, NULL, 10));
            if (!value)
                return line;
            line = json_line_at(text, (size_t)(value - text));
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
            char list[400] = "";
            for (int i = 0; keys[i]; i++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "",
                         keys[i]);
            return json_fail(p, ERR_JSON_UNKNOWN_KEY, key, "unknown key (accepted: %s)", list);
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
