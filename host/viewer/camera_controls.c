// SPDX-License-Identifier: MIT
#include "viewer/camera_controls.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"
#include "scene/camera.h"
#include "scene/camera_json.h"

/* The view's orthonormal frame, as camera_from_desc builds it (right = forward x up). */
typedef struct {
    float forward[3], right[3], up[3];
    float distance; /* eye to target */
} ViewFrame;

static ViewFrame view_frame(const CameraDesc *c)
{
    ViewFrame f;
    for (int i = 0; i < 3; i++)
        f.forward[i] = c->target[i] - c->eye[i];
    f.distance = length3(f.forward);
    normalize3(f.forward);
    cross3(f.forward, c->up, f.right);
    normalize3(f.right);
    cross3(f.right, f.forward, f.up);
    return f;
}

/* ---- Controls ------------------------------------------------------------------------------- */

void viewer_camera_orbit(CameraDesc *c, float yaw, float pitch)
{
    float axis[3] = {c->up[0], c->up[1], c->up[2]};
    float offset[3];
    for (int i = 0; i < 3; i++)
        offset[i] = c->eye[i] - c->target[i];
    float radius = length3(offset);
    if (!normalize3(axis) || !(radius > 0.0f))
        return;
    /* Spherical coordinates about the up axis: polar angle from up, horizontal direction. */
    float along = dot3(offset, axis) / radius;
    float polar = acosf(fminf(fmaxf(along, -1.0f), 1.0f));
    float horizontal[3];
    for (int i = 0; i < 3; i++)
        horizontal[i] = offset[i] - along * radius * axis[i];
    if (!normalize3(horizontal)) {
        ViewFrame f = view_frame(c); /* straight above or below: any direction across up works */
        cross3(axis, f.right, horizontal);
        normalize3(horizontal);
    }
    float side[3];
    cross3(axis, horizontal, side);
    float cos_yaw = cosf(yaw), sin_yaw = sinf(yaw);
    /* Stay a little off the up axis, where the frame (forward x up) would degenerate. */
    const float margin = 0.01f;
    polar = fminf(fmaxf(polar + pitch, margin), 3.14159265f - margin);
    for (int i = 0; i < 3; i++) {
        float h = cos_yaw * horizontal[i] + sin_yaw * side[i];
        c->eye[i] = c->target[i] + radius * (cosf(polar) * axis[i] + sinf(polar) * h);
    }
}

void viewer_camera_pan(CameraDesc *c, float dx, float dy, int height)
{
    ViewFrame f = view_frame(c);
    /* World units per pixel in the plane through the target. */
    float per_pixel = 2.0f * f.distance * tanf(0.5f * c->fov_y * 3.14159265f / 180.0f) /
                      (float)(height > 0 ? height : 1);
    for (int i = 0; i < 3; i++) {
        float delta = per_pixel * (-dx * f.right[i] + dy * f.up[i]);
        c->eye[i] += delta;
        c->target[i] += delta;
    }
}

void viewer_camera_dolly(CameraDesc *c, float steps)
{
    ViewFrame f = view_frame(c);
    float distance = f.distance * powf(0.85f, steps);
    /* Relative floor: the eye approaches the target but never reaches it (eye == target has no
     * view direction). */
    float floor_distance = 1e-4f * fmaxf(length3(c->target), 1.0f);
    distance = fmaxf(distance, floor_distance);
    for (int i = 0; i < 3; i++)
        c->eye[i] = c->target[i] - distance * f.forward[i];
}

void viewer_camera_fly(CameraDesc *c, const float move[3], float distance)
{
    ViewFrame f = view_frame(c);
    float up[3] = {c->up[0], c->up[1], c->up[2]};
    normalize3(up);
    for (int i = 0; i < 3; i++) {
        float delta = distance * (move[0] * f.right[i] + move[1] * up[i] + move[2] * f.forward[i]);
        c->eye[i] += delta;
        c->target[i] += delta;
    }
}

void viewer_camera_pixel_direction(const CameraDesc *c, int width, int height, double x, double y,
                                   float dir[3])
{
    Camera cam = camera_from_desc(c, width, height);
    float tan_half = cam.up.s[3], aspect = cam.forward.s[3];
    float sx = (float)(2.0 * x / width - 1.0) * tan_half * aspect;
    float sy = (float)(1.0 - 2.0 * y / height) * tan_half;
    for (int i = 0; i < 3; i++)
        dir[i] = cam.forward.s[i] + sx * cam.right.s[i] + sy * cam.up.s[i];
    normalize3(dir);
}

float viewer_camera_axis_distance(const CameraDesc *c, const float dir[3], float t)
{
    ViewFrame f = view_frame(c);
    return t * dot3(dir, f.forward);
}

/* ---- JSON ----------------------------------------------------------------------------------- */

bool viewer_camera_parse(const char *json, CameraDesc *c, Error *err)
{
    return camera_desc_parse_option(json, c, err); /* pt render --camera reads it the same way */
}

/* The shortest %g text (6 to 9 digits) that reads back as exactly x: a pasted camera gives the
 * very same view, and round values stay short. */
static void format_float(char out[24], float x)
{
    for (int digits = 6; digits <= 9; digits++) {
        snprintf(out, 24, "%.*g", digits, x);
        if (strtof(out, NULL) == x)
            return;
    }
}

void viewer_camera_format(const CameraDesc *c, char *out, size_t size)
{
    const float *values[] = {&c->eye[0],    &c->eye[1],    &c->eye[2], &c->target[0],
                             &c->target[1], &c->target[2], &c->up[0],  &c->up[1],
                             &c->up[2],     &c->fov_y,     &c->aperture, &c->focus_distance};
    char text[12][24];
    for (int i = 0; i < 12; i++)
        format_float(text[i], *values[i]);
    snprintf(out, size,
             "\"camera\": {\"eye\": [%s, %s, %s], \"target\": [%s, %s, %s], \"up\": [%s, %s, %s], "
             "\"fov_y\": %s, \"aperture\": %s, \"focus_distance\": %s}",
             text[0], text[1], text[2], text[3], text[4], text[5], text[6], text[7], text[8],
             text[9], text[10], text[11]);
}
