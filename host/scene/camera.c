// SPDX-License-Identifier: MIT
#include "scene/camera.h"

#include <math.h>

static void normalize3(float v[3])
{
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0.0f)
        v[0] /= len, v[1] /= len, v[2] /= len;
}

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

Camera camera_from_desc(const CameraDesc *desc, int width, int height)
{
    float forward[3] = {desc->target[0] - desc->eye[0], desc->target[1] - desc->eye[1],
                        desc->target[2] - desc->eye[2]};
    float target_distance = sqrtf(forward[0] * forward[0] + forward[1] * forward[1] +
                                  forward[2] * forward[2]);
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
