/* SPDX-License-Identifier: MIT */
/* path_state.cl: kernel parameter lists expanded from the shared lists, so that the host's
 * clSetKernelArg order and every stage's signature cannot drift apart. */

/* restrict: every buffer is a separate cl_mem, so no two parameters alias; NVIDIA can then read
 * the read-only ones through the non-coherent texture path. */
#define PATH_STATE_PARAM(type, name) global type *restrict name,
/* Every PATH_STATE_FIELDS and SAMPLE_STATE_FIELDS buffer, each followed by a comma. */
#define PATH_STATE_PARAMS PATH_STATE_FIELDS(PATH_STATE_PARAM) SAMPLE_STATE_FIELDS(PATH_STATE_PARAM)

#define PATH_STATE_ARG(type, name) name,
/* The same buffers as arguments of a call, each followed by a comma. */
#define PATH_STATE_ARGS PATH_STATE_FIELDS(PATH_STATE_ARG) SAMPLE_STATE_FIELDS(PATH_STATE_ARG)
#define SCENE_ARGS                                                                                 \
    bvh_nodes, bvh_tris, positions, normals, uvs, triangles, material_ids, materials, texels,      \
        textures, lights,

/* The scene's read-only buffers, in the order host/render/wavefront.c sets them; ends with a comma. */
#define SCENE_PARAMS                                                                               \
    const global TraversalNode *restrict bvh_nodes, const global TraversalPrim *restrict bvh_tris, \
        const global float4 *restrict positions, const global float4 *restrict normals,            \
        const global float2 *restrict uvs, const global Triangle *restrict triangles,              \
        const global uint *restrict material_ids, const global Material *restrict materials,       \
        const global uint *restrict texels, const global TextureInfo *restrict textures,           \
        const global LightEntry *restrict lights,

/* The pixel and sample index of window sample k (see PATH_STATE_FIELDS in shared.h). */
inline uint window_pixel(constant RenderParams *p, uint k)
{
    return (p->batch_start + k) % (p->width * p->height);
}

inline uint window_sample(constant RenderParams *p, uint k)
{
    return p->sample_index + (p->batch_start + k) / (p->width * p->height);
}
