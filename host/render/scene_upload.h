/* SPDX-License-Identifier: MIT */
/* scene_upload.h: the flattened scene, its BVH and its light table as device buffers, uploaded
 * once. The buffers are cl/shared.h's SCENE_BUFFERS list. */
#ifndef PT_SCENE_UPLOAD_H
#define PT_SCENE_UPLOAD_H

#include "accel/scene_bvh.h"
#include "device/device.h"
#include "scene/scene.h"
#include "scene/scene_data.h"

typedef struct {
#define SCENE_BUFFER_MEMBER(type, name) cl_mem name;
    SCENE_BUFFERS(SCENE_BUFFER_MEMBER)
#undef SCENE_BUFFER_MEMBER
    SceneParams params; /* their counts and totals, as every RenderParams carries them */
    size_t bytes; /* device memory used */
} SceneBuffers;

/* ERR_ALLOC_TOO_LARGE names the buffer that does not fit. */
bool scene_buffers_upload(Device *dev, const SceneData *data, const SceneBvh *bvh,
                          SceneBuffers *out, Error *err);
/* The parameters that the scene fixes: its camera, film size, shutter and background from the
 * description, and the buffers' SceneParams. The wavefront and the AOV pass add their own
 * (seed, depth, flags, ...). */
RenderParams render_params_for_scene(const SceneDesc *desc, const SceneBuffers *buffers);
/* The BVH's levels for the scene: one for one mesh in world space; else flat when every instance
 * is static and their triangles add up to at most FLAT_BVH_TRIANGLE_BUDGET (unless
 * data->keep_two_levels), two otherwise. Flat costs memory per instanced triangle (the BVH and
 * 56 bytes a triangle) and saves the two-level walk's set-up per instance entered and the
 * overlap of instance boxes (bench/README.md "Flat BVHs for instances"). */
#define FLAT_BVH_TRIANGLE_BUDGET (1u << 20)
BvhLevels scene_accel_levels(const SceneData *data);
/* The triangles rays are traced against: the scene's, or every instance's mesh's, counted once
 * per instance. */
uint64_t scene_traced_triangles(const SceneData *data);
/* The program features those levels need (cl/shared/features.h: INSTANCES, TLAS). */
#define BVH_LEVELS_FEATURES(levels)                                                               \
    ((levels) == BVH_TWO_LEVEL ? (ProgramFeatures)(FEATURE_INSTANCES | FEATURE_TLAS)              \
     : (levels) == BVH_FLAT    ? (ProgramFeatures)FEATURE_INSTANCES                               \
                               : 0u)
/* The scene's BVH for the device's layout (dev->bvh_width, bvh_quantized) with the given levels,
 * which the program's features must match (session.c builds both from scene_accel_levels; the
 * tests' program has every feature, so two levels, unless a test builds it otherwise). */
void scene_accel_build(SceneBvh *out, const SceneData *data, const Device *dev, BvhLevels levels);
/* The kernels' instances and motions (cl/shared.h) from the scene's and the BVH's: *instances has
 * data->num_instances entries, *motions max(1, data->num_moving); free() both. */
void scene_instances_for_device(const SceneData *data, const SceneBvh *bvh, Instance **instances,
                                InstanceMotion **motions);
void scene_buffers_release(SceneBuffers *buffers);

/* Binds every scene buffer to kernel arguments first, first + 1, ... in SCENE_BUFFERS order (the
 * kernels' SCENE_PARAMS); returns the index of the argument after them. */
cl_uint scene_buffers_set_args(const SceneBuffers *buffers, cl_kernel kernel, cl_uint first);

#endif
