/* SPDX-License-Identifier: MIT */
/* camera.h: from the scene's camera description to the kernels' Camera. */
#ifndef PT_CAMERA_H
#define PT_CAMERA_H

#include "scene.h"
#include "shared_types.h"

Camera camera_from_desc(const CameraDesc *desc, int width, int height);
/* A camera looking at the box [min, max] from the front (+z), fitting it in a 40-degree view. */
CameraDesc camera_frame_bounds(const float min[3], const float max[3]);

#endif
