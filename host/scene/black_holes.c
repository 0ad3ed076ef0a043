// SPDX-License-Identifier: MIT
/* black_holes.c: parsing and checking the "black_holes" array. */
#include "scene/black_holes.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The largest length (position coordinate, radius, influence) a hole may have: the geodesic
 * integrator squares lengths and sums three squares in float, which stays finite below 1e18
 * (3e36 < FLT_MAX 3.4e38); a hole at 3e38 made every value it computed inf or NaN. */
#define BLACK_HOLE_MAX_LENGTH 1e18f

/* An optional number (def when absent) that must satisfy lo <= v (lo < v when open_lo) and v <= hi. */
static bool read_number(JsonParser *p, const cJSON *e, const char *name, const char *prefix,
                        float def, float lo, bool open_lo, float hi, float *out)
{
    return json_read_member_in_range(p, e, prefix, name, def, lo, open_lo, hi, out);
}

static double length3(const float v[3])
{
    return sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
}

static bool parse_noise(JsonParser *p, const cJSON *e, const char *prefix, BlackHole *h)
{
    static const char *const keys[] = {"frequency", "octaves", "swirl", NULL};
    if (!json_check_object(p, e, prefix, keys))
        return false;
    float frequency, octaves, swirl;
    if (!read_number(p, e, "frequency", prefix, 4.0f, 0.0f, true, 1e6f, &frequency) ||
        !read_number(p, e, "octaves", prefix, 4.0f, 1.0f, false, 12.0f, &octaves) ||
        !read_number(p, e, "swirl", prefix, 0.0f, -1e4f, false, 1e4f, &swirl))
        return false;
    if (octaves != floorf(octaves)) {
        char key[256];
        snprintf(key, sizeof key, "%s.octaves", prefix);
        return json_fail(p, ERR_JSON_TYPE, key, "expected an integer");
    }
    h->noise = (float4){{frequency, octaves, swirl, 0.0f}};
    return true;
}

static bool parse_disk(JsonParser *p, const cJSON *e, const char *prefix, float mass, BlackHole *h)
{
    static const char *const keys[] = {"normal",      "inner_radius", "outer_radius", "emission",
                                       "temperature", "opacity",      "noise",        NULL};
    if (!json_check_object(p, e, prefix, keys))
        return false;
    char key[192];
    float n[3] = {0.0f, 1.0f, 0.0f};
    const cJSON *item;
    if ((item = json_member(e, "normal"))) {
        snprintf(key, sizeof key, "%s.normal", prefix);
        if (!json_read_unit_vector(p, item, key, n))
            return false;
    }
    float inner, outer, temperature, opacity;
    if (!read_number(p, e, "inner_radius", prefix, 6.0f * mass, 0.0f, true, BLACK_HOLE_MAX_LENGTH, &inner))
        return false;
    snprintf(key, sizeof key, "%s.outer_radius", prefix);
    if (!(item = json_member(e, "outer_radius")))
        return json_fail(p, ERR_JSON_VALUE, key, "missing");
    if (!read_number(p, e, "outer_radius", prefix, 0.0f, 0.0f, true, BLACK_HOLE_MAX_LENGTH, &outer))
        return false;
    snprintf(key, sizeof key, "%s.inner_radius", prefix);
    if (!((double)inner > 2.0 * mass))
        return json_fail(p, ERR_JSON_VALUE, key, "%g is inside the horizon (2M = %g)", inner, 2.0 * mass);
    if (!(inner < outer))
        return json_fail(p, ERR_JSON_VALUE, key, "%g is not below outer_radius %g", inner, outer);
    float emission[3] = {1.0f, 1.0f, 1.0f};
    snprintf(key, sizeof key, "%s.emission", prefix);
    if ((item = json_member(e, "emission")) && !json_read_colour(p, item, key, emission))
        return false;
    if (!read_number(p, e, "temperature", prefix, 0.0f, 0.0f, false, 1e6f, &temperature) ||
        !read_number(p, e, "opacity", prefix, 1.0f, 0.0f, false, 1.0f, &opacity))
        return false;
    if (json_member(e, "temperature") && !(temperature >= 500.0f)) {
        snprintf(key, sizeof key, "%s.temperature", prefix);
        return json_fail(p, ERR_JSON_VALUE, key, "%g K is out of range [500, 1e6]", temperature);
    }
    /* A unit tangent: n crossed with the axis it is least aligned with. */
    float ax[3] = {fabsf(n[0]) < 0.9f ? 1.0f : 0.0f, fabsf(n[0]) < 0.9f ? 0.0f : 1.0f, 0.0f};
    float t[3] = {n[1] * ax[2] - n[2] * ax[1], n[2] * ax[0] - n[0] * ax[2], n[0] * ax[1] - n[1] * ax[0]};
    double tl = length3(t);
    h->normal = (float4){{n[0], n[1], n[2], 0.0f}};
    h->tangent = (float4){{(float)(t[0] / tl), (float)(t[1] / tl), (float)(t[2] / tl), 1.0f}};
    h->radii = (float4){{inner, outer, opacity, temperature}};
    h->emission = (float4){{emission[0], emission[1], emission[2], 0.0f}};
    snprintf(key, sizeof key, "%s.noise", prefix);
    return !(item = json_member(e, "noise")) || parse_noise(p, item, key, h);
}

