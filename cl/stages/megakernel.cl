/* SPDX-License-Identifier: MIT */
/* trace_paths: the CPU's variant of the wavefront loop (host/render/megakernel.c), one work item
 * per window sample from camera ray to last bounce: start_path, then extend_path, shade_path and
 * connect_path in turn until the path ends, the same stage functions in the same order as the
 * wavefront's generate_camera_rays, intersect_closest, shade_surface and intersect_shadow. A path's
 * radiance therefore gets the same additions in the same order and the film the same bits. On a
 * CPU a work item runs on one core anyway (PoCL vectorises none of these stages), so what a GPU
 * needs the wavefront for, coherent lanes, is worth nothing there, while the path's state stays in
 * the cache between stages and no compaction, refill or count read-back runs between bounces.
 * Work item j uses slot j: the host launches at most a pool of samples, first_sample .. + n - 1.
 * counters[COUNTER_EXTENSION_RAYS / COUNTER_SHADOW_RAYS] count the rays (one atomic per group).
 * Not for the ablations (no compaction, brute force) nor scenes with black holes (their bent rays
 * are a stage of their own). */

kernel void trace_paths(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS uint first_sample,
                        uint n, global uint *counters)
{
    local uint group_extension, group_shadow;
    if (get_local_id(0) == 0)
        group_extension = group_shadow = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    SceneView scene = SCENE_VIEW;
    uint slot = get_global_id(0);
    uint extension = 0, shadow = 0;
    if (slot < n) {
        start_path(p, PATH_STATE_ARGS slot, first_sample + slot);
        while (extend_path(p, &scene, PATH_STATE_ARGS slot, false)) {
            extension++;
            if (shade_path(p, &scene, PATH_STATE_ARGS slot) &&
                connect_path(p, &scene, PATH_STATE_ARGS slot, false))
                shadow++;
        }
    }
    if (extension > 0)
        atomic_add(&group_extension, extension);
    if (shadow > 0)
        atomic_add(&group_shadow, shadow);
    /* Every work item reaches this barrier: no early return above. */
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0) {
        if (group_extension > 0)
            atomic_add(&counters[COUNTER_EXTENSION_RAYS], group_extension);
        if (group_shadow > 0)
            atomic_add(&counters[COUNTER_SHADOW_RAYS], group_shadow);
    }
}

#if BVH_WIDTH == 8 && !PT_FEATURE_INSTANCES && !PT_FEATURE_CUTOUT
/* trace_paths_packets: trace_paths with eight paths per work item, whose rays are traced as
 * packets (trace_packet, bvh_traverse_packet.cl). Work item i runs window samples 8 i .. 8 i + 7 in
 * slots 8 i .. 8 i + 7, bounce by bounce: their extension rays as one packet (extend_packet), each
 * live path's shading (shade_path), their shadow rays as one packet (connect_packet) and each
 * unoccluded shadow ray's contribution (connect_path's end), until all eight have ended.
 * Neighbouring samples are neighbouring pixels of one sample pass, whose camera rays and first
 * shadow rays are coherent; packets whose rays part ways go on ray by ray (PACKET_MIN_RAYS). Each
 * path's stages run in trace_paths' order with trace_bvh's hits, so the film's bits are the same.
 * Built where the packet walk applies: the 8-wide layout, one BVH level and no cut-outs (whose
 * walks pass through hits); scenes with bent rays never take a megakernel. The host launches
 * ceil(n / PACKET_RAYS) work items. */

