/* SPDX-License-Identifier: MIT */
/* camera.h: from the scene's camera description to the kernels' Camera. */
#ifndef PT_CAMERA_H
#define PT_CAMERA_H

#include "base/shared_types.h"

typedef struct {
    float eye[3], target[3], up[3];
    float fov_y;          /* degrees, vertical */
    float aperture;       /* lens diameter; 0 = pinhole */
    float focus_distance; /* 0 = distance from eye to target */
    float shutter_open, shutter_close; /* scene time; equal (default 0, 0): no motion blur */
} CameraDesc;

/* Camera coordinates (eye, target, up) must lie within +-CAMERA_COORDINATE_LIMIT: farther out, a
 * float ray origin no longer resolves a scene of any sensible size, and squared distances
 * approach float overflow (1e30 made the view direction infinite). */
#define CAMERA_COORDINATE_LIMIT 1e15

Camera camera_from_desc(const CameraDesc *desc, int width, int height);
/* A camera looking at the box [min, max] from the front (+z), fitting it in a 40-degree view. */
CameraDesc camera_frame_bounds(const float min[3], const float max[3]);

#endif
