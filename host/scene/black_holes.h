/* SPDX-License-Identifier: MIT */
/* black_holes.h: the scene's "black_holes" array (README "Black holes"): Schwarzschild holes with
 * optional accretion disks, as the device's BlackHole records (cl/shared/render.h), and the checks
 * that need the whole scene (holes that overlap, a camera inside a horizon). */
#ifndef PT_BLACK_HOLES_H
#define PT_BLACK_HOLES_H

#include <cJSON.h>
#include <stdbool.h>

#include "base/shared_types.h"
#include "scene/json.h"

/* Rays are straight outside a hole's influence sphere. Its default radius is where the deflection
 * still ahead of a ray leaving it, at most about 4M / R (the weak-field 4M / b with b >= R, both
 * halves of the path), drops below this tolerance in radians: R = 4M / tolerance = 2000 M. */
#define BLACK_HOLE_DEFLECTION_TOLERANCE 2e-3
/* A hole's extent for the overlap check: its photon sphere (3M) or its disk, whichever is larger. */
#define BLACK_HOLE_PHOTON_SPHERE 3.0

/* Reads the "black_holes" array into a malloc'ed array (*out, *count; NULL and 0 when empty).
 * Holes of mass 0 are dropped (the scene renders as without them). Errors name the key and value:
 * a negative or non-finite mass, a disk with inner >= outer radius or an inner radius at or inside
 * the horizon (2M), an influence radius inside the disk or the photon sphere, two holes whose
 * extents (photon sphere or disk) overlap. */
bool black_holes_from_json(JsonParser *p, const cJSON *array, BlackHole **out, int *count);

/* Fails, naming "camera.eye", when eye lies at or inside the horizon of one of the holes. */
bool black_holes_check_camera(JsonParser *p, const BlackHole *holes, int count, const float eye[3]);

#endif
