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
} CameraDesc;

Camera camera_from_desc(const CameraDesc *desc, int width, int height);
/* A camera looking at the box [min, max] from the front (+z), fitting it in a 40-degree view. */
CameraDesc camera_frame_bounds(const float min[3], const float max[3]);

#endif
