/* SPDX-License-Identifier: MIT */
/* intersect_shadow: resolves the next-event shadow rays that shade_surface_split queued (the
 * wavefront with RenderSettings.split_shadow; shade_surface traces its own with
 * shadow_ray_occluded, and the megakernels with connect_path).
 * Reads: active[0..n_active), shadow_origin (tmax), shadow_direction (bounce: the one that queued
 * it, for the cut-out decisions), shadow_contribution (waits), sample_id. Writes:
 * radiance[sample_id] += contribution when unoccluded; shadow_contribution's waits = false.
 * Runs before compaction: a path killed by Russian roulette may still have a shadow ray.
 * Launched over the active list; with RENDER_SHADOW_QUEUE only the first shadow_count[0] items
 * work, on the slots that shade_surface appended to shadow_queue.
 * counters[COUNTER_SHADOW_RAYS] counts the rays traced (count_group_rays, path_state.cl).
 * intersect_shadow_brute_force: the same without the BVH (see intersect_closest.cl). */

#define INTERSECT_SHADOW_PARAMS                                                                    \
    constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS const global uint *active,            \
        uint n_active, global uint *counters, const global uint *shadow_queue,                     \
        const global uint *shadow_count

/* The end of slot's shadow ray, whose contribution was read from shadow_contribution: added to
 * the sample's radiance unless occluded, and the slot waits no more. Shared with megakernel.cl. */
inline void resolve_shadow_ray(PATH_STATE_PARAMS uint slot, float4 contribution, bool occluded)
{
    if (!occluded)
        radiance[sample_id[slot]] += (float4)(xyz(contribution), 0.0f);
    shadow_contribution[slot] = shadow_contribution_pack((float3)(0.0f), false);
}

/* With media: whether the shadow ray o + t d, t in [0, tmax), starting in medium slot `medium`,
 * reaches its end, passing through `interface` surfaces (into the medium beyond each) and no
 * other; *tr is multiplied by the transmittance of the media along it (medium_transmittance).
 * The queuing bounce's DIM_MEDIUM number seeds the ratio tracking: its hashed stream only, never
 * the number itself, which placed the vertex this ray starts from (the segment that reached it
 * took it as its first distance: reused, the first tentative collision here would depend on where
 * the vertex is). Its DIM_SHADOW_OPACITY stream drives the cut-out pass-throughs, one per piece. */
#define SHADOW_CROSSING_LIMIT 64u
PT_INLINE bool shadow_through_media(constant RenderParams *p, const SceneView *scene,
                                    uint brute_count, float3 o, float3 d, float tmax, float time,
                                    bool brute_force, uint medium, RngKey key, uint bounce,
                                    float3 *tr)
{
    MediumRng rng = medium_rng(rng_bounce_bits(key, bounce, DIM_MEDIUM), 0x1b873593u);
    rng.drawn = 1u; /* past `first`: see above */
    uint opacity = rng_bounce_bits(key, bounce, DIM_SHADOW_OPACITY);
    for (uint piece = 0u; piece <= SHADOW_CROSSING_LIMIT; piece++) {
        Hit h;
        if (PT_FEATURE(CUTOUT))
            h = trace_closest_through(scene, brute_count, o, d, 0.0f, tmax, time, brute_force,
                                      hash_pcg(opacity + piece));
        else
            h = brute_force ? scene_brute_force(scene, brute_count, o, d, 0.0f, tmax, false, time)
                            : scene_closest(scene, brute_count, o, d, 0.0f, tmax, time);
        bool reaches = h.prim == HIT_NONE;
        if (medium != 0u) {
            *tr *= medium_transmittance(scene, medium_at_slot(scene, medium), o, d,
                                        reaches ? tmax : h.t, &rng);
            if (!(max3(*tr) > 0.0f))
                return false;
        }
        if (reaches)
            return true;
        Material m = scene->materials[scene->material_ids[h.prim]];
        if (m.type != MATERIAL_INTERFACE)
            return false;
        SurfaceHit s = surface_at(scene, h, time);
        medium = medium_toward(p, m, s.geometric_normal, d, medium);
        o = offset_ray_origin(s.position, s.geometric_normal, d);
        tmax -= h.t;
    }
    return false;
}

/* Whether something stops the shadow ray o + t d, t in [0, tmax), of sample k's path, queued at
 * bounce (its cut-out and media streams) in medium slot `medium`; with media *contribution is
 * scaled by the transmittance along it. brute_force is a constant at every call. Shared by
 * connect_path and shade_surface (shade_surface.cl). */
