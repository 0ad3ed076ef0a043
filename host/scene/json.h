/* SPDX-License-Identifier: MIT */
/* json.h: reading JSON input (the scene file, the viewer's --camera) with errors that name the
 * input, the line and the key path ("scene.json:7: camera.fov_y: 0 is out of range (0, 180)"). */
#ifndef PT_SCENE_JSON_PARSER_H
#define PT_SCENE_JSON_PARSER_H

#include <cJSON.h>
#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

/* What every check needs to report an error: the input's name (a file, or "--camera"), its text
 * (to find a key's line; NULL: messages carry no line) and err. */
typedef struct {
    const char *file;
    const char *text;
    Error *err;
} JsonParser;

/* The 1-based line of text[offset]. */
int json_line_at(const char *text, size_t offset);

/* Parses text; on malformed JSON records "file:line:column: malformed JSON" and returns NULL. */
cJSON *json_parse_text(const char *file, const char *text, Error *err);

/* Records "file:line: key: message" (the line when the key path, e.g. "objects[1].obj", can be
 * found in the text). Always returns false. */
bool json_fail(JsonParser *p, ErrorCode code, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* Typed values; key is the item's path, for messages. */
bool json_read_float(JsonParser *p, const cJSON *item, const char *key, float *out);
bool json_read_int(JsonParser *p, const cJSON *item, const char *key, int *out);
bool json_read_vec3(JsonParser *p, const cJSON *item, const char *key, float out[3]);
/* A path from the scene file (key names it in errors) joined onto the scene file's folder;
 * absolute paths stay as they are. */
bool json_path_resolve(JsonParser *p, const char *key, const char *relative, char out[1024]);
/* A colour: [r, g, b], or one number for a grey; every channel finite and >= 0. */
bool json_read_colour(JsonParser *p, const cJSON *item, const char *key, float out[3]);

/* Optional member `name` of object e (key "prefix.name" in messages): def when absent; it must
 * lie in [lo, hi], or (lo, hi] with open_lo. */
bool json_read_member_in_range(JsonParser *p, const cJSON *e, const char *prefix, const char *name,
                               float def, float lo, bool open_lo, float hi, float *out);
/* A direction: three finite numbers, not all zero, returned normalised. */
bool json_read_unit_vector(JsonParser *p, const cJSON *item, const char *key, float out[3]);

/* Checks that item is an object whose keys are all in `keys` (NULL-terminated), none twice.
 * path: the object's key path ("" for the top level). */
bool json_check_object(JsonParser *p, const cJSON *item, const char *path, const char *const *keys);

/* The member called name (case-sensitive), NULL when absent. */
const cJSON *json_member(const cJSON *object, const char *name);

#endif
