// SPDX-License-Identifier: MIT
/* default_rig.c: the sky, key light and ground of the default rig (default_rig.h says why each). */
#include "scene/default_rig.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"
#include "io/mesh_shapes.h"
#include "scene/analytic_lights.h"

#define PI_F 3.14159265f

/* Radiance: horizon near white, zenith a light blue (the sky of an overcast-bright day, not a
 * saturated one that would tint the model), below the horizon a warm dark grey. */
static const float sky_horizon[3] = {0.95f, 0.95f, 0.93f};
static const float sky_zenith[3] = {0.42f, 0.55f, 0.78f};
static const float sky_below[3] = {0.22f, 0.21f, 0.20f};
#define RIG_SKY_SCALE 0.55f

void rig_sky_radiance(const ViewBasis *b, const float d[3], float out[3])
{
    float t = dot3(d, b->up);
    for (int i = 0; i < 3; i++) {
        if (t >= 0.0f) {
            /* sqrt: the blue comes in quickly above the horizon, as in a real sky. */
            float s = sqrtf(fminf(t, 1.0f));
            out[i] = RIG_SKY_SCALE * (sky_horizon[i] + s * (sky_zenith[i] - sky_horizon[i]));
        } else {
            /* A short blend below the horizon, so the horizon is not a hard line. */
            float s = fminf(-t * 8.0f, 1.0f);
            out[i] = RIG_SKY_SCALE * (sky_horizon[i] + s * (sky_below[i] - sky_horizon[i]));
        }
    }
}

bool rig_add_sky(SceneData *data, const ViewBasis *b, Error *err)
{
    float *rgb = malloc((size_t)RIG_SKY_WIDTH * RIG_SKY_HEIGHT * 3 * sizeof *rgb);
    if (!rgb) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for the default sky");
        return false;
    }
    /* Each texel's direction by shared/DESIGN.md "Environment" (rotation 0): u = 0.5 +
     * atan2(x, -z) / 2 pi, v = acos(y) / pi, at the texel's centre. */
    for (int j = 0; j < RIG_SKY_HEIGHT; j++) {
        float theta = PI_F * ((float)j + 0.5f) / RIG_SKY_HEIGHT;
        for (int i = 0; i < RIG_SKY_WIDTH; i++) {
            float phi = 2.0f * PI_F * (((float)i + 0.5f) / RIG_SKY_WIDTH - 0.5f);
            float d[3] = {sinf(theta) * sinf(phi), cosf(theta), -sinf(theta) * cosf(phi)};
            rig_sky_radiance(b, d, rgb + 3 * ((size_t)j * RIG_SKY_WIDTH + i));
        }
    }
    bool ok = environment_build(&data->environment, rgb, RIG_SKY_WIDTH, RIG_SKY_HEIGHT, 1.0f, 0.0f,
                                "the default sky", err);
    free(rgb);
    return ok;
}

bool rig_add_sun(SceneData *data, const ViewBasis *b, const CameraDesc *camera, Error *err)
{
    AnalyticLight *lights = realloc(data->analytic_lights, (data->num_analytic + 1) * sizeof *lights);
    if (!lights) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for the default light");
        return false;
    }
    data->analytic_lights = lights;
    float toward[3], travel[3];
    /* The camera's azimuth around the up axis (0 when it looks straight down or up). */
    float back[3] = {camera->eye[0] - camera->target[0], camera->eye[1] - camera->target[1],
                     camera->eye[2] - camera->target[2]};
    float x = dot3(back, b->right), y = dot3(back, b->front);
    float camera_azimuth = x != 0.0f || y != 0.0f ? atan2f(x, y) * 180.0f / PI_F : 0.0f;
    view_direction(b, camera_azimuth + RIG_SUN_AZIMUTH, RIG_SUN_ELEVATION, toward);
    for (int i = 0; i < 3; i++)
        travel[i] = -toward[i];
    /* Slightly warm, as sunlight against the blue fill. */
    const float irradiance[3] = {RIG_SUN_IRRADIANCE * 1.0f, RIG_SUN_IRRADIANCE * 0.96f,
                                 RIG_SUN_IRRADIANCE * 0.90f};
    lights[data->num_analytic++] = analytic_light_sun(travel, irradiance, RIG_SUN_ANGLE);
    return true;
}

