/* SPDX-License-Identifier: MIT */
/* intersect_closest: extends every live path by one segment.
 * Reads: active[0..n_active), ray_origin (path_ray_origin), ray_direction. Writes: hit (t, u, v,
 * triangle or HIT_NONE). Next: shade_surface. Without compaction, dead slots are in the list and
 * skipped. counters[COUNTER_EXTENSION_RAYS] counts the rays traced (count_group_rays,
 * path_state.cl). intersect_closest_brute_force is the same stage without the BVH (pt bench's
 * ablation row and the test that it renders the same image): a kernel of its own, so that the
 * production kernel carries no brute-force branch. With PT_FEATURE(CUTOUT), hits on cut-out
 * materials may be passed through (trace_closest_through): a pass-through is not a bounce,
 * path_depth stays. */

#define INTERSECT_CLOSEST_PARAMS                                                                   \
    constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS const global uint *active,            \
        uint n_active, global uint *counters

/* Traces the closest hit of the live path in slot into hit (and hit_instance); false, touching
 * nothing, for a free slot (path_depth 0). brute_force is a constant at every call. The stage
 * kernels below and the CPU's path-per-work-item kernel (megakernel.cl) share it. */
PT_INLINE bool intersect_closest_path(constant RenderParams *p, const SceneView *scene,
                                      PATH_STATE_PARAMS uint slot, bool brute_force)
{
    uint depth = path_depth[slot];
    if (!depth)
        return false;
    uint brute_count = SCENE_BRUTE_FORCE_COUNT(p); /* scene_trace.cl */
    float4 origin = path_ray_origin(p, ray_origin, slot, depth);
    float3 o = xyz(origin), d = xyz(ray_direction[slot]);
    float time = PT_FEATURE(MOTION) ? path_time[slot] : 0.0f;
    Hit h;
    if (PT_FEATURE(CUTOUT)) {
        /* Cut-outs let the ray through stochastically (surface_detail.cl); the vertex it reaches
         * is bounce path_depth - 1, whose DIM_OPACITY stream decides. */
        RngKey key = path_rng_key(p, active_pixels, sample_id[slot]);
        h = trace_closest_through(scene, brute_count, o, d, 0.0f, INFINITY, time, brute_force,
                                  rng_bounce_bits(key, depth - 1u, DIM_OPACITY));
    } else {
        h = brute_force ? scene_brute_force(scene, brute_count, o, d, 0.0f, INFINITY, false, time)
                        : scene_closest(scene, brute_count, o, d, 0.0f, INFINITY, time);
    }
    /* A ray bent by black holes starts partway along its segment (integrate_geodesic.cl):
     * the curve's length so far is ray_origin's travelled lane (0 for every straight ray). */
    if (ray_origin_bent(p))
        h.t += ray_origin_travelled(origin);
    hit[slot] = hit_pack(h.t, h.u, h.v, h.prim);
    if (PT_FEATURE(INSTANCES))
        hit_instance[slot] = h.instance;
    return true;
}

/* The work-group's share of either kernel; brute_force is a constant in each. */
PT_INLINE void intersect_closest_group(constant RenderParams *p, const SceneView *scene,
                                       PATH_STATE_PARAMS const global uint *active, uint n_active,
                                       global uint *counters, local uint *group_rays,
                                       bool brute_force)
{
    clear_group_rays(group_rays);
    uint i = get_global_id(0);
    uint slot = i < n_active ? active[i] : 0u;
    bool traced = i < n_active && intersect_closest_path(p, scene, PATH_STATE_ARGS slot, brute_force);
    /* Every work item gets here: no early return above. */
    count_group_rays(group_rays, traced ? 1u : 0u, 0u, counters);
}

#if PT_PART(CORE)
kernel void intersect_closest(INTERSECT_CLOSEST_PARAMS)
{
    local uint group_rays[2];
    SceneView scene = SCENE_VIEW;
    intersect_closest_group(p, &scene, PATH_STATE_ARGS active, n_active, counters, group_rays,
                            false);
}
#endif

#if PT_PART(ABLATION)
kernel void intersect_closest_brute_force(INTERSECT_CLOSEST_PARAMS)
{
    local uint group_rays[2];
    SceneView scene = SCENE_VIEW;
    intersect_closest_group(p, &scene, PATH_STATE_ARGS active, n_active, counters, group_rays,
                            true);
}
#endif
