// SPDX-License-Identifier: MIT
/* import_json.c: pieces of pt JSON the importers share (scene/import_json.h). */
#include "scene/import_json.h"

#include <math.h>
#include <string.h>

cJSON *import_json_vec3(const double v[3])
{
    /* Rounded through float: the scene reads floats, and the JSON stays short. */
    double f[3] = {(float)v[0], (float)v[1], (float)v[2]};
    return cJSON_CreateDoubleArray(f, 3);
}

cJSON *import_json_colour(const float c[3])
{
    double v[3] = {c[0], c[1], c[2]};
    return import_json_vec3(v);
}

cJSON *import_json_matrix_transform(const double m[16])
{
    cJSON *list = cJSON_CreateArray(), *op = cJSON_CreateObject();
    if (!list || !op) {
        cJSON_Delete(list);
        cJSON_Delete(op);
        return NULL;
    }
    cJSON_AddItemToObject(op, "matrix", cJSON_CreateDoubleArray(m, 16));
    cJSON_AddItemToArray(list, op);
    return list;
}

void import_bounds_add_mesh(ImportBounds *b, const Mesh *mesh, const double m[16])
{
    for (size_t i = 0; i < mesh->num_positions; i++) {
        const float *p = mesh->positions + 3 * i;
        for (int c = 0; c < 3; c++) {
            double w = m[4 * c] * p[0] + m[4 * c + 1] * p[1] + m[4 * c + 2] * p[2] + m[4 * c + 3];
            if (!b->any || w < b->min[c])
                b->min[c] = w;
            if (!b->any || w > b->max[c])
                b->max[c] = w;
        }
        b->any = true;
    }
}

double import_bounds_centre(const ImportBounds *b, double centre[3])
{
    double e2 = 0;
    for (int c = 0; c < 3; c++) {
        centre[c] = b->any ? 0.5 * (b->min[c] + b->max[c]) : 0.0;
        double e = b->any ? b->max[c] - b->min[c] : 0.0;
        e2 += e * e;
    }
    double d = sqrt(e2);
    return d > 0 && isfinite(d) ? d : 1.0;
}

cJSON *import_json_framing_camera(const ImportBounds *b, double fov_y)
{
    double centre[3], eye[3], up[3] = {0, 1, 0};
    double diagonal = import_bounds_centre(b, centre);
    for (int c = 0; c < 3; c++)
        eye[c] = centre[c] + (c == 2 ? 1.5 * diagonal : 0.0);
    cJSON *camera = cJSON_CreateObject();
    if (!camera)
        return NULL;
    cJSON_AddItemToObject(camera, "eye", import_json_vec3(eye));
    cJSON_AddItemToObject(camera, "target", import_json_vec3(centre));
    cJSON_AddItemToObject(camera, "up", import_json_vec3(up));
    cJSON_AddNumberToObject(camera, "fov_y", (float)fov_y);
    return camera;
}
