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
/* The scene's BVH for the device's layout (dev->bvh_width, bvh_quantized): two levels when asked,
 * which a program built with PT_FEATURE(INSTANCES) needs (session.c asks for data->two_level and
 * builds the program to match; the tests' program has every feature), else one. */
void scene_accel_build(SceneBvh *out, const SceneData *data, const Device *dev, bool two_level);
/* The kernels' instances and motions (cl/shared.h) from the scene's and the BVH's: *instances has
 * data->num_instances entries, *motions max(1, data->num_moving); free() both. */
void scene_instances_for_device(const SceneData *data, const SceneBvh *bvh, Instance **instances,
                                InstanceMotion **motions);
void scene_buffers_release(SceneBuffers *buffers);

/* Binds every scene buffer to kernel arguments first, first + 1, ... in SCENE_BUFFERS order (the
 * kernels' SCENE_PARAMS); returns the index of the argument after them. */
cl_uint scene_buffers_set_args(const SceneBuffers *buffers, cl_kernel kernel, cl_uint first);

#endif
