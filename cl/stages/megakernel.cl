/* SPDX-License-Identifier: MIT */
/* trace_paths: the CPU's variant of the wavefront loop (host/render/megakernel.c), one work item
 * per window sample from camera ray to last bounce: start_path, then intersect_closest_path, shade_path and
 * connect_path in turn until the path ends, the same stage functions in the same order as the
 * wavefront's generate_camera_rays, intersect_closest, shade_surface and intersect_shadow. A path's
 * radiance therefore gets the same additions in the same order and the film the same bits. On a
 * CPU a work item runs on one core anyway (PoCL vectorises none of these stages), so what a GPU
 * needs the wavefront for, coherent lanes, is worth nothing there, while the path's state stays in
 * the cache between stages and no compaction, refill or count read-back runs between bounces.
 * Work item j uses slot j: the host launches at most a pool of samples, first_sample .. + n - 1.
 * counters[COUNTER_EXTENSION_RAYS / COUNTER_SHADOW_RAYS] count the rays (count_group_rays).
 * Not for the ablations (no compaction, brute force) nor scenes with black holes (their bent rays
 * are a stage of their own). */

/* The path in slot, waiting for its extension ray, to its end: intersect_closest_path, shade_path
 * and connect_path in turn, the wavefront's stages in their order; the rays traced are added to
 * *extension and *shadow. */
PT_INLINE void run_path(constant RenderParams *p, const SceneView *scene, PATH_STATE_PARAMS uint slot,
                        uint *extension, uint *shadow)
{
    while (intersect_closest_path(p, scene, PATH_STATE_ARGS slot, false)) {
        (*extension)++;
        if (shade_path(p, scene, PATH_STATE_ARGS slot, 0) &&
            connect_path(p, scene, PATH_STATE_ARGS slot, false))
            (*shadow)++;
    }
}

#if PT_PART(MEGAKERNEL)
kernel void trace_paths(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS uint first_sample,
                        uint n, global uint *counters)
{
    local uint group_rays[2];
    clear_group_rays(group_rays);
    SceneView scene = SCENE_VIEW;
    uint slot = get_global_id(0);
    uint extension = 0, shadow = 0;
    if (slot < n) {
        start_path(p, PATH_STATE_ARGS slot, first_sample + slot, true);
        run_path(p, &scene, PATH_STATE_ARGS slot, &extension, &shadow);
    }
    /* Every work item gets here: no early return above. */
    count_group_rays(group_rays, extension, shadow, counters);
}
#endif

/* finish_paths: the wavefront's tail (host/render/wavefront.c). Once a window has no samples left
 * to start and few paths are live, stepping them bounce by bounce costs a handful of launches and
 * a count read-back per step for little work each; this kernel takes the live paths of the active
 * list (after a compaction: each waits for its extension ray) to their ends in one launch, with
 * the same stage functions in the same order as the steps it replaces, so the film's bits and the
 * ray counts are the wavefront's. Not for scenes with black holes (their bent rays are a stage of
 * their own) nor the brute-force ablation. A part of its own (TAIL), which a GPU render builds
 * beside its first windows (device_build_in_background) and a CPU render, which takes
 * trace_paths, never asks for. */
#if PT_PART(TAIL)
kernel void finish_paths(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                         const global uint *active, uint n_active, global uint *counters)
{
    local uint group_rays[2];
    clear_group_rays(group_rays);
    SceneView scene = SCENE_VIEW;
    uint i = get_global_id(0);
    uint extension = 0, shadow = 0;
    if (i < n_active)
        run_path(p, &scene, PATH_STATE_ARGS active[i], &extension, &shadow);
    /* Every work item gets here: no early return above. */
    count_group_rays(group_rays, extension, shadow, counters);
}
#endif

#if BVH_WIDTH == 8 && !PT_FEATURE(INSTANCES) && !PT_FEATURE(CUTOUT) && !PT_FEATURE(MEDIA)
#if PACKET_RAYS != 8
#error "trace_paths_packets traces PACKET_RAYS paths in float8 lanes: the host's count must be 8"
#endif
/* trace_paths_packets: trace_paths with eight paths per work item, whose rays are traced as
 * packets (trace_packet, bvh_traverse_packet.cl). Work item i runs window samples 8 i .. 8 i + 7 in
 * slots 8 i .. 8 i + 7, bounce by bounce: their extension rays as one packet (extend_packet), each
 * live path's shading (shade_path), their shadow rays as one packet (connect_packet) and each
 * unoccluded shadow ray's contribution (connect_path's end), until all eight have ended.
 * Neighbouring samples are neighbouring pixels of one sample pass, whose camera rays and first
 * shadow rays are coherent; packets whose rays part ways go on ray by ray (PACKET_MIN_RAYS). Each
 * path's stages run in trace_paths' order with trace_bvh's hits, so the film's bits are the same.
 * Built where the packet walk applies: the 8-wide layout, one BVH level, no cut-outs and no media
 * (whose walks pass through hits); scenes with bent rays never take a megakernel. The host launches
 * ceil(n / PACKET_RAYS) work items. */

