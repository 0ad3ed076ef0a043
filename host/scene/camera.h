/* SPDX-License-Identifier: MIT */
/* camera.h: from the scene's camera description to the kernels' Camera. */
#ifndef PT_CAMERA_H
#define PT_CAMERA_H

#include <stdbool.h>

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

/* Which way a model file is up, and so where its front is: Y-up (OBJ, PLY and glTF convention;
 * the front faces +z) or Z-up (Blender's and most CAD's; the front faces -y). pt --up. */
typedef enum { UP_AXIS_Y, UP_AXIS_Z } UpAxis;
typedef struct {
    float up[3], front[3], right[3]; /* right-handed: front x right = up */
} ViewBasis;
ViewBasis view_basis(UpAxis up);
/* A point of view around the model: the unit direction from the model toward it, azimuth degrees
 * from the front toward the right, elevation degrees above the horizon. */
void view_direction(const ViewBasis *b, float azimuth, float elevation, float out[3]);

/* The first view of a bare model (shared/DESIGN.md "First contact"): a 3/4 view, as a product
 * photo or Blender's default camera sees an object (VIEW_AZIMUTH to the front's right,
 * VIEW_ELEVATION above the horizon), looking at the box's centre from the distance at which all
 * eight corners of [min, max] fit the 40-degree vertical view and the film's aspect with a 5%
 * margin. A flat box (a plane) is seen from above at the same angle, so it never shows edge-on. A
 * box deeper than VIEW_LONG_RATIO times its width is seen from 90 - VIEW_AZIMUTH instead (its side's
 * 3/4, never end-on). The front is +z for Y-up (glTF's convention; OBJ and PLY have none). */
#define VIEW_LONG_RATIO 1.5f
#define VIEW_AZIMUTH 35.0f
#define VIEW_ELEVATION 15.0f
CameraDesc camera_frame_model(const float min[3], const float max[3], float aspect, const ViewBasis *b);
/* The same from another side: FRAME_BACK from the front's opposite side (the model's front is
 * -front, as Spot's head), FRAME_FRONT straight from the front at the centre's height (a set lit
 * by its own lamps and open to the front, as the Cornell box). */
typedef enum { FRAME_THREE_QUARTER, FRAME_BACK, FRAME_FRONT } FrameSide;
CameraDesc camera_frame_model_from(const float min[3], const float max[3], float aspect,
                                   const ViewBasis *b, FrameSide side);
/* Whether a box is long along the front axis (VIEW_LONG_RATIO). */
bool camera_box_is_long(const float min[3], const float max[3], const ViewBasis *b);

#endif
