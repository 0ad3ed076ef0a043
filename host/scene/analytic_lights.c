// SPDX-License-Identifier: MIT
/* analytic_lights.c: parsing the "lights" array and each light's power. */
#include "scene/analytic_lights.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static float luminance3(const float c[3]) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

static bool read_color(JsonParser *p, const cJSON *e, const char *name, const char *prefix, float out[3])
{
    char key[96];
    snprintf(key, sizeof key, "%s.%s", prefix, name);
    const cJSON *item = json_member(e, name);
    if (!item)
        return json_fail(p, ERR_JSON_VALUE, key, "missing");
    return json_read_colour(p, item, key, out);
}

/* A unit vector from a non-zero finite one. */
static bool read_direction(JsonParser *p, const cJSON *e, const char *prefix, float out[3])
{
    char key[96];
    snprintf(key, sizeof key, "%s.direction", prefix);
    const cJSON *item = json_member(e, "direction");
    if (!item)
        return json_fail(p, ERR_JSON_VALUE, key, "missing");
    return json_read_unit_vector(p, item, key, out);
}

/* An angle in degrees within [lo, hi] (lo excluded when open_lo), or def when absent. */
static bool read_angle(JsonParser *p, const cJSON *e, const char *name, const char *prefix, float def,
                       float lo, bool open_lo, float hi, float *out)
{
    return json_read_member_in_range(p, e, prefix, name, def, lo, open_lo, hi, out);
}

AnalyticLight analytic_light_sun(const float direction[3], const float irradiance[3], float angle)
{
    AnalyticLight l = {.type = angle > 0.0f ? LIGHT_SUN : LIGHT_DIRECTIONAL};
    l.position = (float4){{direction[0], direction[1], direction[2], 0.0f}};
    l.color = (float4){{irradiance[0], irradiance[1], irradiance[2], luminance3(irradiance)}};
    double half = 0.5 * angle * PI / 180.0;
    if (half > 0.0) {
        /* Radiance L over the disc with L x pi sin^2(half) = E: a surface facing the sun
         * receives exactly E (the cosine-weighted integral over the cone). */
        double s = sin(half);
        l.params.s[0] = (float)cos(half);
        l.params.s[1] = (float)(1.0 / (PI * s * s));
        l.params.s[2] = (float)(1.0 / (2.0 * PI * (1.0 - cos(half))));
    } else {
        l.params.s[0] = 1.0f;
    }
    return l;
}

