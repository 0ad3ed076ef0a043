/* SPDX-License-Identifier: MIT */
/* lights.h: the alias table over emissive triangles that next-event estimation samples from. */
#ifndef PT_LIGHTS_H
#define PT_LIGHTS_H

#include <stdint.h>

#include "scene/scene_data.h"

typedef struct {
    LightEntry *entries; /* one per light: (instance, emissive triangle), analytic, environment;
                            NULL when there is none */
    uint32_t count;
    float total_power;   /* sum of area * luminance(Ke), plus the environment's: the pdfs' normaliser */
    float env_pick_pdf;  /* the environment entry's probability; 0 without a map */
    AnalyticLight *analytic; /* a copy of the scene's analytic lights, params.w = pick probability */
    uint32_t num_analytic;
} LightTable;

/* Builds the table from every instance's emissive triangles (data->instances in order, each over
 * its mesh's range of data->emissive_triangles: one entry per pair, LightEntry.instance naming the
 * instance), each weighted by its world area (through the instance's to_world: a moving
 * instance's at shutter open) * luminance(Ke); a SceneData without instances counts as one
 * identity instance of every emissive triangle, so one-level scenes get v1's table. Then the
 * environment map if any (one entry, triangle = LIGHT_ENVIRONMENT, weighted by its mean luminance x
 * 4 pi R^2 with R the radius of the scene's bounding sphere: DESIGN's power over pi, as for the
 * triangles), and the analytic lights (LIGHT_ANALYTIC_BASE + index, weighted by
 * analytic_light_weight). Triangles of zero area or zero emission, and dark lights, are left out. */
void light_table_build(LightTable *table, const SceneData *data);
void light_table_free(LightTable *table);

#endif
