/* SPDX-License-Identifier: MIT */
/* intersect_shadow: resolves the next-event shadow rays that shade_surface queued.
 * Reads: active[0..n_active), shadow_origin, shadow_direction, shadow_contribution (w = 1: a ray
 * waits). Writes: radiance += contribution when unoccluded; shadow_contribution.w = 0.
 * Runs before compaction: a path killed by Russian roulette may still have a shadow ray. */

kernel void intersect_shadow(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                             const global uint *active, uint n_active)
{
    uint i = get_global_id(0);
    if (i >= n_active)
        return;
    uint slot = active[i];
    float4 contribution = shadow_contribution[slot];
    if (contribution.w == 0.0f)
        return;
    float4 origin = shadow_origin[slot];
    if (!trace_any(bvh_nodes, bvh_tris, p->num_triangles, xyz(origin), xyz(shadow_direction[slot]),
                   0.0f, origin.w))
        radiance[slot] += (float4)(xyz(contribution), 0.0f);
    shadow_contribution[slot] = (float4)(0.0f);
}
