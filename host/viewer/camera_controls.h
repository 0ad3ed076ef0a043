/* SPDX-License-Identifier: MIT */
/* viewer_camera.h: the viewer's camera controls as pure functions on the scene's CameraDesc (orbit,
 * pan, dolly, fly, the ray under a pixel), and the camera as JSON: parsed from --camera, printed by
 * the 'C' key in the scene format so it can be pasted into a scene file. */
#ifndef PT_VIEWER_CAMERA_H
#define PT_VIEWER_CAMERA_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"
#include "scene/scene.h"

/* Turns the eye around the target: yaw about the camera's up axis, pitch toward or away from it
 * (radians). The distance to the target is kept and the view never looks straight along up. */
void viewer_camera_orbit(CameraDesc *c, float yaw, float pitch);

/* Moves eye and target together across the view so that a point at the target's depth follows a
 * cursor moved by (dx, dy) pixels (y down) on a film `height` pixels tall. */
void viewer_camera_pan(CameraDesc *c, float dx, float dy, int height);

/* Moves the eye toward the target (steps > 0) or away; each step is 15% of the distance. The eye
 * never reaches the target. */
void viewer_camera_dolly(CameraDesc *c, float steps);

/* Moves eye and target together by `distance` along (right, up, forward) weights in move[]:
 * right and forward from the view, up along the camera's up vector. */
void viewer_camera_fly(CameraDesc *c, const float move[3], float distance);

/* The unit direction of the ray through the centre of film pixel (x, y) (fractional, y down), as
 * cl/core/camera.cl computes it for a pinhole. */
void viewer_camera_pixel_direction(const CameraDesc *c, int width, int height, double x, double y,
                                   float dir[3]);

/* Distance along the view axis of a point at ray distance t in direction dir (for focus). */
float viewer_camera_axis_distance(const CameraDesc *c, const float dir[3], float t);

/* Reads a JSON object like the scene's "camera" (or the fragment `"camera": {...}` that
 * viewer_camera_format prints) over *c: keys present replace the values, others are kept.
 * Errors name the key (ERR_JSON_UNKNOWN_KEY, ERR_JSON_TYPE, ERR_JSON_VALUE) or the position of
 * malformed JSON (ERR_JSON_SYNTAX). *c is unchanged on error. */
bool viewer_camera_parse(const char *json, CameraDesc *c, Error *err);

/* `"camera": {"eye": [...], ...}` on one line, ready to paste into a scene. */
void viewer_camera_format(const CameraDesc *c, char *out, size_t size);

#endif
