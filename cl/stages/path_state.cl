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

/* The random-number key of window sample k's path: every stage that draws for the path in a slot
 * (sample_id[slot] = k) draws from this key, so the wavefront and the megakernel agree. */
inline RngKey path_rng_key(constant RenderParams *p, const global uint *active_pixels, uint k)
{
    return render_rng_key(p, window_pixel(p, active_pixels, k), window_sample(p, k));
}

/* The state of a path still on its camera ray (path_depth 1) that need not be stored: a pinhole's
 * rays all start at the eye, with throughput 1 in the camera's medium. generate_camera_rays writes
 * neither lane then, which spares it two of its five scattered 16-byte stores a path (the stage
 * writes into free slots, wherever the paths that ended left them). Stored where a path at depth 1
 * may have moved on from its camera ray or a lens draws the origin: with media (crossing an
 * interface keeps the depth and moves the origin) and bent rays (integrate_geodesic moves both).
 * Readers take the lanes through path_ray_origin and path_throughput, which give the stored value
 * bit for bit where both exist (the megakernels, whose packets read the lanes directly, store
 * them). */
inline bool camera_state_implied(constant RenderParams *p)
{
    return !PT_FEATURE(MEDIA) && !ray_origin_bent(p) && !camera_has_lens(p);
}

/* The throughput lane every camera path starts with: 1, in the camera's medium. */
inline float4 camera_throughput(constant RenderParams *p)
{
    return throughput_pack((float3)(1.0f), medium_state(p->scene.camera_medium, 0u));
}

/* ray_origin[slot] of the path at `depth`, the camera's eye where camera_state_implied. */
inline float4 path_ray_origin(constant RenderParams *p, const global float4 *ray_origin, uint slot,
                              uint depth)
{
    if (depth == 1u && camera_state_implied(p))
        return ray_origin_pack_eta(p, xyz(p->camera.eye), 1.0f);
    return ray_origin[slot];
}

/* throughput[slot] of the path at `depth`, 1 in the camera's medium where camera_state_implied. */
inline float4 path_throughput(constant RenderParams *p, const global float4 *throughput, uint slot,
                              uint depth)
{
    if (depth == 1u && camera_state_implied(p))
        return camera_throughput(p);
    return throughput[slot];
}

/* The hit lane (hit_pack) and the slot's hit_instance as the Hit that surface_at takes. */
inline Hit path_hit(float4 hit, uint instance)
{
    Hit h = {hit_t(hit), hit.y, hit.z, hit_prim(hit), instance};
    return h;
}

/* The work-group's ray counts (extension, shadow) in local memory, one global atomic each per
 * group (intersect_closest, shade_surface, intersect_shadow, megakernel.cl): cleared before the
 * rays are traced, added to counters[COUNTER_EXTENSION_RAYS / COUNTER_SHADOW_RAYS] after. Both
 * contain a barrier, so every work item of the group calls them. */
inline void clear_group_rays(local uint *group_rays)
{
    if (get_local_id(0) == 0)
        group_rays[0] = group_rays[1] = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
}

inline void count_group_rays(local uint *group_rays, uint extension, uint shadow,
                             global uint *counters)
{
    if (extension > 0)
        atomic_add(&group_rays[0], extension);
    if (shadow > 0)
        atomic_add(&group_rays[1], shadow);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0) {
        if (group_rays[0] > 0)
            atomic_add(&counters[COUNTER_EXTENSION_RAYS], group_rays[0]);
        if (group_rays[1] > 0)
            atomic_add(&counters[COUNTER_SHADOW_RAYS], group_rays[1]);
    }
}
