/* SPDX-License-Identifier: MIT */
/* scene_trace.cl: the ray queries every stage calls, over the scene's whole acceleration structure
 * (host/accel/scene_bvh.h): one level (PT_FEATURE_INSTANCES=0: the one world-space mesh's BVH, v1's
 * walk) or two (a TLAS over instances, each instance's BLAS walked in its object space). `time` is
 * the path's shutter fraction (path_time), which moving instances are placed at. Hits are reported
 * for tmin <= t < tmax with the instance and the (global) triangle index; ties go to the lower
 * (instance, triangle). num_prims is for the brute-force ablation only. */

inline Hit scene_closest(const SceneView *scene, uint num_prims, float3 o, float3 d, float tmin,
                         float tmax, float time)
{
    (void)time;
    return trace_closest(scene->bvh_nodes, scene->bvh_tris, num_prims, o, d, tmin, tmax);
}

/* The first hit found (not the closest): an occlusion test, or the start of a cut-out walk. */
inline Hit scene_any(const SceneView *scene, uint num_prims, float3 o, float3 d, float tmin,
                     float tmax, float time)
{
    (void)time, (void)num_prims;
    return trace_bvh(scene->bvh_nodes, scene->bvh_tris, o, d, tmin, tmax, true);
}

inline bool scene_occluded(const SceneView *scene, uint num_prims, float3 o, float3 d, float tmin,
                           float tmax, float time)
{
    return scene_any(scene, num_prims, o, d, tmin, tmax, time).prim != HIT_NONE;
}

/* Every triangle of every instance, no BVH: the brute-force ablation (the *_brute_force stages). */
inline Hit scene_brute_force(const SceneView *scene, uint num_prims, float3 o, float3 d, float tmin,
                             float tmax, bool any_hit, float time)
{
    (void)time;
    return trace_brute_force(scene->bvh_tris, num_prims, o, d, tmin, tmax, any_hit);
}