/* The merged static mesh alone (mesh 0 placed once, unmoved, holding every triangle): the ground
 * joins it, so a bare model stays a one-level scene (no instance traversal for the ground). */
static bool one_static_mesh(const SceneData *data)
{
    return data->num_meshes == 1 && data->num_instances == 1 && !data->instances[0].moving &&
           affine_is_identity(&data->instances[0].to_world) &&
           data->meshes[0].num_triangles == data->num_triangles;
}

/* The scene's bounding radius and its lowest and highest points along up. */
static float extent_along(const SceneData *data, const ViewBasis *b, float *lowest, float *highest)
{
    float radius = 0.0f;
    *lowest = INFINITY, *highest = -INFINITY;
    for (int i = 0; i < 3; i++) {
        float half = 0.5f * (data->bounds_max[i] - data->bounds_min[i]);
        radius += half * half;
    }
    for (int k = 0; k < 8; k++) {
        float c[3] = {k & 1 ? data->bounds_max[0] : data->bounds_min[0],
                      k & 2 ? data->bounds_max[1] : data->bounds_min[1],
                      k & 4 ? data->bounds_max[2] : data->bounds_min[2]};
        *lowest = fminf(*lowest, dot3(c, b->up));
        *highest = fmaxf(*highest, dot3(c, b->up));
    }
    return sqrtf(radius);
}

bool rig_model_is_flat(const SceneData *data, const ViewBasis *b)
{
    float lowest, highest, radius = extent_along(data, b, &lowest, &highest);
    return !(highest - lowest > 1e-3f * radius) || !isfinite(radius);
}

bool rig_add_ground(SceneData *data, const ViewBasis *b, Error *err)
{
    if (rig_model_is_flat(data, b))
        return true; /* the model is its own ground */
    float lowest, highest, center[3], radius = extent_along(data, b, &lowest, &highest);
    for (int i = 0; i < 3; i++)
        center[i] = 0.5f * (data->bounds_min[i] + data->bounds_max[i]);
    Mesh mesh = {0};
    ObjMaterial *ground = calloc(1, sizeof *ground);
    if (!ground || !mesh_rectangle(&mesh)) {
        free(ground);
        mesh_free(&mesh);
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for the default ground");
        return false;
    }
    snprintf(ground->name, sizeof ground->name, "pt default ground");
    for (int i = 0; i < 3; i++)
        ground->kd[i] = RIG_GROUND_ALBEDO, ground->tf[i] = 1.0f;
    ground->ni = ground->d = ground->bump_scale = 1.0f;
    ground->illum = -1;
    mesh.materials = ground;
    mesh.num_materials = 1;
    for (size_t t = 0; t < mesh.num_triangles; t++)
        mesh.material_ids[t] = 0;
    /* The rectangle's x, y, z become front, right and up (front x right = up: no mirroring),
     * scaled to the ground's size, its centre under the model's at the lowest point. */
    double size = (double)RIG_GROUND_HALF_SIZE * radius, rows[16] = {0};
    float along = dot3(center, b->up);
    for (int i = 0; i < 3; i++) {
        rows[4 * i + 0] = size * b->front[i];
        rows[4 * i + 1] = size * b->right[i];
        rows[4 * i + 2] = b->up[i];
        rows[4 * i + 3] = center[i] + (lowest - along) * b->up[i];
    }
    rows[15] = 1.0;
    Affine place;
    affine_from_rows16(rows, &place);
    bool merge = one_static_mesh(data);
    uint32_t first_triangle = data->num_triangles, first_vertex = data->num_vertices;
    ObjectOptions options = {.material = NO_MATERIAL};
    bool ok = scene_data_append_object(data, &mesh, "the default ground", &options, NULL, err);
    mesh_free(&mesh);
    if (!ok)
        return false;
    scene_data_bake_transform(data, first_triangle, first_vertex, &place);
    if (merge) {
        data->num_meshes = data->num_instances = 0;
        first_triangle = first_vertex = 0;
    }
    SceneInstance whole = {.mesh = data->num_meshes, .object = -1, .to_world = affine_identity()};
    if (!scene_data_add_mesh(data, first_triangle, first_vertex, err) ||
        !scene_data_add_instance(data, &whole, err))
        return false;
    scene_data_finish_instances(data);
    return true;
}