/* Extends the live paths of slots first .. first + 7 (those < n) by their closest hits. */
PT_INLINE void extend_packet(const SceneView *scene, PATH_STATE_PARAMS uint first, uint n)
{
    float3 origin[8], dir[8];
    float tmin[8], tmax[8];
    int live[8];
    bool any = false;
    for (uint k = 0; k < 8u; k++) {
        uint slot = first + k;
        bool on = slot < n && path_depth[slot] != 0u;
        uint s = on ? slot : first; /* a dead lane holds some ray: trace_packet leaves it out */
        origin[k] = xyz(ray_origin[s]), dir[k] = xyz(ray_direction[s]);
        tmin[k] = 0.0f, tmax[k] = INFINITY;
        live[k] = on ? -1 : 0;
        any |= on;
    }
    if (!any)
        return;
    RayPacket r = ray_packet(scene->bvh_nodes, origin, dir, tmin);
    HitPacket h = trace_packet(scene->bvh_nodes, scene->bvh_tris, &r, vload8(0, live),
                               vload8(0, tmax), false);
    float t[8], u[8], v[8];
    uint prim[8];
    vstore8(h.t, 0, t), vstore8(h.u, 0, u), vstore8(h.v, 0, v), vstore8(h.prim, 0, prim);
    for (uint k = 0; k < 8u; k++)
        if (live[k]) {
#if PT_FEATURE_BLACK_HOLES
            t[k] += ray_origin[first + k].w; /* as extend_path: 0 for straight rays */
#endif
            hit[first + k] = (float4)(t[k], u[k], v[k], as_float(prim[k]));
        }
}

/* The shadow rays waiting in slots first .. first + 7 (those < n) as one packet: bit k set where
 * slot first + k's is occluded. */
PT_INLINE uint connect_packet(const SceneView *scene, PATH_STATE_PARAMS uint first, uint n)
{
    float3 origin[8], dir[8];
    float tmin[8], tmax[8];
    int live[8];
    bool any = false;
    for (uint k = 0; k < 8u; k++) {
        uint slot = first + k;
        bool on = slot < n && shadow_contribution[slot].w != 0.0f;
        uint s = on ? slot : first;
        float4 o = shadow_origin[s];
        origin[k] = xyz(o), dir[k] = xyz(shadow_direction[s]);
        tmin[k] = 0.0f, tmax[k] = o.w;
        live[k] = on ? -1 : 0;
        any |= on;
    }
    if (!any)
        return 0u;
    RayPacket r = ray_packet(scene->bvh_nodes, origin, dir, tmin);
    HitPacket h = trace_packet(scene->bvh_nodes, scene->bvh_tris, &r, vload8(0, live),
                               vload8(0, tmax), true);
    return lane_bits(vload8(0, live) & (h.prim != (uint8)(HIT_NONE)));
}

kernel void trace_paths_packets(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                                uint first_sample, uint n, global uint *counters)
{
    local uint group_extension, group_shadow;
    if (get_local_id(0) == 0)
        group_extension = group_shadow = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    SceneView scene = SCENE_VIEW;
    uint first = PACKET_RAYS * get_global_id(0);
    uint extension = 0, shadow = 0;
    if (first < n) {
        uint end = min(first + PACKET_RAYS, n);
        for (uint slot = first; slot < end; slot++)
            start_path(p, PATH_STATE_ARGS slot, first_sample + slot);
        for (bool live = true; live;) {
            extend_packet(&scene, PATH_STATE_ARGS first, n);
            for (uint slot = first; slot < end; slot++)
                if (path_depth[slot] != 0u) {
                    extension++;
                    shade_path(p, &scene, PATH_STATE_ARGS slot);
                }
            uint occluded = connect_packet(&scene, PATH_STATE_ARGS first, n);
            live = false;
            for (uint slot = first; slot < end; slot++) {
                if (shadow_contribution[slot].w != 0.0f) {
                    shadow++;
                    if (!(occluded & (1u << (slot - first))))
                        radiance[sample_id[slot]] += (float4)(xyz(shadow_contribution[slot]), 0.0f);
                    shadow_contribution[slot] = (float4)(0.0f);
                }
                live |= path_depth[slot] != 0u;
            }
        }
    }
    if (extension > 0)
        atomic_add(&group_extension, extension);
    if (shadow > 0)
        atomic_add(&group_shadow, shadow);
    /* Every work item reaches this barrier: no early return above. */
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0) {
        if (group_extension > 0)
            atomic_add(&counters[COUNTER_EXTENSION_RAYS], group_extension);
        if (group_shadow > 0)
            atomic_add(&counters[COUNTER_SHADOW_RAYS], group_shadow);
    }
}
#endif