/* One hole; *keep is false for a hole of mass 0 (dropped). */
static bool parse_hole(JsonParser *p, const cJSON *e, const char *prefix, BlackHole *h, bool *keep)
{
    static const char *const keys[] = {"position", "mass", "disk", "influence_radius", NULL};
    if (!json_check_object(p, e, prefix, keys))
        return false;
    char key[128];
    memset(h, 0, sizeof *h);
    float pos[3], mass;
    const cJSON *item = json_member(e, "position");
    snprintf(key, sizeof key, "%s.position", prefix);
    if (!item)
        return json_fail(p, ERR_JSON_VALUE, key, "missing");
    if (!json_read_vec3(p, item, key, pos))
        return false;
    for (int c = 0; c < 3; c++)
        if (!(fabsf(pos[c]) <= BLACK_HOLE_MAX_LENGTH))
            return json_fail(p, ERR_JSON_VALUE, key, "[%g, %g, %g]: coordinates must lie within "
                             "+-%g (the lensing is integrated in float)", pos[0], pos[1], pos[2],
                             (double)BLACK_HOLE_MAX_LENGTH);
    snprintf(key, sizeof key, "%s.mass", prefix);
    if (!(item = json_member(e, "mass")))
        return json_fail(p, ERR_JSON_VALUE, key, "missing");
    if (!json_read_float(p, item, key, &mass))
        return false;
    if (!(mass >= 0.0f) || !(mass <= 1e30f))
        return json_fail(p, ERR_JSON_VALUE, key, "%g must be >= 0 (and finite)", mass);
    *keep = mass > 0.0f;
    h->centre = (float4){{pos[0], pos[1], pos[2], mass}};
    h->normal = (float4){{0.0f, 1.0f, 0.0f, 0.0f}};
    h->tangent = (float4){{1.0f, 0.0f, 0.0f, 0.0f}};
    snprintf(key, sizeof key, "%s.disk", prefix);
    if ((item = json_member(e, "disk")) && *keep && !parse_disk(p, item, key, mass, h))
        return false;
    float extent = fmaxf((float)BLACK_HOLE_PHOTON_SPHERE * mass, h->radii.s[1]);
    float influence = fmaxf((float)(4.0 * mass / BLACK_HOLE_DEFLECTION_TOLERANCE), extent);
    if ((item = json_member(e, "influence_radius"))) {
        snprintf(key, sizeof key, "%s.influence_radius", prefix);
        if (!json_read_float(p, item, key, &influence))
            return false;
        if (*keep && !(influence > extent))
            return json_fail(p, ERR_JSON_VALUE, key,
                             "%g must lie beyond the photon sphere (3M) and the disk (%g)", influence,
                             extent);
    }
    if (!(influence <= BLACK_HOLE_MAX_LENGTH)) { /* from mass (its default) or as given */
        if (!json_member(e, "influence_radius"))
            snprintf(key, sizeof key, "%s.mass", prefix);
        return json_fail(p, ERR_JSON_VALUE, key, "%g gives an influence radius of %g, over %g (the "
                         "lensing is integrated in float)", json_member(e, "influence_radius") ?
                         (double)influence : (double)mass, (double)influence,
                         (double)BLACK_HOLE_MAX_LENGTH);
    }
    h->normal.s[3] = influence;
    return true;
}

