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
