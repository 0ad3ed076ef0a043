/* SPDX-License-Identifier: MIT */
/* intersect_shadow: resolves the next-event shadow rays that shade_surface queued.
 * Reads: active[0..n_active), shadow_origin, shadow_direction (w: as_float of the bounce that
 * queued it, for the cut-out decisions), shadow_contribution (w = 1: a ray waits), sample_id. Writes: radiance[sample_id] += contribution when unoccluded;
 * shadow_contribution.w = 0.
 * Runs before compaction: a path killed by Russian roulette may still have a shadow ray.
 * Launched over the active list; with RENDER_SHADOW_QUEUE only the first shadow_count[0] items
 * work, on the slots that shade_surface appended to shadow_queue.
 * counters[COUNTER_SHADOW_RAYS] counts the rays traced (one global atomic per work-group).
 * intersect_shadow_brute_force: the same without the BVH (see intersect_closest.cl). */

#define INTERSECT_SHADOW_PARAMS                                                                    \
    constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS const global uint *active,            \
        uint n_active, global uint *counters, const global uint *shadow_queue,                     \
        const global uint *shadow_count

/* Traces the shadow ray that slot's path waits for (shadow_contribution.w != 0) and adds its
 * contribution to radiance[sample_id] when unoccluded; false, touching nothing, when none waits.
 * brute_force is a constant at every call. Shared by the kernels below and megakernel.cl. */
PT_INLINE bool connect_path(constant RenderParams *p, const SceneView *scene,
                            PATH_STATE_PARAMS uint slot, bool brute_force)
{
    float4 contribution = shadow_contribution[slot];
    if (contribution.w == 0.0f)
        return false;
    uint brute_count = SCENE_BRUTE_FORCE_COUNT(p); /* scene_trace.cl */
    float4 origin = shadow_origin[slot];
    float3 d = xyz(shadow_direction[slot]);
    float time = PT_FEATURE(MOTION) ? path_time[slot] : 0.0f;
    bool occluded;
    if (PT_FEATURE(CUTOUT)) {
        /* shade_surface put the queuing bounce in shadow_direction.w: its DIM_SHADOW_OPACITY
         * stream decides the cut-out pass-throughs. */
        uint k = sample_id[slot];
        RngKey key = rng_path_key(window_pixel(p, active_pixels, k), window_sample(p, k), p->seed);
        uint bounce = as_uint(shadow_direction[slot].w);
        occluded = trace_occluded_through(scene, brute_count, xyz(origin), d, origin.w, time,
                                          brute_force,
                                          rng_bounce_bits(key, bounce, DIM_SHADOW_OPACITY));
    } else {
        occluded = brute_force ? scene_brute_force(scene, brute_count, xyz(origin), d, 0.0f,
                                                   origin.w, true, time).prim != HIT_NONE
                               : scene_occluded(scene, brute_count, xyz(origin), d, 0.0f,
                                                origin.w, time);
    }
    if (!occluded)
        radiance[sample_id[slot]] += (float4)(xyz(contribution), 0.0f);
    shadow_contribution[slot] = (float4)(0.0f);
    return true;
}

/* The work-group's share of either kernel; brute_force is a constant in each. */
PT_INLINE void intersect_shadow_group(constant RenderParams *p, const SceneView *scene,
                                      PATH_STATE_PARAMS const global uint *active, uint n_active,
                                      global uint *counters, const global uint *shadow_queue,
                                      const global uint *shadow_count, local uint *group_rays,
                                      bool brute_force)
{
    if (get_local_id(0) == 0)
        *group_rays = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    uint i = get_global_id(0);
    bool queue = (p->flags & RENDER_SHADOW_QUEUE) != 0u;
    if (i < (queue ? shadow_count[0] : n_active)) {
        uint slot = queue ? shadow_queue[i] : active[i];
        if (connect_path(p, scene, PATH_STATE_ARGS slot, brute_force))
            atomic_inc(group_rays);
    }
    /* Every work item reaches this barrier: no early return above. */
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0 && *group_rays > 0)
        atomic_add(&counters[COUNTER_SHADOW_RAYS], *group_rays);
}

kernel void intersect_shadow(INTERSECT_SHADOW_PARAMS)
{
    local uint group_rays;
    SceneView scene = SCENE_VIEW;
    intersect_shadow_group(p, &scene, PATH_STATE_ARGS active, n_active, counters, shadow_queue,
                           shadow_count, &group_rays, false);
}

kernel void intersect_shadow_brute_force(INTERSECT_SHADOW_PARAMS)
{
    local uint group_rays;
    SceneView scene = SCENE_VIEW;
    intersect_shadow_group(p, &scene, PATH_STATE_ARGS active, n_active, counters, shadow_queue,
                           shadow_count, &group_rays, true);
}
