/* SPDX-License-Identifier: MIT */
/* vertex_normals.h: smooth shading for meshes without `vn` (objects[i].smooth): vertex normals
 * weighted by each triangle's area and its angle at the vertex, shared by every corner at the same
 * OBJ position (so UV seams do not show as shading seams). */
#ifndef PT_VERTEX_NORMALS_H
#define PT_VERTEX_NORMALS_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "base/shared_types.h"
#include "io/mesh.h"

/* For the triangles[first_triangle, num_triangles) without TRIANGLE_HAS_NORMALS: computes the
 * normals of their vertices (vertices[first_vertex + i] was created by mesh corner
 * first_corner[i]) and sets TRIANGLE_HAS_NORMALS where all three got one (a vertex whose
 * triangles all have zero area keeps none, and its triangles stay flat). */
bool vertex_normals_smooth(const Mesh *mesh, const float4 *positions, float4 *normals,
                           Triangle *triangles, uint32_t first_triangle, uint32_t num_triangles,
                           uint32_t first_vertex, const uint32_t *first_corner, Error *err);

#endif
