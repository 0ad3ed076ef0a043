/* SPDX-License-Identifier: MIT */
/* analytic_lights.h: the scene's "lights" array (shared/DESIGN.md "Lights"): point, spot,
 * directional and sun lights as the device's AnalyticLight records, and their power for the light
 * table. */
#ifndef PT_ANALYTIC_LIGHTS_H
#define PT_ANALYTIC_LIGHTS_H

#include <cJSON.h>
#include <stdbool.h>

#include "base/shared_types.h"
#include "scene/json.h"

/* Reads the "lights" array into a malloc'ed array (*out, *count; NULL and 0 for an empty array).
 * Errors name the key and value: an unknown type, a missing key, a zero direction, a negative
 * intensity or irradiance, falloff_angle > cone_angle, angles out of range. */
bool analytic_lights_from_json(JsonParser *p, const cJSON *array, AnalyticLight **out, int *count);

/* A sun (angle > 0: a disc of that diameter in degrees) or, with angle 0, a directional light:
 * direction (unit) is where the light travels, irradiance on a surface facing it. */
AnalyticLight analytic_light_sun(const float direction[3], const float irradiance[3], float angle);

/* The light's weight in the light table, in the triangles' unit (power / pi: a triangle weighs
 * area x luminance): point 4 I, spot I x (the profile's solid-angle integral) / pi, directional and
 * sun E x R^2 (E through the scene's bounding disc, pi R^2, over pi); I and E as luminance. */
double analytic_light_weight(const AnalyticLight *light, double bounding_radius2);

#endif
