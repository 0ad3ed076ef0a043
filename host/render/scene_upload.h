/* SPDX-License-Identifier: MIT */
/* scene_gpu.h: the flattened scene and its BVH as device buffers, uploaded once. */
#ifndef PT_SCENE_GPU_H
#define PT_SCENE_GPU_H

#include "accel/bvh.h"
#include "device/device.h"
#include "scene/scene_data.h"

typedef struct {
    cl_mem positions, normals, uvs, triangles, material_ids, materials, texels, textures;
    cl_mem bvh_nodes, bvh_tris;
    uint32_t num_bvh_prims; /* entries of bvh_tris (RenderParams.num_bvh_prims) */
    size_t bytes; /* device memory used */
} SceneBuffers;

/* ERR_ALLOC_TOO_LARGE names the buffer that does not fit. */
bool scene_buffers_upload(Device *dev, const SceneData *data, const Bvh *bvh, SceneBuffers *out,
                          Error *err);
void scene_buffers_release(SceneBuffers *buffers);

#endif
