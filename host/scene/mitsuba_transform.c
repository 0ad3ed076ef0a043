// SPDX-License-Identifier: MIT
/* mitsuba_transform.c: Mitsuba's <transform> property (translate, scale, rotate, matrix, lookat
 * operations) as an affine map, and an affine map as pt's JSON transform
 * (scene/mitsuba_internal.h). */
#include "scene/mitsuba_internal.h"

#include <math.h>
#include <string.h>

/* "x, y, z" of a lookat/translate/... attribute, or its x/y/z attributes (default `fallback`). */
static bool op_vector(Mitsuba *m, const XmlElement *op, const char *attribute, double fallback,
                      double out[3])
{
    const char *text = xml_attribute(op, attribute);
    if (text)
        return mi_parse_list(m, op, text, out, 3);
    static const char *const axes[] = {"x", "y", "z"};
    for (int i = 0; i < 3; i++) {
        out[i] = fallback;
        if (xml_attribute(op, axes[i]) && !mi_parse_number(m, op, axes[i], &out[i]))
            return false;
    }
    return true;
}

static void normalize(double v[3])
{
    double len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int i = 0; i < 3; i++)
        v[i] /= len;
}

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Mitsuba's look_at: columns (left = up x dir, up' = dir x left, dir, origin). */
static bool look_at(Mitsuba *m, const XmlElement *op, Affine *out)
{
    double origin[3], target[3], up[3] = {0, 1, 0}, dir[3], left[3], new_up[3];
    if (!xml_attribute(op, "origin") || !xml_attribute(op, "target"))
        return mi_fail(m, op, "needs origin=\"x, y, z\" and target=\"x, y, z\"");
    if (!mi_parse_list(m, op, xml_attribute(op, "origin"), origin, 3) ||
        !mi_parse_list(m, op, xml_attribute(op, "target"), target, 3) ||
        (xml_attribute(op, "up") && !mi_parse_list(m, op, xml_attribute(op, "up"), up, 3)))
        return false;
    for (int i = 0; i < 3; i++)
        dir[i] = target[i] - origin[i];
    cross(up, dir, left);
    double dir_len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double left_len = sqrt(left[0] * left[0] + left[1] * left[1] + left[2] * left[2]);
    if (!(dir_len > 0.0) || !(left_len > 1e-9 * dir_len))
        return mi_fail(m, op, "origin equals target, or up is parallel to the view direction");
    normalize(dir);
    normalize(left);
    cross(dir, left, new_up);
    for (int r = 0; r < 3; r++) {
        out->m[r][0] = left[r];
        out->m[r][1] = new_up[r];
        out->m[r][2] = dir[r];
        out->m[r][3] = origin[r];
    }
    return true;
}

/* One operation of a <transform> as an affine map. */
static bool transform_op(Mitsuba *m, const XmlElement *op, Affine *out)
{
    double v[3];
    *out = affine_identity();
    if (strcmp(op->name, "translate") == 0) {
        if (!op_vector(m, op, "value", 0.0, v))
            return false;
        *out = affine_translate(v[0], v[1], v[2]);
    } else if (strcmp(op->name, "scale") == 0) {
        double s;
        if (xml_attribute(op, "value") && !strchr(xml_attribute(op, "value"), ',') &&
            !strchr(xml_attribute(op, "value"), ' ')) {
            if (!mi_parse_number(m, op, "value", &s))
                return false;
            v[0] = v[1] = v[2] = s;
        } else if (!op_vector(m, op, "value", 1.0, v)) {
            return false;
        }
        *out = affine_scale(v[0], v[1], v[2]);
    } else if (strcmp(op->name, "rotate") == 0) {
        double angle;
        if (!op_vector(m, op, "axis", 0.0, v) || !mi_parse_number(m, op, "angle", &angle))
            return false;
        if (!affine_rotate(v, angle, out))
            return mi_fail(m, op, "the rotation axis has zero length");
    } else if (strcmp(op->name, "matrix") == 0) {
        double rows[16];
        const char *value = xml_attribute(op, "value");
        if (!value)
            return mi_fail(m, op, "missing value=\"16 numbers\"");
        if (!mi_parse_list(m, op, value, rows, 16))
            return false;
        if (!affine_from_rows16(rows, out))
            return mi_fail(m, op, "a projective matrix (last row not 0 0 0 1)");
    } else if (strcmp(op->name, "lookat") == 0) {
        return look_at(m, op, out);
    } else {
        return mi_fail(m, op, "not a transform operation (translate, rotate, scale, matrix, lookat)");
    }
    return true;
}

bool mi_transform(Mitsuba *m, const XmlElement *e, const char *name, Affine *out)
{
    const XmlElement *t = mi_prop(m, e, name);
    *out = affine_identity();
    if (!t)
        return true;
    if (strcmp(t->name, "transform"))
        return mi_fail(m, t, "expected <transform name=\"%s\">", name);
    for (int i = 0; i < t->num_children; i++) {
        Affine op;
        if (!transform_op(m, t->children[i], &op))
            return false;
        *out = affine_mul(&op, out); /* Mitsuba: each operation left-multiplies */
    }
    if (!affine_is_finite(out))
        return mi_fail(m, t, "the transform is not finite");
    return true;
}

cJSON *mi_matrix_transform(const Affine *a)
{
    double rows[16] = {0};
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            rows[4 * r + c] = a->m[r][c];
    rows[15] = 1.0;
    cJSON *list = cJSON_CreateArray(), *op = cJSON_CreateObject();
    cJSON_AddItemToArray(list, op);
    cJSON_AddItemToObject(op, "matrix", cJSON_CreateDoubleArray(rows, 16));
    return list;
}