PT_INLINE bool shadow_ray_occluded(constant RenderParams *p, const SceneView *scene,
                                   const global uint *active_pixels, uint k, float3 o, float3 d,
                                   float tmax, float time, uint medium, uint bounce,
                                   bool brute_force, float3 *contribution)
{
    uint brute_count = SCENE_BRUTE_FORCE_COUNT(p); /* scene_trace.cl */
    if (PT_FEATURE(MEDIA)) {
        RngKey key = path_rng_key(p, active_pixels, k);
        float3 tr = (float3)(1.0f);
        bool reaches = shadow_through_media(p, scene, brute_count, o, d, tmax, time, brute_force,
                                            medium, key, bounce, &tr);
        *contribution *= tr;
        return !reaches;
    }
    if (PT_FEATURE(CUTOUT)) {
        /* The queuing bounce's DIM_SHADOW_OPACITY stream decides the cut-out pass-throughs. */
        RngKey key = path_rng_key(p, active_pixels, k);
        return trace_occluded_through(scene, brute_count, o, d, tmax, time, brute_force,
                                      rng_bounce_bits(key, bounce, DIM_SHADOW_OPACITY));
    }
    return brute_force
               ? scene_brute_force(scene, brute_count, o, d, 0.0f, tmax, true, time).prim != HIT_NONE
               : scene_occluded(scene, brute_count, o, d, 0.0f, tmax, time);
}

/* Traces the shadow ray that slot's path waits for (shadow_contribution_waits) and adds its
 * contribution to radiance[sample_id] when unoccluded; false, touching nothing, when none waits.
 * brute_force is a constant at every call. Shared by the kernels below and megakernel.cl. */
PT_INLINE bool connect_path(constant RenderParams *p, const SceneView *scene,
                            PATH_STATE_PARAMS uint slot, bool brute_force)
{
    float4 contribution = shadow_contribution[slot];
    if (!shadow_contribution_waits(contribution))
        return false;
    float4 origin = shadow_origin[slot];
    float4 direction = shadow_direction[slot];
    float time = PT_FEATURE(MOTION) ? path_time[slot] : 0.0f;
    float3 c = xyz(contribution);
    bool occluded = shadow_ray_occluded(
        p, scene, active_pixels, sample_id[slot], xyz(origin), xyz(direction),
        shadow_origin_tmax(origin), time, shadow_direction_medium(direction),
        shadow_direction_bounce(direction), brute_force, &c);
    resolve_shadow_ray(PATH_STATE_ARGS slot, (float4)(c, contribution.w), occluded);
    return true;
}

/* The work-group's share of either kernel; brute_force is a constant in each. */
PT_INLINE void intersect_shadow_group(constant RenderParams *p, const SceneView *scene,
                                      PATH_STATE_PARAMS const global uint *active, uint n_active,
                                      global uint *counters, const global uint *shadow_queue,
                                      const global uint *shadow_count, local uint *group_rays,
                                      bool brute_force)
{
    clear_group_rays(group_rays);
    uint i = get_global_id(0);
    bool queue = (p->flags & RENDER_SHADOW_QUEUE) != 0u;
    bool traced = false;
    if (i < (queue ? shadow_count[0] : n_active)) {
        uint slot = queue ? shadow_queue[i] : active[i];
        traced = connect_path(p, scene, PATH_STATE_ARGS slot, brute_force);
    }
    /* Every work item gets here: no early return above. */
    count_group_rays(group_rays, 0u, traced ? 1u : 0u, counters);
}

#if PT_PART(SPLIT)
kernel void intersect_shadow(INTERSECT_SHADOW_PARAMS)
{
    local uint group_rays[2];
    SceneView scene = SCENE_VIEW;
    intersect_shadow_group(p, &scene, PATH_STATE_ARGS active, n_active, counters, shadow_queue,
                           shadow_count, group_rays, false);
}
#endif

#if PT_PART(ABLATION)
kernel void intersect_shadow_brute_force(INTERSECT_SHADOW_PARAMS)
{
    local uint group_rays[2];
    SceneView scene = SCENE_VIEW;
    intersect_shadow_group(p, &scene, PATH_STATE_ARGS active, n_active, counters, shadow_queue,
                           shadow_count, group_rays, true);
}
#endif
