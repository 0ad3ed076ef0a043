// SPDX-License-Identifier: MIT
/* import_pbrt_transforms.c: pbrt-v4's transform directives (Translate, Scale, Rotate, LookAt,
 * Transform, ConcatTransform), named coordinate systems and the graphics state stack
 * (AttributeBegin/End, TransformBegin/End), for import_pbrt.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/import_pbrt_internal.h"

/* ---- Transforms ----------------------------------------------------------------------------- */

/* n numbers following a transform directive. */
static bool read_numbers(PbrtImport *imp, const char *directive, double *out, int n)
{
    for (int i = 0; i < n; i++) {
        PbrtToken t;
        if (!pbrt_next(imp->reader, &t, imp->err))
            return false;
        if (i == 0 && t.kind == PBRT_TOKEN_OPEN && n == 16)
            if (!pbrt_next(imp->reader, &t, imp->err))
                return false;
        if (t.kind != PBRT_TOKEN_NUMBER)
            return pbrt_fail(imp, imp->line, "%s: expected %d numbers", directive, n);
        out[i] = t.number;
    }
    if (n == 16) { /* the optional closing bracket */
        PbrtToken t;
        if (!pbrt_peek(imp->reader, &t, imp->err))
            return false;
        if (t.kind == PBRT_TOKEN_CLOSE)
            pbrt_next(imp->reader, &t, imp->err);
    }
    return true;
}

/* pbrt's LookAt: camera_from_world, with image-right = cross(up, view direction). */
static bool look_at(PbrtImport *imp, const double v[9], Affine *out)
{
    double dir[3] = {v[3] - v[0], v[4] - v[1], v[5] - v[2]}, up[3] = {v[6], v[7], v[8]};
    double ld = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    double lu = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
    if (!(ld > 0.0) || !(lu > 0.0))
        return pbrt_fail(imp, imp->line, "LookAt: eye and target coincide, or up is zero");
    for (int i = 0; i < 3; i++)
        dir[i] /= ld, up[i] /= lu;
    double right[3] = {up[1] * dir[2] - up[2] * dir[1], up[2] * dir[0] - up[0] * dir[2],
                       up[0] * dir[1] - up[1] * dir[0]};
    double lr = sqrt(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
    if (!(lr > 1e-9))
        return pbrt_fail(imp, imp->line, "LookAt: up and the view direction are parallel");
    for (int i = 0; i < 3; i++)
        right[i] /= lr;
    double new_up[3] = {dir[1] * right[2] - dir[2] * right[1], dir[2] * right[0] - dir[0] * right[2],
                        dir[0] * right[1] - dir[1] * right[0]};
    Affine world_from_camera;
    for (int r = 0; r < 3; r++) {
        world_from_camera.m[r][0] = right[r];
        world_from_camera.m[r][1] = new_up[r];
        world_from_camera.m[r][2] = dir[r];
        world_from_camera.m[r][3] = v[r];
    }
    return affine_invert(&world_from_camera, out) ||
           pbrt_fail(imp, imp->line, "LookAt: singular transform");
}

/* Translate, Scale, Rotate, LookAt, Transform, ConcatTransform; false when the word is none. */
bool pbrt_transform_directive(PbrtImport *imp, const char *word, bool *handled)
{
    static const struct { const char *name; int n; } ops[] = {
        {"Translate", 3}, {"Scale", 3}, {"Rotate", 4}, {"LookAt", 9}, {"Transform", 16},
        {"ConcatTransform", 16}};
    int op = -1;
    for (int i = 0; i < 6; i++)
        if (strcmp(word, ops[i].name) == 0)
            op = i;
    *handled = op >= 0;
    if (op < 0)
        return true;
    double v[16];
    if (!read_numbers(imp, word, v, ops[op].n))
        return false;
    Affine m = affine_identity();
    if (op == 0)
        m = affine_translate(v[0], v[1], v[2]);
    else if (op == 1)
        m = affine_scale(v[0], v[1], v[2]);
    else if (op == 2 && !affine_rotate(v + 1, v[0], &m))
        return pbrt_fail(imp, imp->line, "Rotate: the axis (%g %g %g) has no direction", v[1], v[2], v[3]);
    else if (op == 3 && !look_at(imp, v, &m))
        return false;
    if (op >= 4) { /* pbrt's 16 numbers are the matrix's columns */
        double rows[16];
        for (int r = 0; r < 4; r++)
            for (int c = 0; c < 4; c++)
                rows[4 * r + c] = v[4 * c + r];
        if (!affine_from_rows16(rows, &m))
            return pbrt_fail(imp, imp->line, "%s: projective matrices are not imported (the last "
                             "column must be 0 0 0 1)", word);
    }
    if (!affine_is_finite(&m))
        return pbrt_fail(imp, imp->line, "%s: non-finite transform", word);
    if (imp->ignore_transforms)
        return true;
    imp->state.ctm = op == 4 ? m : affine_mul(&imp->state.ctm, &m);
    return true;
}

bool pbrt_coord_system(PbrtImport *imp, const char *name, bool define)
{
    for (int i = 0; i < imp->num_coord_systems; i++)
        if (strcmp(imp->coord_systems[i].name, name) == 0) {
            if (define)
                imp->coord_systems[i].ctm = imp->state.ctm;
            else
                imp->state.ctm = imp->coord_systems[i].ctm;
            return true;
        }
    if (!define) {
        pbrt_warn_once(imp, name, "CoordSysTransform: no coordinate system \"%s\" (ignored)", name);
        return true;
    }
    void *grown = realloc(imp->coord_systems, (size_t)(imp->num_coord_systems + 1) * sizeof *imp->coord_systems);
    if (!grown || strlen(name) >= SCENE_NAME_LIMIT)
        return pbrt_fail(imp, imp->line, "CoordinateSystem: \"%.40s\": too long or out of memory", name);
    imp->coord_systems = grown;
    snprintf(imp->coord_systems[imp->num_coord_systems].name, SCENE_NAME_LIMIT, "%s", name);
    imp->coord_systems[imp->num_coord_systems++].ctm = imp->state.ctm;
    return true;
}

bool pbrt_push_state(PbrtImport *imp, const char *directive)
{
    if (imp->depth == (int)(sizeof imp->stack / sizeof imp->stack[0]))
        return pbrt_fail(imp, imp->line, "%s: nested more than 64 deep", directive);
    imp->stack[imp->depth++] = imp->state;
    return true;
}

bool pbrt_pop_state(PbrtImport *imp, const char *directive, bool transform_only)
{
    if (imp->depth == 0)
        return pbrt_fail(imp, imp->line, "%s without a matching begin", directive);
    PbrtState saved = imp->stack[--imp->depth];
    if (transform_only)
        imp->state.ctm = saved.ctm;
    else
        imp->state = saved;
    return true;
}
