/* SPDX-License-Identifier: MIT */
/* default_rig.h: the light a scene gets when it brings none a camera can use (shared/DESIGN.md
 * "First contact"; README "The first image"), built from pt's own features so it renders exactly
 * as a scene that wrote it would:
 *   - a sky: an environment generated in memory, a gradient from a pale horizon to a light blue
 *     zenith over the upper hemisphere and a warm dark grey below the horizon, as in a photo
 *     studio's or Blender's first render: soft fill from every side, so no part of the model is
 *     black, and a background that separates a light grey model from the sky by hue and value;
 *   - a key light: a sun 50 degrees above the horizon, 95 degrees around to the camera's left,
 *     12 degrees wide: shadows with soft edges that fall to the right and back, where the camera
 *     sees them, and a lit side and a shadow side that show the shape (key to fill about 2:1 on a
 *     surface facing up);
 *   - a ground (bare model files only): a square 200 bounding radii wide (its edge is the horizon) at the model's lowest
 *     point, perpendicular to the up axis, diffuse grey 0.3: darker than the default 0.8 material
 *     so the model stands out, and it receives the contact shadow that sets the model down.
 * Every value is a constant here; tests/test_default_rig.c checks the rig's geometry. */
#ifndef PT_DEFAULT_RIG_H
#define PT_DEFAULT_RIG_H

#include <stdbool.h>

#include "base/error.h"
#include "scene/camera.h"
#include "scene/scene_data.h"

#define RIG_SKY_WIDTH 128 /* the generated sky map; the gradient is smooth at this size */
#define RIG_SKY_HEIGHT 64
#define RIG_SUN_AZIMUTH (-95.0f) /* from the camera's azimuth */
#define RIG_SUN_ELEVATION 50.0f
#define RIG_SUN_ANGLE 12.0f
#define RIG_SUN_IRRADIANCE 2.0f
#define RIG_GROUND_ALBEDO 0.3f
#define RIG_GROUND_HALF_SIZE 100.0f /* bounding radii */

/* The sky's radiance in direction d (unit) for the given up axis. */
void rig_sky_radiance(const ViewBasis *b, const float d[3], float out[3]);
/* Builds the sky as data->environment (which must be empty). */
bool rig_add_sky(SceneData *data, const ViewBasis *b, Error *err);
/* The key light placed for the camera, for data->analytic_lights (appended; the array is
 * reallocated). */
bool rig_add_sun(SceneData *data, const ViewBasis *b, const CameraDesc *camera, Error *err);
/* The ground under the scene's world bounds, added to the scene as a mesh of its own material;
 * none when the bounds have no height along the up axis (a flat model is its own
 * ground: nothing is added). Call before the BVH is built. False: out of memory (err set). */
bool rig_add_ground(SceneData *data, const ViewBasis *b, Error *err);
/* Whether the scene has no height along up (less than a thousandth of its bounding radius). */
bool rig_model_is_flat(const SceneData *data, const ViewBasis *b);

#endif
