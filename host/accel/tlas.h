/* SPDX-License-Identifier: MIT */
/* tlas.h: the two-level half of scene_bvh_build (scene_bvh.h): one BLAS per mesh, a TLAS over the
 * instances' boxes, joined into one node array and one prim array. Not for use outside
 * host/accel/. */
#ifndef PT_TLAS_H
#define PT_TLAS_H

#include "accel/scene_bvh.h"

/* Fills out's arrays, per-mesh tables (already allocated for num_meshes), tlas_nodes and build
 * times, for out->width and out->quantized. */
void scene_bvh_build_two_level(SceneBvh *out, const float4 *positions, const Triangle *triangles,
                               const BvhMesh *meshes, uint32_t num_meshes,
                               const BvhInstance *instances, uint32_t num_instances);

#endif
