/* SPDX-License-Identifier: MIT */
/* shade_surface_connect: shade_surface and intersect_shadow in one launch (RenderSettings
 * .connect_in_shading). Each work item shades its slot's vertex (shade_path) and traces the
 * shadow ray it queued at once, from registers: the shadow lanes are neither written nor read,
 * and no intersect_shadow launch, shadow queue or second read of the active list runs per step.
 * The additions to radiance[sample_id] come in the wavefront's order (the vertex's own light,
 * then the shadow ray's), so the film's bits are the two stages'. What it costs: lanes whose
 * vertex queued no ray (specular, or the light behind) idle while the others trace, and the
 * traversal's registers join shading's. Not with the brute-force ablation.
 * Reads and writes what shade_surface does, and counts its shadow rays as intersect_shadow does
 * (counters[COUNTER_SHADOW_RAYS]). A part of its own (CONNECT): built only when asked for. */

#if PT_PART(CONNECT)
kernel void shade_surface_connect(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                                  const global uint *active, uint n_active,
                                  global uint *shadow_queue, global uint *shadow_count,
                                  global uint *counters)
{
    local uint group_rays[2];
    clear_group_rays(group_rays);
    SceneView scene = SCENE_VIEW;
    uint i = get_global_id(0);
    bool traced = false;
    if (i < n_active) {
        uint slot = active[i];
        ShadowRay ray;
        if (shade_path(p, &scene, PATH_STATE_ARGS slot, &ray)) {
            float time = PT_FEATURE(MOTION) ? path_time[slot] : 0.0f;
            uint k = sample_id[slot];
            float3 c = ray.contribution;
            if (!shadow_ray_occluded(p, &scene, active_pixels, k, ray.origin, ray.direction,
                                     ray.tmax, time, ray.medium, ray.bounce, false, &c))
                radiance[k] += (float4)(c, 0.0f);
            traced = true;
        }
    }
    /* Every work item gets here: no early return above. */
    count_group_rays(group_rays, 0u, traced ? 1u : 0u, counters);
}
#endif
