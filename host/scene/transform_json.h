/* SPDX-License-Identifier: MIT */
/* transform_json.h: an object's "transform" and "transform_end" (shared/DESIGN.md "Objects"): a
 * list of operations applied in the order written, composed into one Affine. */
#ifndef PT_TRANSFORM_JSON_H
#define PT_TRANSFORM_JSON_H

#include <stdbool.h>

#include "base/transform.h"
#include "scene/json.h"
#include "scene/scene_types.h"

/* The operation list at item (key names it in errors, e.g. "objects[2].transform") composed:
 * M = op_n ... op_2 op_1. Errors: not an array, an operation that is not an object with exactly
 * one known key (translate, scale, rotate, matrix), non-finite numbers, a zero scale, a rotation
 * axis of length 0, a matrix of other than 16 numbers or with a last row other than 0 0 0 1, and a
 * singular or non-finite operation or result. */
bool transform_from_json(JsonParser *p, const cJSON *item, const char *key, Affine *out);

/* objects[index]'s transform and transform_end (identity when absent; transform_end = transform
 * when absent). A transform_end without a shutter interval (has_shutter false) is still checked,
 * then warned about ("no motion blur") and dropped: the object is static at its transform. */
bool object_transform_from_json(JsonParser *p, const cJSON *object, int index, bool has_shutter,
                                ObjectTransform *out);

#endif
