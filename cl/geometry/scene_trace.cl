/* SPDX-License-Identifier: MIT */
/* scene_trace.cl: the ray queries every stage calls, over the scene's whole acceleration structure
 * (host/accel/scene_bvh.h): one level (without PT_FEATURE(INSTANCES): the one world-space mesh's
 * BVH, v1's walk), two (PT_FEATURE(TLAS): a TLAS over instances, each instance's BLAS walked in
 * its object space: trace_scene_bvh of bvh_traverse.cl or bvh_traverse_wide.cl), or flat
 * (instances without TLAS: one world-space BVH over every instance's triangles, walked as one
 * level, whose hits flat_prims maps to their instance and triangle). `time` is the path's shutter
 * fraction (path_time), which moving instances are placed at. Hits are reported for
 * tmin <= t < tmax with the instance and the (global) triangle index; ties go to the lower
 * (instance, triangle): a flat BVH numbers its triangles in that order. brute_count is for the
 * brute-force ablation only: the entries of bvh_tris (one level, flat) or of instances (two
 * levels), SCENE_BRUTE_FORCE_COUNT(p) of the RenderParams. */

/* The walk, as constants (a logical operator between PT_FEATUREs warns: constant operands). */
#if PT_FEATURE(INSTANCES) && PT_FEATURE(TLAS)
#define SCENE_TWO_LEVELS 1
#define SCENE_FLAT_BVH 0
#elif PT_FEATURE(INSTANCES)
#define SCENE_TWO_LEVELS 0
#define SCENE_FLAT_BVH 1
#else
#define SCENE_TWO_LEVELS 0
#define SCENE_FLAT_BVH 0
#endif
#define SCENE_BRUTE_FORCE_COUNT(p) \
    (SCENE_TWO_LEVELS ? (p)->scene.num_instances : (p)->scene.num_bvh_prims)

/* A flat BVH's hit (prim: its index among the baked triangles) as two levels report it. */
inline Hit flat_hit_unbaked(const global uint2 *flat_prims, Hit h)
{
    if (h.prim != HIT_NONE) {
        uint2 baked = flat_prims[h.prim];
        h.instance = baked.x;
        h.prim = baked.y;
    }
    return h;
}

/* Hits of the one-level walk as the scene reports them: a flat BVH's unbaked, others as they are. */
inline Hit scene_hit_of_one_level(const SceneView *scene, Hit h)
{
    return SCENE_FLAT_BVH ? flat_hit_unbaked(scene->flat_prims, h) : h;
}

/* The closest hit, or with any_hit the first one found. */
inline Hit scene_trace(const SceneView *scene, float3 o, float3 d, float tmin, float tmax,
                       float time, bool any_hit)
{
    if (SCENE_TWO_LEVELS)
        return trace_scene_bvh(scene->bvh_nodes, scene->bvh_tris, scene->instances,
                               scene->instance_motion, o, d, tmin, tmax, time, any_hit);
    return scene_hit_of_one_level(
        scene, trace_bvh_query(scene->bvh_nodes, scene->bvh_tris, o, d, tmin, tmax, any_hit));
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
    if (SCENE_TWO_LEVELS)
        return trace_scene_brute_force(scene->bvh_tris, scene->instances, scene->instance_motion,
                                       brute_count, o, d, tmin, tmax, time, any_hit);
    return scene_hit_of_one_level(scene,
                            trace_brute_force(scene->bvh_tris, brute_count, o, d, tmin, tmax, any_hit));
}
