// SPDX-License-Identifier: MIT
/* import_pbrt_params.c: what every part of the pbrt-v4 importer uses: messages that name the file
 * and line (one warning per thing dropped), typed parameter readers with pbrt's defaults, the check
 * that named files stay in the scene's folder, and an object's transform as pt's JSON matrix. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/import_pbrt_internal.h"

/* ---- Messages -------------------------------------------------------------------------------- */

bool pbrt_fail(PbrtImport *imp, int line, const char *fmt, ...)
{
    char what[768];
    va_list args;
    va_start(args, fmt);
    vsnprintf(what, sizeof what, fmt, args);
    va_end(args);
    error_set(imp->err, ERR_FILE_READ, imp->file, line, "%s:%d: %s", imp->file, line, what);
    return false;
}

void pbrt_warn_once(PbrtImport *imp, const char *key, const char *fmt, ...)
{
    for (int i = 0; i < imp->num_warned; i++)
        if (strcmp(imp->warned[i], key) == 0)
            return;
    char (*grown)[160] = realloc(imp->warned, (size_t)(imp->num_warned + 1) * sizeof *grown);
    if (grown) {
        imp->warned = grown;
        snprintf(imp->warned[imp->num_warned++], sizeof *grown, "%s", key);
    }
    char what[768];
    va_list args;
    va_start(args, fmt);
    vsnprintf(what, sizeof what, fmt, args);
    va_end(args);
    warn("%s:%d: %s", imp->file, imp->line, what);
}

void pbrt_warn_unused(PbrtImport *imp, const char *directive, const char *type, PbrtParams *params)
{
    for (int i = 0; i < params->count; i++) {
        if (params->items[i].used)
            continue;
        char key[160];
        snprintf(key, sizeof key, "%s %s %s", directive, type, params->items[i].name);
        pbrt_warn_once(imp, key, "%s \"%s\": parameter \"%s\" is not imported (ignored)", directive,
                       type, params->items[i].name);
    }
}

/* ---- Parameters ----------------------------------------------------------------------------- */

static bool numeric(PbrtImport *imp, PbrtParam *q, PbrtParamType type, int count)
{
    if (q->type != type && !(type == PBRT_FLOAT && q->type == PBRT_INTEGER))
        return pbrt_fail(imp, q->line, "\"%s\": expected type %s, not %s", q->name,
                         pbrt_param_type_name(type), pbrt_param_type_name(q->type));
    if (q->count != count)
        return pbrt_fail(imp, q->line, "\"%s\": expected %d value%s, not %d", q->name, count,
                         count == 1 ? "" : "s", q->count);
    return true;
}

bool pbrt_float(PbrtImport *imp, PbrtParams *p, const char *name, float fallback, float *out)
{
    PbrtParam *q = pbrt_param(p, name);
    *out = fallback;
    if (!q)
        return true;
    if (!numeric(imp, q, PBRT_FLOAT, 1))
        return false;
    *out = (float)q->numbers[0];
    if (!isfinite(*out))
        return pbrt_fail(imp, q->line, "\"%s\": %g is out of range", name, q->numbers[0]);
    return true;
}

bool pbrt_int(PbrtImport *imp, PbrtParams *p, const char *name, int fallback, int *out)
{
    PbrtParam *q = pbrt_param(p, name);
    *out = fallback;
    if (!q)
        return true;
    if (!numeric(imp, q, PBRT_INTEGER, 1))
        return false;
    *out = (int)q->numbers[0];
    return true;
}

bool pbrt_bool(PbrtImport *imp, PbrtParams *p, const char *name, bool fallback, bool *out)
{
    PbrtParam *q = pbrt_param(p, name);
    *out = fallback;
    if (!q)
        return true;
    if (!numeric(imp, q, PBRT_BOOL, 1))
        return false;
    *out = q->numbers[0] != 0.0;
    return true;
}

const char *pbrt_string(PbrtImport *imp, PbrtParams *p, const char *name, bool *ok)
{
    PbrtParam *q = pbrt_param(p, name);
    if (!q)
        return NULL;
    if (q->type != PBRT_STRING || q->count != 1) {
        *ok = pbrt_fail(imp, q->line, "\"%s\": expected one string", name);
        return NULL;
    }
    return q->strings[0];
}

bool pbrt_vec3(PbrtImport *imp, PbrtParams *p, const char *name, const float fallback[3], float out[3])
{
    PbrtParam *q = pbrt_param(p, name);
    for (int i = 0; i < 3; i++)
        out[i] = fallback[i];
    if (!q)
        return true;
    if (!q->numbers || q->count != 3 || q->type == PBRT_SPECTRUM || q->type == PBRT_BOOL)
        return pbrt_fail(imp, q->line, "\"%s\": expected 3 numbers (point3/vector3)", name);
    for (int i = 0; i < 3; i++)
        out[i] = (float)q->numbers[i];
    return true;
}

bool pbrt_check_path(PbrtImport *imp, const char *name, const char *what, int line)
{
    char resolved[1024];
    Error e = {0};
    if (!name[0])
        return pbrt_fail(imp, line, "%s: empty file name", what);
    if (fs_resolve_inside(imp->path, name, what, resolved, sizeof resolved, &e))
        return true;
    error_set(imp->err, e.code, imp->file, line, "%s:%d: %s", imp->file, line, e.message);
    return false;
}

cJSON *pbrt_matrix_json(const PbrtImport *imp, const Affine *ctm)
{
    Affine m = affine_mul(&imp->pt_from_pbrt, ctm);
    double rows[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            rows[4 * r + c] = m.m[r][c];
    cJSON *list = cJSON_CreateArray(), *op = cJSON_CreateObject();
    cJSON_AddItemToObject(op, "matrix", cJSON_CreateDoubleArray(rows, 16));
    cJSON_AddItemToArray(list, op);
    return list;
}
