/* SPDX-License-Identifier: MIT */
/* scene_media.h: the media of SceneData (shared/medium.h, shared/DESIGN.md "Media"): adding one
 * (with its grid's bricks for a grid medium) and turning dielectrics' Beer-Lambert `absorption`
 * into the interior media they are. */
#ifndef PT_SCENE_MEDIA_H
#define PT_SCENE_MEDIA_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "base/transform.h"
#include "io/volume_grid.h"
#include "scene/scene_data.h"

/* Appends medium m (its coefficients, g, emission, type; flags are set here from them) and
 * returns its slot (1 + its index), or 0 with err set (ERR_TOO_LARGE past MEDIUM_COUNT_LIMIT or
 * 2^32 grid entries, ERR_OUT_OF_MEMORY). A grid medium (m->type MEDIUM_GRID) gives its grid and
 * object_to_world, the medium's transform: the bricks are copied, or taken over when they are the
 * scene's first (the grid's arrays then become NULL; volume_grid_free frees what is left), and
 * m->to_index is set to the inverse of object_to_world times the grid's index_to_object; a
 * homogeneous one gives NULL for both. */
uint32_t scene_data_add_medium(SceneData *data, const Medium *m, VolumeGrid *grid,
                               const Affine *object_to_world, Error *err);

/* Gives every dielectric with an `absorption` and no medium interface of its own a homogeneous
 * interior medium of that absorption and no scattering (exterior: the world medium): the image is
 * the Beer-Lambert one it always was. Call after every material and medium is in. */
bool scene_data_media_from_absorption(SceneData *data, Error *err);
/* Whether m is a dielectric with a Beer-Lambert absorption (which is an interior medium). */
bool material_has_absorption(const Material *m);
/* The homogeneous medium of absorption sigma (no scattering): its slot, or 0 with err set. */
uint32_t scene_data_add_absorption_medium(SceneData *data, const float4 *sigma, Error *err);

/* Principled subsurface (shared/DESIGN.md "Media"): gives material `index` (a principled one with
 * subsurface > 0) a homogeneous interior medium of sigma_t = 1 / radius per channel and the
 * single-scattering albedo that makes the walk's diffuse reflectance its base colour (Van de
 * Hulst's inversion, as Cycles), no scattering anisotropy; exterior: the world medium. A textured
 * base colour uses its constant factor (the medium is one for the whole object). Returns the
 * medium's slot, or 0 with err set. */
uint32_t scene_data_add_subsurface_medium(SceneData *data, uint32_t index, const float radius[3],
                                          Error *err);
/* The single-scattering albedo whose random walk in a half-space reflects `colour` (diffuse
 * reflectance in [0, 1]), g = 0: Cycles' subsurface_random_walk_remap. */
float subsurface_albedo(float colour);

/* Whether the kernels must track media (FEATURE_MEDIA): a medium scatters or emits, or an
 * `interface` surface is there to pass through; and whether any medium is a grid
 * (FEATURE_GRID_MEDIA). */
bool scene_data_media_track(const SceneData *data);
bool scene_data_has_grid_media(const SceneData *data);

#endif