static float hole_extent(const BlackHole *h)
{
    return fmaxf((float)BLACK_HOLE_PHOTON_SPHERE * h->centre.s[3], h->radii.s[1]);
}

bool black_holes_from_json(JsonParser *p, const cJSON *array, BlackHole **out, int *count)
{
    *out = NULL;
    *count = 0;
    if (!cJSON_IsArray(array))
        return json_fail(p, ERR_JSON_TYPE, "black_holes", "expected an array of black holes");
    int n = cJSON_GetArraySize(array);
    if (n == 0)
        return true;
    BlackHole *holes = calloc((size_t)n, sizeof *holes);
    int *index = calloc((size_t)n, sizeof *index); /* JSON index of each kept hole */
    if (!holes || !index)
        die("out of memory");
    int i = 0, kept = 0;
    for (const cJSON *e = array->child; e; e = e->next, i++) {
        char prefix[64];
        bool keep = false;
        snprintf(prefix, sizeof prefix, "black_holes[%d]", i);
        if (!cJSON_IsObject(e) || !parse_hole(p, e, prefix, &holes[kept], &keep)) {
            if (!cJSON_IsObject(e))
                json_fail(p, ERR_JSON_TYPE, prefix, "expected an object");
            free(holes), free(index);
            return false;
        }
        if (keep)
            index[kept++] = i;
    }
    for (int a = 0; a < kept; a++)
        for (int b = a + 1; b < kept; b++) {
            float d[3] = {holes[a].centre.s[0] - holes[b].centre.s[0],
                          holes[a].centre.s[1] - holes[b].centre.s[1],
                          holes[a].centre.s[2] - holes[b].centre.s[2]};
            double dist = length3(d), reach = (double)hole_extent(&holes[a]) + hole_extent(&holes[b]);
            if (dist < reach) {
                char key[64];
                snprintf(key, sizeof key, "black_holes[%d].position", index[b]);
                json_fail(p, ERR_JSON_VALUE, key,
                          "overlaps black_holes[%d]: centres %g apart, their photon spheres or disks "
                          "reach %g",
                          index[a], dist, reach);
                free(holes), free(index);
                return false;
            }
        }
    free(index);
    if (kept == 0) {
        free(holes);
        return true;
    }
    *out = holes;
    *count = kept;
    return true;
}

bool black_holes_check_camera(JsonParser *p, const BlackHole *holes, int count, const float eye[3])
{
    for (int i = 0; i < count; i++) {
        float d[3] = {eye[0] - holes[i].centre.s[0], eye[1] - holes[i].centre.s[1],
                      eye[2] - holes[i].centre.s[2]};
        double horizon = 2.0 * holes[i].centre.s[3];
        if (length3(d) <= horizon)
            return json_fail(p, ERR_JSON_VALUE, "camera.eye",
                             "[%g, %g, %g] is inside the horizon of a black hole (radius 2M = %g "
                             "around [%g, %g, %g])",
                             eye[0], eye[1], eye[2], horizon, holes[i].centre.s[0],
                             holes[i].centre.s[1], holes[i].centre.s[2]);
    }
    return true;
}
