// SPDX-License-Identifier: MIT
/* transform_json.c: see transform_json.h. Each operation is checked on its own (so the message
 * names the operation at fault), then the composition, which can be singular or overflow even
 * when no operation is. */
#include "scene/transform_json.h"

#include "scene/camera.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* n finite numbers from the array item. */
static bool read_numbers(JsonParser *p, const cJSON *item, const char *key, int n, double *out)
{
    if (!cJSON_IsArray(item) || cJSON_GetArraySize(item) != n)
        return json_fail(p, ERR_JSON_TYPE, key, "expected an array of %d numbers", n);
    int i = 0;
    for (const cJSON *e = item->child; e; e = e->next, i++) {
        if (!cJSON_IsNumber(e))
            return json_fail(p, ERR_JSON_TYPE, key, "expected an array of %d numbers", n);
        if (!isfinite(e->valuedouble))
            return json_fail(p, ERR_JSON_VALUE, key, "element %d (%g) is not a finite number", i,
                             e->valuedouble);
        out[i] = e->valuedouble;
    }
    return true;
}

static bool read_number(JsonParser *p, const cJSON *item, const char *key, double *out)
{
    if (!cJSON_IsNumber(item))
        return json_fail(p, ERR_JSON_TYPE, key, "expected a number");
    if (!isfinite(item->valuedouble))
        return json_fail(p, ERR_JSON_VALUE, key, "%g is not a finite number", item->valuedouble);
    *out = item->valuedouble;
    return true;
}

static bool read_scale(JsonParser *p, const cJSON *item, const char *key, Affine *out)
{
    double s[3];
    if (cJSON_IsNumber(item)) {
        if (!read_number(p, item, key, &s[0]))
            return false;
        s[1] = s[2] = s[0];
    } else if (!read_numbers(p, item, key, 3, s)) {
        return false;
    }
    for (int i = 0; i < 3; i++)
        if (s[i] == 0.0)
            return json_fail(p, ERR_JSON_VALUE, key, "[%g, %g, %g] has a zero component (singular)",
                             s[0], s[1], s[2]);
    *out = affine_scale(s[0], s[1], s[2]);
    return true;
}

static bool read_rotate(JsonParser *p, const cJSON *item, const char *key, Affine *out)
{
    static const char *const keys[] = {"axis", "angle", NULL};
    if (!json_check_object(p, item, key, keys))
        return false;
    char axis_key[320], angle_key[320];
    snprintf(axis_key, sizeof axis_key, "%s.axis", key);
    snprintf(angle_key, sizeof angle_key, "%s.angle", key);
    const cJSON *axis_item = json_member(item, "axis"), *angle_item = json_member(item, "angle");
    if (!axis_item)
        return json_fail(p, ERR_JSON_VALUE, axis_key, "missing");
    if (!angle_item)
        return json_fail(p, ERR_JSON_VALUE, angle_key, "missing");
    double axis[3], angle;
    if (!read_numbers(p, axis_item, axis_key, 3, axis) ||
        !read_number(p, angle_item, angle_key, &angle))
        return false;
    if (!affine_rotate(axis, angle, out))
        return json_fail(p, ERR_JSON_VALUE, axis_key, "[%g, %g, %g] has no direction (length 0)",
                         axis[0], axis[1], axis[2]);
    return true;
}

/* m (a matrix operation, or the composition: `what`) must be finite and invertible. */
static bool check_regular(JsonParser *p, const Affine *m, const char *key, const char *what)
{
    double det = affine_det(m);
    Affine inverse;
    if (!affine_is_finite(m) || !isfinite(det))
        return json_fail(p, ERR_JSON_VALUE, key, "%sis not finite (overflow; det %g)", what, det);
    /* 1e300 is finite, but the points it places overflow float (a bound of inf made the BVH and
     * the motion's interpolation loop): the camera's coordinate limit holds for transforms too. */
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            if (fabs(m->m[r][c]) > CAMERA_COORDINATE_LIMIT)
                return json_fail(p, ERR_JSON_VALUE, key, "%shas an entry %g beyond %g (pt's "
                                 "coordinate limit)", what, m->m[r][c], CAMERA_COORDINATE_LIMIT);
    if (!affine_invert(m, &inverse))
        return json_fail(p, ERR_JSON_VALUE, key, "%sis singular or too close to it (det %g)", what,
                         det);
    return true;
}