/* The rays of slots first + k for the bits k set in lanes (!= 0) as one packet from tmin 0:
 * origins in origins' xyz, directions in dirs' xyz, tmax the shadow rays' (shadow_origin_tmax)
 * where tmax_in_w, else infinite. A lane without a ray holds another lane's, which trace_packet
 * leaves out. */
PT_INLINE HitPacket trace_slots(const SceneView *scene, const global float4 *origins,
                                const global float4 *dirs, bool tmax_in_w, uint first, uint lanes,
                                bool any_hit)
{
    float3 origin[8], dir[8];
    float tmin[8], tmax[8];
    for (uint k = 0; k < 8u; k++) {
        uint s = first + ((lanes >> k) & 1u ? k : lowest_lane(lanes));
        float4 o = origins[s];
        origin[k] = xyz(o), dir[k] = xyz(dirs[s]);
        tmin[k] = 0.0f, tmax[k] = tmax_in_w ? shadow_origin_tmax(o) : INFINITY;
    }
    RayPacket r = ray_packet(scene->bvh_nodes, origin, dir, tmin);
    return trace_packet(scene->bvh_nodes, scene->bvh_tris, &r, lanes_of(lanes), vload8(0, tmax),
                        any_hit);
}

/* intersect_closest_path for the live paths of slots first .. first + 7 (those < n), as one packet.
 * It reads ray_origin directly, not through path_ray_origin: trace_paths_packets' start_path
 * stores the camera rays' origins (store_implied), so this is for its slots only. */
PT_INLINE void extend_packet(constant RenderParams *p, const SceneView *scene,
                             PATH_STATE_PARAMS uint first, uint n)
{
    uint lanes = 0;
    for (uint k = 0; k < 8u; k++)
        if (first + k < n && path_depth[first + k] != 0u)
            lanes |= 1u << k;
    if (lanes == 0u)
        return;
    HitPacket h = trace_slots(scene, ray_origin, ray_direction, false, first, lanes, false);
    float t[8], u[8], v[8];
    uint prim[8];
    vstore8(h.t, 0, t), vstore8(h.u, 0, u), vstore8(h.v, 0, v), vstore8(h.prim, 0, prim);
    for (uint k = 0; k < 8u; k++)
        if ((lanes >> k) & 1u) {
            if (ray_origin_bent(p))
                t[k] += ray_origin_travelled(ray_origin[first + k]); /* as intersect_closest_path */
            hit[first + k] = hit_pack(t[k], u[k], v[k], prim[k]);
        }
}

/* The shadow rays waiting in slots first .. first + 7 (those < n) as one packet: bit k set where
 * slot first + k's is occluded. */
PT_INLINE uint connect_packet(const SceneView *scene, PATH_STATE_PARAMS uint first, uint n)
{
    uint lanes = 0;
    for (uint k = 0; k < 8u; k++)
        if (first + k < n && shadow_contribution_waits(shadow_contribution[first + k]))
            lanes |= 1u << k;
    if (lanes == 0u)
        return 0u;
    HitPacket h = trace_slots(scene, shadow_origin, shadow_direction, true, first, lanes, true);
    return lanes & lane_bits(h.prim != (uint8)(HIT_NONE));
}

#if PT_PART(MEGAKERNEL)
kernel void trace_paths_packets(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                                uint first_sample, uint n, global uint *counters)
{
    local uint group_rays[2];
    clear_group_rays(group_rays);
    SceneView scene = SCENE_VIEW;
    uint first = PACKET_RAYS * get_global_id(0);
    uint extension = 0, shadow = 0;
    if (first < n) {
        uint end = min(first + PACKET_RAYS, n);
        for (uint slot = first; slot < end; slot++)
            start_path(p, PATH_STATE_ARGS slot, first_sample + slot, true);
        for (bool live = true; live;) {
            extend_packet(p, &scene, PATH_STATE_ARGS first, n);
            for (uint slot = first; slot < end; slot++)
                if (path_depth[slot] != 0u) {
                    extension++;
                    shade_path(p, &scene, PATH_STATE_ARGS slot, 0);
                }
            uint occluded = connect_packet(&scene, PATH_STATE_ARGS first, n);
            live = false;
            for (uint slot = first; slot < end; slot++) {
                float4 contribution = shadow_contribution[slot];
                if (shadow_contribution_waits(contribution)) {
                    shadow++;
                    resolve_shadow_ray(PATH_STATE_ARGS slot, contribution,
                                       (occluded >> (slot - first)) & 1u);
                }
                live |= path_depth[slot] != 0u;
            }
        }
    }
    /* Every work item gets here: no early return above. */
    count_group_rays(group_rays, extension, shadow, counters);
}
#endif
#endif
