// SPDX-License-Identifier: MIT
#include "scene/lights.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "scene/analytic_lights.h"

static double cross_length(const double e1[3], const double e2[3])
{
    double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                   e1[0] * e2[1] - e1[1] * e2[0]};
    return sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/* Triangle t's area in world space under to_world (NULL: the identity; the edges as v1 took
 * them, so that one-level scenes keep their table to the bit). */
static double triangle_area(const SceneData *data, const Affine *to_world, uint32_t t)
{
    uint4 v = data->triangles[t].v;
    const float *a = data->positions[v.s[0]].s, *b = data->positions[v.s[1]].s,
                *c = data->positions[v.s[2]].s;
    if (!to_world) {
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        return 0.5 * cross_length(e1, e2);
    }
    double corner[3][3], world[3][3];
    for (int k = 0; k < 3; k++) {
        corner[0][k] = a[k], corner[1][k] = b[k], corner[2][k] = c[k];
    }
    for (int i = 0; i < 3; i++)
        affine_point(to_world, corner[i], world[i]);
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = world[1][k] - world[0][k];
        e2[k] = world[2][k] - world[0][k];
    }
    return 0.5 * cross_length(e1, e2);
}

/* The emissive triangles the table takes from instance i: its mesh's range of
 * emissive_triangles. A SceneData without instances (built by hand, before scene_data_finish)
 * counts as one identity instance of everything. */
static void instance_emitters(const SceneData *data, uint32_t i, uint32_t *first, uint32_t *count,
                              const Affine **to_world)
{
    if (data->num_instances == 0) {
        *first = 0, *count = data->num_emissive, *to_world = NULL;
        return;
    }
    const SceneInstance *inst = &data->instances[i];
    const SceneMesh *mesh = &data->meshes[inst->mesh];
    *first = mesh->first_emissive, *count = mesh->num_emissive;
    *to_world = affine_is_identity(&inst->to_world) ? NULL : &inst->to_world;
}

/* The environment's weight: mean luminance x 4 pi R^2, R the bounding sphere's radius (the flux of
 * the sky through that sphere, over pi). */
static double bounding_radius2(const SceneData *data)
{
    double r2 = 0.0;
    for (int a = 0; a < 3; a++) {
        double half = 0.5 * ((double)data->bounds_max[a] - (double)data->bounds_min[a]);
        r2 += half > 0.0 && isfinite(half) ? half * half : 0.0;
    }
    if (!(r2 > 0.0))
        r2 = 1.0; /* a point-sized scene: any positive radius gives the same pdfs without triangles */
    return r2;
}

static double environment_power(const SceneData *data)
{
    return data->environment.mean_luminance * 4.0 * 3.14159265358979323846 * bounding_radius2(data);
}

