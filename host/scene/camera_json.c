// SPDX-License-Identifier: MIT
#include "scene/camera_json.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Camera coordinates within +-CAMERA_COORDINATE_LIMIT (json_read_vec3 has already rejected
 * non-finite ones). */
static bool check_coordinates(JsonParser *p, const float v[3], const char *key)
{
    for (int i = 0; i < 3; i++)
        if (fabs(v[i]) > CAMERA_COORDINATE_LIMIT)
            return json_fail(p, ERR_JSON_VALUE, key, "element %d (%g) is too large: camera "
                             "coordinates must lie within +-%g", i, v[i], CAMERA_COORDINATE_LIMIT);
    return true;
}

/* The camera must define a view: eye != target, and up not along the view direction. In double:
 * within the coordinate limit, no product below overflows. */
static bool check_frame(JsonParser *p, const CameraDesc *c, const char *path)
{
    char eye[64], target[64], up_key[64];
    snprintf(eye, sizeof eye, "%s.eye", path);
    snprintf(target, sizeof target, "%s.target", path);
    snprintf(up_key, sizeof up_key, "%s.up", path);
    if (!check_coordinates(p, c->eye, eye) || !check_coordinates(p, c->target, target) ||
        !check_coordinates(p, c->up, up_key))
        return false;
    double dir[3], up[3];
    for (int i = 0; i < 3; i++)
        dir[i] = (double)c->target[i] - (double)c->eye[i], up[i] = c->up[i];
    double dist = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double up_len = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
    if (!(dist > 0.0))
        return json_fail(p, ERR_JSON_VALUE, target, "[%g, %g, %g] is the same point as %s",
                         c->target[0], c->target[1], c->target[2], eye);
    if (!(up_len > 0.0))
        return json_fail(p, ERR_JSON_VALUE, up_key, "[%g, %g, %g] has no direction", c->up[0],
                         c->up[1], c->up[2]);
    double cross[3] = {dir[1] * up[2] - dir[2] * up[1], dir[2] * up[0] - dir[0] * up[2],
                       dir[0] * up[1] - dir[1] * up[0]};
    double sine = sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]) /
                  (dist * up_len);
    if (!(sine > 1e-6))
        return json_fail(p, ERR_JSON_VALUE, up_key, "[%g, %g, %g] is parallel to the view direction",
                         c->up[0], c->up[1], c->up[2]);
    return true;
}

/* Reads the scalar `name` of obj when present, then checks the value: an angle (fov_y) in
 * (0, 180), a length not negative. */
static bool read_scalar(JsonParser *p, const cJSON *obj, const char *path, const char *name,
                        bool is_angle, float *value)
{
    char key[64];
    snprintf(key, sizeof key, "%s.%s", path, name);
    const cJSON *item = json_member(obj, name);
    if (item && !json_read_float(p, item, key, value))
        return false;
    if (is_angle && !(*value > 0.0f && *value < 180.0f))
        return json_fail(p, ERR_JSON_VALUE, key, "%g is out of range (0, 180)", *value);
    if (!is_angle && *value < 0.0f)
        return json_fail(p, ERR_JSON_VALUE, key, "%g is negative", *value);
    return true;
}

static bool read_vector(JsonParser *p, const cJSON *obj, const char *path, const char *name,
                        float value[3])
{
    char key[64];
    snprintf(key, sizeof key, "%s.%s", path, name);
    const cJSON *item = json_member(obj, name);
    return !item || json_read_vec3(p, item, key, value);
}

/* shutter: [open, close] in scene time, finite, open <= close. */
static bool read_shutter(JsonParser *p, const cJSON *obj, const char *path, CameraDesc *c)
{
    const cJSON *item = json_member(obj, "shutter");
    if (!item)
        return true;
    char key[64];
    snprintf(key, sizeof key, "%s.shutter", path);
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != 2)
        return json_fail(p, ERR_JSON_TYPE, key, "expected [open, close]");
    float open, close;
    if (!json_read_float(p, cJSON_GetArrayItem(item, 0), key, &open) ||
        !json_read_float(p, cJSON_GetArrayItem(item, 1), key, &close))
        return false;
    if (open > close)
        return json_fail(p, ERR_JSON_VALUE, key, "[%g, %g]: open is after close", open, close);
    c->shutter_open = open, c->shutter_close = close;
    return true;
}

bool camera_desc_from_json(JsonParser *p, const cJSON *obj, const char *path,
                           bool require_eye_target, CameraDesc *inout)
{
    static const char *const keys[] = {"eye", "target", "up", "fov_y", "aperture", "focus_distance",
                                       "shutter", NULL};
    if (!json_check_object(p, obj, path, keys))
        return false;
    static const char *const required[] = {"eye", "target"};
    for (int i = 0; i < 2 && require_eye_target; i++)
        if (!json_member(obj, required[i])) {
            char key[64];
            snprintf(key, sizeof key, "%s.%s", path, required[i]);
            return json_fail(p, ERR_JSON_VALUE, key, "missing");
        }
    CameraDesc c = *inout;
    bool ok = read_vector(p, obj, path, "eye", c.eye) &&
              read_vector(p, obj, path, "target", c.target) &&
              read_vector(p, obj, path, "up", c.up) &&
              read_scalar(p, obj, path, "fov_y", true, &c.fov_y) &&
              read_scalar(p, obj, path, "aperture", false, &c.aperture) &&
              read_scalar(p, obj, path, "focus_distance", false, &c.focus_distance) &&
              read_shutter(p, obj, path, &c) &&
              check_frame(p, &c, path);
    if (!ok)
        return false;
    *inout = c;
    return true;
}

/* Parses text; the fragment `"camera": {...}` (what the viewer's C key prints) is read as
 * {"camera": {...}}. */
static cJSON *parse_option_text(const char *json, Error *err)
{
    const char *start = json;
    while (isspace((unsigned char)*start))
        start++;
    char *wrapped = NULL;
    if (*start == '"') {
        size_t n = strlen(start);
        wrapped = malloc(n + 3);
        if (!wrapped)
            die("out of memory");
        snprintf(wrapped, n + 3, "{%s}", start);
    }
    const char *text = wrapped ? wrapped : json, *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, true);
    if (!root)
        error_set(err, ERR_JSON_SYNTAX, NULL, 0, "--camera: malformed JSON near '%.24s'",
                  end && *end ? end : "(end of text)");
    free(wrapped);
    return root;
}

bool camera_desc_parse_option(const char *json, CameraDesc *c, Error *err)
{
    cJSON *root = parse_option_text(json, err);
    if (!root)
        return false;
    const cJSON *object = root;
    const cJSON *inner = cJSON_GetObjectItemCaseSensitive(root, "camera");
    if (inner && cJSON_GetArraySize(root) == 1)
        object = inner;
    bool ok = cJSON_IsObject(object);
    if (!ok)
        error_set(err, ERR_JSON_TYPE, NULL, 0,
                  "--camera: expected a JSON object like the scene's camera, e.g. "
                  "{\"eye\": [0, 1, 3.9], \"target\": [0, 1, 0]}");
    /* The scene's camera reader: keys present replace the values, and the same checks with the
     * same messages, named "--camera: camera.<key>: ...". */
    JsonParser p = {.file = "--camera", .text = NULL, .err = err};
    ok = ok && camera_desc_from_json(&p, object, "camera", false, c);
    cJSON_Delete(root);
    return ok;
}
