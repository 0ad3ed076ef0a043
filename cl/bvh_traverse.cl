/* SPDX-License-Identifier: MIT */
/* bvh_traverse.cl: closest-hit and any-hit queries used by every kernel that traces rays.
 * Interim: a brute-force loop over the triangles until the BVH lands (the node array is ignored). */

Hit trace_closest(const global BvhNode *nodes, const global BvhTriangle *tris, uint num_tris,
                  float3 origin, float3 dir, float tmin, float tmax)
{
    (void)nodes;
    Hit hit = {tmax, 0.0f, 0.0f, HIT_NONE};
    for (uint i = 0; i < num_tris; i++) {
        float t, u, v;
        if (intersect_triangle(origin, dir, xyz(tris[i].v0), xyz(tris[i].v1), xyz(tris[i].v2), tmin,
                               hit.t, &t, &u, &v)) {
            hit.t = t, hit.u = u, hit.v = v, hit.prim = as_uint(tris[i].v0.w);
        }
    }
    return hit;
}

bool trace_any(const global BvhNode *nodes, const global BvhTriangle *tris, uint num_tris,
               float3 origin, float3 dir, float tmin, float tmax)
{
    (void)nodes;
    for (uint i = 0; i < num_tris; i++) {
        float t, u, v;
        if (intersect_triangle(origin, dir, xyz(tris[i].v0), xyz(tris[i].v1), xyz(tris[i].v2), tmin,
                               tmax, &t, &u, &v))
            return true;
    }
    return false;
}
