/* SPDX-License-Identifier: MIT */
/* path_state.cl: kernel parameter lists expanded from the shared lists, so that the host's
 * clSetKernelArg order and every stage's signature cannot drift apart. */

/* restrict: every buffer is a separate cl_mem, so no two parameters alias; NVIDIA can then read
 * the read-only ones through the non-coherent texture path. */
#define PATH_STATE_PARAM(type, name) global type *restrict name,
/* Every PATH_STATE_FIELDS, SAMPLE_STATE_FIELDS and PIXEL_STATE_FIELDS buffer, each followed by a
 * comma. */
#define PATH_STATE_PARAMS                                                                          \
    PATH_STATE_FIELDS(PATH_STATE_PARAM) SAMPLE_STATE_FIELDS(PATH_STATE_PARAM)                      \
    PIXEL_STATE_FIELDS(PATH_STATE_PARAM)

#define PATH_STATE_ARG(type, name) name,
/* The same buffers as arguments of a call, each followed by a comma. */
#define PATH_STATE_ARGS                                                                            \
    PATH_STATE_FIELDS(PATH_STATE_ARG) SAMPLE_STATE_FIELDS(PATH_STATE_ARG)                          \
    PIXEL_STATE_FIELDS(PATH_STATE_ARG)

/* Every SCENE_BUFFERS buffer (shared.h), in the order host/render/wavefront.c binds them, each
 * followed by a comma. */
#define SCENE_PARAM(type, name) const global type *restrict name,
#define SCENE_PARAMS SCENE_BUFFERS(SCENE_PARAM)

/* Initialiser of the SceneView over a kernel's SCENE_PARAMS: SceneView scene = SCENE_VIEW; */
#define SCENE_VIEW_INIT(type, name) name,
#define SCENE_VIEW {SCENE_BUFFERS(SCENE_VIEW_INIT)}

/* The pixel and sample index of window sample k (see PATH_STATE_FIELDS in shared.h). Without
 * RENDER_ADAPTIVE the list (then one entry) is never read. */
inline uint window_pixel(constant RenderParams *p, const global uint *active_pixels, uint k)
{
    uint i = (p->window_start + k) % p->window_pixels;
    if (p->flags & RENDER_ADAPTIVE)
        i = active_pixels[i];
    return p->pixel_offset + i;
}

inline uint window_sample(constant RenderParams *p, uint k)
{
    return p->sample_index + (p->window_start + k) / p->window_pixels;
}
