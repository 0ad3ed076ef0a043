/* SPDX-License-Identifier: MIT */
/* media_json.h: the scene's "media" block (shared/DESIGN.md "Media"): named homogeneous and grid
 * media read into the Medium the kernels take (coefficients already scaled) plus what a grid
 * medium still has to load (its file, grid name and transform). Names are looked up by the
 * top-level "medium", camera.medium and objects' "interior" / "exterior". */
#ifndef PT_MEDIA_JSON_H
#define PT_MEDIA_JSON_H

#include <stdbool.h>
#include <stdint.h>

#include "base/shared_types.h"
#include "base/transform.h"
#include "scene/json.h"
#include "scene/texture_json.h" /* SCENE_NAME_LIMIT */

#define MEDIUM_GRID_NAME_LIMIT 256 /* NanoVDB's grid names are at most 256 bytes with the NUL */

typedef struct {
    char name[SCENE_NAME_LIMIT];
    /* type, sigma_a, sigma_s (homogeneous: times scale; grid: per unit of density, density_scale
     * and sigma_t multiplied in), g in sigma_a.w, emission; flags and grid fields are set when
     * the medium is added (scene_data_add_medium). */
    Medium m;
    char file[1024];                  /* grid: resolved against the scene file */
    char grid[MEDIUM_GRID_NAME_LIMIT]; /* grid: the grid's name; "" = the file's first */
    Affine transform;                 /* grid: "transform" (identity when absent) */
} MediumDesc;

/* Reads the "media" object into a malloc'ed array (*out, *count). */
bool media_from_json(JsonParser *p, const cJSON *obj, MediumDesc **out, int *count);
/* The medium slot (1 + index) of the medium called `name`, or 0. */
uint32_t medium_desc_slot(const MediumDesc *descs, int count, const char *name);
/* The string item at key (a medium's name, e.g. "objects[2].interior") as a slot; *slot is left
 * as it is when item is NULL. Errors: not a string, or no medium of that name. */
bool media_read_slot(JsonParser *p, const cJSON *item, const char *key, const MediumDesc *descs,
                     int count, uint32_t *slot);

#endif