static bool read_matrix(JsonParser *p, const cJSON *item, const char *key, Affine *out)
{
    double rows[16];
    if (!read_numbers(p, item, key, 16, rows))
        return false;
    if (!affine_from_rows16(rows, out))
        return json_fail(p, ERR_JSON_VALUE, key, "the last row is [%g, %g, %g, %g], not "
                         "[0, 0, 0, 1] (rows first, column vectors: p' = M p)", rows[12], rows[13], rows[14],
                         rows[15]);
    return check_regular(p, out, key, "");
}

/* One operation: an object with exactly one key naming it. */
static bool read_operation(JsonParser *p, const cJSON *op, const char *key, Affine *out)
{
    if (!cJSON_IsObject(op) || !op->child || op->child->next)
        return json_fail(p, ERR_JSON_TYPE, key, "expected an object with one key: translate, "
                         "scale, rotate or matrix");
    const cJSON *value = op->child;
    char op_key[256];
    snprintf(op_key, sizeof op_key, "%s.%.64s", key, value->string);
    if (strcmp(value->string, "translate") == 0) {
        double t[3];
        if (!read_numbers(p, value, op_key, 3, t))
            return false;
        *out = affine_translate(t[0], t[1], t[2]);
        return true;
    }
    if (strcmp(value->string, "scale") == 0)
        return read_scale(p, value, op_key, out);
    if (strcmp(value->string, "rotate") == 0)
        return read_rotate(p, value, op_key, out);
    if (strcmp(value->string, "matrix") == 0)
        return read_matrix(p, value, op_key, out);
    return json_fail(p, ERR_JSON_UNKNOWN_KEY, op_key, "unknown operation (known: translate, scale, "
                     "rotate, matrix)");
}

bool transform_from_json(JsonParser *p, const cJSON *item, const char *key, Affine *out)
{
    if (!cJSON_IsArray(item))
        return json_fail(p, ERR_JSON_TYPE, key, "expected an array of operations");
    Affine m = affine_identity();
    int i = 0;
    for (const cJSON *op = item->child; op; op = op->next, i++) {
        char op_key[128];
        snprintf(op_key, sizeof op_key, "%s[%d]", key, i);
        Affine a;
        if (!read_operation(p, op, op_key, &a))
            return false;
        m = affine_mul(&a, &m); /* the later operation applies after the earlier ones */
    }
    if (!check_regular(p, &m, key, "the composed transform "))
        return false;
    *out = m;
    return true;
}

bool object_transform_from_json(JsonParser *p, const cJSON *object, int index, bool has_shutter,
                                ObjectTransform *out)
{
    char key[64], end_key[64];
    snprintf(key, sizeof key, "objects[%d].transform", index);
    snprintf(end_key, sizeof end_key, "objects[%d].transform_end", index);
    const cJSON *item = json_member(object, "transform");
    const cJSON *end = json_member(object, "transform_end");
    out->transform = affine_identity();
    out->has_end = false;
    if (item && !transform_from_json(p, item, key, &out->transform))
        return false;
    out->transform_end = out->transform;
    if (!end)
        return true;
    Affine m;
    if (!transform_from_json(p, end, end_key, &m))
        return false;
    if (!has_shutter) {
        warn("%s: %s: no motion blur: camera.shutter has no interval (absent or open == close), so "
             "the object is static at its transform", p->file, end_key);
        return true;
    }
    out->transform_end = m;
    out->has_end = true;
    return true;
}
