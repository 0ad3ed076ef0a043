/* SPDX-License-Identifier: MIT */
/* scene_trace.cl: the ray queries every stage calls, over the scene's whole acceleration structure
 * (host/accel/scene_bvh.h): one level (without PT_FEATURE(INSTANCES): the one world-space mesh's
 * BVH, v1's walk) or two (a TLAS over instances, each instance's BLAS walked in its object space:
 * trace_scene_bvh of bvh_traverse.cl or bvh_traverse_wide.cl). `time` is the path's shutter
 * fraction (path_time), which moving instances are placed at. Hits are reported for
 * tmin <= t < tmax with the instance and the (global) triangle index; ties go to the lower
 * (instance, triangle). brute_count is for the brute-force ablation only: the entries of bvh_tris
 * (one level) or of instances (two levels), SCENE_BRUTE_FORCE_COUNT(p) of the RenderParams. */

#define SCENE_BRUTE_FORCE_COUNT(p) \
    (PT_FEATURE(INSTANCES) ? (p)->scene.num_instances : (p)->scene.num_bvh_prims)

/* The closest hit, or with any_hit the first one found. */
inline Hit scene_trace(const SceneView *scene, float3 o, float3 d, float tmin, float tmax,
                       float time, bool any_hit)
{
    if (PT_FEATURE(INSTANCES))
        return trace_scene_bvh(scene->bvh_nodes, scene->bvh_tris, scene->instances,
                               scene->instance_motion, o, d, tmin, tmax, time, any_hit);
    return trace_bvh(scene->bvh_nodes, scene->bvh_tris, o, d, tmin, tmax, any_hit);
}

inline Hit scene_closest(const SceneView *scene, uint brute_count, float3 o, float3 d, float tmin,
                         float tmax, float time)
{
    (void)brute_count;
    return scene_trace(scene, o, d, tmin, tmax, time, false);
}

/* The first hit found (not the closest): an occlusion test, or the start of a cut-out walk. */
inline Hit scene_any(const SceneView *scene, uint brute_count, float3 o, float3 d, float tmin,
                     float tmax, float time)
{
    (void)brute_count;
    return scene_trace(scene, o, d, tmin, tmax, time, true);
}

inline bool scene_occluded(const SceneView *scene, uint brute_count, float3 o, float3 d, float tmin,
                           float tmax, float time)
{
    return scene_any(scene, brute_count, o, d, tmin, tmax, time).prim != HIT_NONE;
}

/* Every triangle of every instance, no BVH: the brute-force ablation (the *_brute_force stages). */
inline Hit scene_brute_force(const SceneView *scene, uint brute_count, float3 o, float3 d,
                             float tmin, float tmax, bool any_hit, float time)
{
    if (PT_FEATURE(INSTANCES))
        return trace_scene_brute_force(scene->bvh_tris, scene->instances, scene->instance_motion,
                                       brute_count, o, d, tmin, tmax, time, any_hit);
    return trace_brute_force(scene->bvh_tris, brute_count, o, d, tmin, tmax, any_hit);
}