static bool parse_light(JsonParser *p, const cJSON *e, const char *prefix, AnalyticLight *l)
{
    static const char *const point_keys[] = {"type", "position", "intensity", NULL};
    static const char *const spot_keys[] = {"type",      "position",      "intensity", "direction",
                                            "cone_angle", "falloff_angle", NULL};
    static const char *const directional_keys[] = {"type", "direction", "irradiance", NULL};
    static const char *const sun_keys[] = {"type", "direction", "irradiance", "angle", NULL};
    char key[96];
    snprintf(key, sizeof key, "%s.type", prefix);
    if (!cJSON_IsObject(e))
        return json_fail(p, ERR_JSON_TYPE, prefix, "expected an object");
    const cJSON *type = json_member(e, "type");
    if (!type)
        return json_fail(p, ERR_JSON_VALUE, key, "missing (point, spot, directional or sun)");
    if (!cJSON_IsString(type))
        return json_fail(p, ERR_JSON_TYPE, key, "expected a string (point, spot, directional or sun)");
    const char *t = type->valuestring;
    memset(l, 0, sizeof *l);
    float v[3];
    if (!strcmp(t, "point") || !strcmp(t, "spot")) {
        bool spot = t[0] == 's';
        l->type = spot ? LIGHT_SPOT : LIGHT_POINT;
        if (!json_check_object(p, e, prefix, spot ? spot_keys : point_keys))
            return false;
        const cJSON *pos = json_member(e, "position");
        snprintf(key, sizeof key, "%s.position", prefix);
        if (!pos)
            return json_fail(p, ERR_JSON_VALUE, key, "missing");
        if (!json_read_vec3(p, pos, key, v))
            return false;
        l->position = (float4){{v[0], v[1], v[2], 0.0f}};
        if (!read_color(p, e, "intensity", prefix, v))
            return false;
        l->color = (float4){{v[0], v[1], v[2], luminance3(v)}};
        if (spot) {
            float cone, falloff;
            if (!read_direction(p, e, prefix, v) ||
                !read_angle(p, e, "cone_angle", prefix, 30.0f, 0.0f, true, 180.0f, &cone))
                return false;
            if (!read_angle(p, e, "falloff_angle", prefix, cone, 0.0f, false, 180.0f, &falloff))
                return false;
            if (falloff > cone) {
                snprintf(key, sizeof key, "%s.falloff_angle", prefix);
                return json_fail(p, ERR_JSON_VALUE, key, "%g is larger than cone_angle %g", falloff, cone);
            }
            l->axis = (float4){{v[0], v[1], v[2], 0.0f}};
            l->params.s[0] = (float)(cone * PI / 180.0);
            l->params.s[1] = (float)(falloff * PI / 180.0);
        }
        return true;
    }
    if (!strcmp(t, "directional") || !strcmp(t, "sun")) {
        bool sun = t[0] == 's';
        l->type = sun ? LIGHT_SUN : LIGHT_DIRECTIONAL;
        if (!json_check_object(p, e, prefix, sun ? sun_keys : directional_keys))
            return false;
        if (!read_direction(p, e, prefix, v))
            return false;
        l->position = (float4){{v[0], v[1], v[2], 0.0f}};
        if (!read_color(p, e, "irradiance", prefix, v))
            return false;
        float irradiance[3] = {v[0], v[1], v[2]};
        float angle = 0.0f;
        if (sun && !read_angle(p, e, "angle", prefix, 0.0f, 0.0f, false, 180.0f, &angle))
            return false;
        float direction[3] = {l->position.s[0], l->position.s[1], l->position.s[2]};
        *l = analytic_light_sun(direction, irradiance, angle);
        l->type = sun ? LIGHT_SUN : LIGHT_DIRECTIONAL;
        return true;
    }
    return json_fail(p, ERR_JSON_VALUE, key, "unknown light type \"%s\" (point, spot, directional or sun)", t);
}

bool analytic_lights_from_json(JsonParser *p, const cJSON *array, AnalyticLight **out, int *count)
{
    *out = NULL;
    *count = 0;
    if (!cJSON_IsArray(array))
        return json_fail(p, ERR_JSON_TYPE, "lights", "expected an array of lights");
    int n = cJSON_GetArraySize(array);
    if (n == 0)
        return true;
    AnalyticLight *lights = calloc((size_t)n, sizeof *lights);
    if (!lights)
        return json_fail(p, ERR_TOO_LARGE, "lights", "out of memory");
    int i = 0;
    for (const cJSON *e = array->child; e; e = e->next, i++) {
        char prefix[64];
        snprintf(prefix, sizeof prefix, "lights[%d]", i);
        if (!parse_light(p, e, prefix, &lights[i])) {
            free(lights);
            return false;
        }
    }
    *out = lights;
    *count = n;
    return true;
}

double analytic_light_weight(const AnalyticLight *l, double bounding_radius2)
{
    double lum = l->color.s[3];
    switch (l->type) {
    case LIGHT_POINT:
        return 4.0 * lum;
    case LIGHT_SPOT: {
        /* 2 pi x the integral of the profile x sin over the cone: 1 inside falloff f, then
         * (c - t) / (c - f) up to the cone c, which integrates to 2 pi (1 - (sin c - sin f) / (c - f)). */
        double c = l->params.s[0], f = l->params.s[1];
        double solid = c - f > 1e-6 ? 2.0 * PI * (1.0 - (sin(c) - sin(f)) / (c - f))
                                    : 2.0 * PI * (1.0 - cos(c));
        return lum * solid / PI;
    }
    default:
        return lum * bounding_radius2;
    }
}
