/* SPDX-License-Identifier: MIT */
/* camera_json.h: the one reader of a camera object, for the scene's "camera" section and the
 * viewer's --camera alike, so both accept and refuse the same cameras with the same messages. */
#ifndef PT_CAMERA_JSON_H
#define PT_CAMERA_JSON_H

#include <stdbool.h>

#include "scene/camera.h"
#include "scene/json.h"

/* Reads the camera object obj (at key path `path`, e.g. "camera") over *inout: keys present
 * replace the values, the others are kept. With require_eye_target (a scene file) eye and target
 * must be present. The result must define a view: fov_y in (0, 180), aperture and
 * focus_distance >= 0, coordinates within +-CAMERA_COORDINATE_LIMIT, eye != target, up not along
 * the view direction; shutter [open, close] finite with open <= close. *inout is unchanged on
 * error. */
bool camera_desc_from_json(JsonParser *p, const cJSON *obj, const char *path,
                           bool require_eye_target, CameraDesc *inout);

/* The --camera option of pt render and pt view: a JSON object like the scene's "camera" (or the
 * fragment `"camera": {...}` that the viewer's C key prints) read over *c with
 * camera_desc_from_json: keys present replace the values, others are kept. Errors are one line
 * that names the key ("--camera: camera.eye: expected an array of 3 numbers") or the position of
 * malformed JSON. *c is unchanged on error. */
bool camera_desc_parse_option(const char *json, CameraDesc *c, Error *err);

#endif