void light_table_build(LightTable *table, const SceneData *data)
{
    memset(table, 0, sizeof *table);
    /* One entry per (instance, emissive triangle of its mesh). */
    uint32_t num_instances = data->num_instances ? data->num_instances : 1;
    uint64_t pairs = 0;
    for (uint32_t i = 0; i < num_instances; i++) {
        uint32_t first, n;
        const Affine *to_world;
        instance_emitters(data, i, &first, &n, &to_world);
        pairs += n;
    }
    bool has_env = data->environment.width > 0;
    uint32_t na = data->num_analytic;
    if (pairs == 0 && !has_env && na == 0)
        return;
    /* Entry indices are uint on the device (LightEntry.alias). */
    if (pairs + na + 1 > UINT32_MAX)
        die("too many emissive triangles over all instances for the light table (%llu)",
            (unsigned long long)pairs);
    size_t slots = (size_t)pairs + na + 1;
    double *power = malloc(slots * sizeof *power);
    uint32_t *tris = malloc(slots * sizeof *tris);
    uint32_t *owner = malloc(slots * sizeof *owner);
    if (!power || !tris || !owner)
        die("out of memory for the light table (%llu emitters)", (unsigned long long)pairs);
    double total = 0.0;
    uint32_t count = 0;
    for (uint32_t i = 0; i < num_instances; i++) {
        uint32_t first, n;
        const Affine *to_world; /* a moving instance's at shutter open (cl/light/light_sample.cl) */
        instance_emitters(data, i, &first, &n, &to_world);
        for (uint32_t e = first; e < first + n; e++) {
            uint32_t t = data->emissive_triangles[e];
            double w = triangle_area(data, to_world, t) *
                       data->materials[data->material_ids[t]].emission.s[3];
            if (w > 0.0 && isfinite(w)) {
                power[count] = w;
                owner[count] = i;
                tris[count++] = t;
                total += w;
            }
        }
    }
    for (uint32_t i = 0; i < na; i++) {
        double w = analytic_light_weight(&data->analytic_lights[i], bounding_radius2(data));
        if (w > 0.0 && isfinite(w)) {
            power[count] = w;
            owner[count] = 0;
            tris[count++] = LIGHT_ANALYTIC_BASE + i;
            total += w;
        }
    }
    if (has_env) {
        double w = environment_power(data);
        if (w > 0.0 && isfinite(w)) {
            power[count] = w;
            owner[count] = 0;
            tris[count++] = LIGHT_ENVIRONMENT;
            total += w;
        }
    }
    if (count == 0) {
        free(power), free(tris), free(owner);
        return;
    }
    /* Vose's alias method: scaled probabilities split into small (< 1) and large worklists. */
    LightEntry *entries = calloc(count, sizeof *entries);
    double *scaled = malloc(count * sizeof *scaled);
    uint32_t *small = malloc(count * sizeof *small), *large = malloc(count * sizeof *large);
    if (!entries || !scaled || !small || !large)
        die("out of memory for the light table (%u emitters)", count);
    uint32_t n_small = 0, n_large = 0;
    for (uint32_t i = 0; i < count; i++) {
        scaled[i] = power[i] / total * count;
        entries[i].triangle = tris[i];
        entries[i].instance = owner[i];
        entries[i].pdf = (float)(power[i] / total);
        if (scaled[i] < 1.0)
            small[n_small++] = i;
        else
            large[n_large++] = i;
    }
    while (n_small > 0 && n_large > 0) {
        uint32_t s = small[--n_small], l = large[--n_large];
        entries[s].prob = (float)scaled[s];
        entries[s].alias = l;
        scaled[l] = (scaled[l] + scaled[s]) - 1.0;
        if (scaled[l] < 1.0)
            small[n_small++] = l;
        else
            large[n_large++] = l;
    }
    /* What remains is 1 up to rounding: keep it always. */
    while (n_large > 0) {
        uint32_t l = large[--n_large];
        entries[l].prob = 1.0f, entries[l].alias = l;
    }
    while (n_small > 0) {
        uint32_t s = small[--n_small];
        entries[s].prob = 1.0f, entries[s].alias = s;
    }
    table->entries = entries;
    table->count = count;
    table->total_power = (float)total;
    if (na > 0) {
        table->analytic = calloc(na, sizeof *table->analytic);
        if (!table->analytic)
            die("out of memory for the light table (%u analytic lights)", na);
        memcpy(table->analytic, data->analytic_lights, na * sizeof *table->analytic);
        table->num_analytic = na;
    }
    for (uint32_t i = 0; i < count; i++) {
        if (tris[i] == LIGHT_ENVIRONMENT)
            table->env_pick_pdf = (float)(power[i] / total);
        else if (tris[i] >= LIGHT_ANALYTIC_BASE)
            table->analytic[tris[i] - LIGHT_ANALYTIC_BASE].params.s[3] = (float)(power[i] / total);
    }
    free(power), free(tris), free(owner), free(scaled), free(small), free(large);
}

void light_table_free(LightTable *table)
{
    free(table->entries);
    free(table->analytic);
    memset(table, 0, sizeof *table);
}
