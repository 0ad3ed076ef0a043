/* SPDX-License-Identifier: MIT */
/* mesh_shapes.h: the analytic shapes of other tools' scene files (Mitsuba's sphere, rectangle,
 * disk and cube, pbrt's sphere and disk, the CS184 COLLADA spheres) as triangle meshes in their
 * own object space, with normals and uvs. pt has no analytic primitives: a sphere is tessellated
 * finely enough that its silhouette is smooth at any film size pt renders at (MESH_SPHERE_SEGMENTS
 * around: the largest gap between the polygon and the circle is 1 - cos(pi / 256) = 7.5e-5 of the
 * radius, a tenth of a pixel for a sphere 1300 pixels across), and its interpolated normals are
 * the true sphere's. */
#ifndef PT_MESH_SHAPES_H
#define PT_MESH_SHAPES_H

#include <stdbool.h>

#include "io/mesh.h"

#define MESH_SPHERE_SEGMENTS 256 /* around the equator; half as many rings */

/* A sphere of `radius` at `center`, `segments` >= 3 around (rings: segments / 2, at least 2):
 * u = phi / 2 pi with phi = atan2(y, x) in [0, 2 pi), v = theta / pi from the +z pole.
 * Outward normals. False: out of memory (mesh empty). */
bool mesh_sphere(Mesh *mesh, const float center[3], float radius, int segments);
/* The unit disk in the z = 0 plane, facing +z, `segments` >= 3 around; uv = (r, phi / 2 pi). */
bool mesh_disk(Mesh *mesh, int segments);
/* The square [-1, 1]^2 in the z = 0 plane, facing +z (counter-clockwise seen from +z); uv (0, 0)
 * at (-1, -1), (1, 1) at (1, 1). */
bool mesh_rectangle(Mesh *mesh);
/* The cube [-1, 1]^3, faces outward, shaded flat (no normals); each face's uv spans [0, 1]^2. */
bool mesh_cube(Mesh *mesh);

#endif
