/* SPDX-License-Identifier: MIT */
/* intersect_closest: extends every live path by one segment.
 * Reads: active[0..n_active), ray_origin, ray_direction. Writes: hit (t, u, v, triangle or
 * HIT_NONE). Next: shade_surface. Without compaction, dead slots are in the list and skipped. */

kernel void intersect_closest(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                              const global uint *active, uint n_active)
{
    uint i = get_global_id(0);
    if (i >= n_active)
        return;
    uint slot = active[i];
    if (!alive[slot])
        return;
    Hit h = trace_closest(bvh_nodes, bvh_tris, p->num_triangles, xyz(ray_origin[slot]),
                          xyz(ray_direction[slot]), 0.0f, INFINITY);
    hit[slot] = (float4)(h.t, h.u, h.v, as_float(h.prim));
}
