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

ViewBasis view_basis(UpAxis up)
{
    if (up == UP_AXIS_Z)
        return (ViewBasis){.up = {0.0f, 0.0f, 1.0f}, .front = {0.0f, -1.0f, 0.0f}, .right = {1.0f, 0.0f, 0.0f}};
    return (ViewBasis){.up = {0.0f, 1.0f, 0.0f}, .front = {0.0f, 0.0f, 1.0f}, .right = {1.0f, 0.0f, 0.0f}};
}

void view_direction(const ViewBasis *b, float azimuth, float elevation, float out[3])
{
    const float to_radians = 3.14159265f / 180.0f;
    float ca = cosf(azimuth * to_radians), sa = sinf(azimuth * to_radians);
    float ce = cosf(elevation * to_radians), se = sinf(elevation * to_radians);
    for (int i = 0; i < 3; i++)
        out[i] = ce * (ca * b->front[i] + sa * b->right[i]) + se * b->up[i];
}

bool camera_box_is_long(const float min[3], const float max[3], const ViewBasis *b)
{
    float extent_front = 0.0f, extent_right = 0.0f;
    for (int i = 0; i < 3; i++) {
        extent_front += fabsf(b->front[i]) * (max[i] - min[i]);
        extent_right += fabsf(b->right[i]) * (max[i] - min[i]);
    }
    return extent_front > VIEW_LONG_RATIO * extent_right;
}

CameraDesc camera_frame_model(const float min[3], const float max[3], float aspect, const ViewBasis *b)
{
    return camera_frame_model_from(min, max, aspect, b, FRAME_THREE_QUARTER);
}

CameraDesc camera_frame_model_from(const float min[3], const float max[3], float aspect,
                                   const ViewBasis *b, FrameSide side)
{
    const float fov_y = 40.0f, margin = 1.05f;
    float center[3], radius = 0.0f;
    for (int i = 0; i < 3; i++) {
        center[i] = 0.5f * (min[i] + max[i]);
        radius += 0.25f * (max[i] - min[i]) * (max[i] - min[i]);
    }
    radius = sqrtf(radius);
    if (!(radius > 0.0f) || !isfinite(radius))
        radius = 1.0f;
    /* A model much deeper (along the front axis) than wide is seen from its side's 3/4 instead,
     * so a rifle or a cow lying along the front axis is not seen end-on. */
    float azimuth = camera_box_is_long(min, max, b) ? 90.0f - VIEW_AZIMUTH : VIEW_AZIMUTH;
    float elevation = VIEW_ELEVATION;
    if (side == FRAME_BACK)
        azimuth = 180.0f - azimuth;
    if (side == FRAME_FRONT)
        azimuth = elevation = 0.0f;
    float back[3], right[3], up[3];
    view_direction(b, azimuth, elevation, back); /* from the centre toward the eye */
    cross3(b->up, back, right);
    normalize3(right);
    cross3(back, right, up);
    float tan_y = tanf(0.5f * fov_y * 3.14159265f / 180.0f) / margin;
    float tan_x = tan_y * (aspect > 0.0f && isfinite(aspect) ? aspect : 1.0f);
    /* A corner at c (relative to the centre) is in view from distance d when its offsets across
     * the view are within (d - depth toward the eye) x tan: d >= |x| / tan_x + depth. */
    float distance = 0.0f;
    for (int k = 0; k < 8; k++) {
        float c[3] = {(k & 1 ? max[0] : min[0]) - center[0], (k & 2 ? max[1] : min[1]) - center[1],
                      (k & 4 ? max[2] : min[2]) - center[2]};
        float depth = dot3(c, back);
        float need = fmaxf(fabsf(dot3(c, right)) / tan_x, fabsf(dot3(c, up)) / tan_y) + depth;
        distance = fmaxf(distance, need);
    }
    /* The eye stays outside the bounding sphere (no corner behind or beside it). */
    distance = fmaxf(distance, 1.05f * radius);
    if (!isfinite(distance))
        distance = radius / sinf(0.5f * fov_y * 3.14159265f / 180.0f);
    CameraDesc desc = {
        .eye = {center[0] + distance * back[0], center[1] + distance * back[1], center[2] + distance * back[2]},
        .target = {center[0], center[1], center[2]},
        .up = {b->up[0], b->up[1], b->up[2]},
        .fov_y = fov_y,
        .focus_distance = distance,
    };
    return desc;
}
