// SPDX-License-Identifier: MIT
#include "scene/camera.h"

#include <math.h>

#include "base/vec3.h"

Camera camera_from_desc(const CameraDesc *desc, int width, int height)
{
    float forward[3] = {desc->target[0] - desc->eye[0], desc->target[1] - desc->eye[1],
                        desc->target[2] - desc->eye[2]};
    float target_distance = length3(forward);
    /* A described camera is checked (camera_json.c): eye != target, up not along the view, all
     * within CAMERA_COORDINATE_LIMIT, so these lengths are finite and not zero. */
    normalize3(forward);
    float right[3], up[3];
    cross3(forward, desc->up, right); /* right-handed: right = forward x up */
    normalize3(right);
    cross3(right, forward, up);
    float focus = desc->focus_distance > 0.0f ? desc->focus_distance : target_distance;
    Camera cam = {
        .eye = {{desc->eye[0], desc->eye[1], desc->eye[2], 0.5f * desc->aperture}},
        .right = {{right[0], right[1], right[2], focus}},
        .up = {{up[0], up[1], up[2], tanf(0.5f * desc->fov_y * 3.14159265f / 180.0f)}},
        .forward = {{forward[0], forward[1], forward[2], (float)width / (float)height}},
    };
    return cam;
}

CameraDesc camera_frame_bounds(const float min[3], const float max[3])
{
    float center[3], radius = 0.0f;
    for (int i = 0; i < 3; i++) {
        center[i] = 0.5f * (min[i] + max[i]);
        float half = 0.5f * (max[i] - min[i]);
        radius += half * half;
    }
    radius = sqrtf(radius);
    if (!(radius > 0.0f))
        radius = 1.0f;
    const float fov_y = 40.0f;
    /* Distance at which the bounding sphere just fits the vertical field of view. */
    float distance = radius / sinf(0.5f * fov_y * 3.14159265f / 180.0f);
    CameraDesc desc = {
        .eye = {center[0], center[1], center[2] + distance},
        .target = {center[0], center[1], center[2]},
        .up = {0.0f, 1.0f, 0.0f},
        .fov_y = fov_y,
        .aperture = 0.0f,
        .focus_distance = distance,
    };
    return desc;
}
