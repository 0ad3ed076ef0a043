/* SPDX-License-Identifier: MIT */
/* bvh_query.cl: the one-level queries, over whichever layout BVH_WIDTH selected. Closest hits on
 * the 2-wide layout take the speculative walk (bvh_traverse_speculative.cl; 0.99-1.07x on an H100:
 * bench/README.md "Leaves postponed"); any hits, and every query on the wide layouts, take
 * trace_bvh (bvh_traverse.cl, bvh_traverse_wide.cl). -DBVH_NO_SPECULATION (through PT_CL_OPTIONS)
 * sends closest hits to trace_bvh too, for comparison: the hits are the same. */

inline Hit trace_bvh_query(const global TraversalNode *nodes, const global TraversalPrim *prims,
                           float3 origin, float3 dir, float tmin, float tmax, bool any_hit)
{
#if BVH_WIDTH == 2 && !defined(BVH_NO_SPECULATION)
    if (!any_hit)
        return trace_bvh_speculative(nodes, prims, origin, dir, tmin, tmax);
#endif
    return trace_bvh(nodes, prims, origin, dir, tmin, tmax, any_hit);
}

/* The queries of the BVH tests and bench_bvh (tests/cl/bvh_test.cl). num_prims is for the
 * brute-force ablation only. */
Hit trace_closest(const global TraversalNode *nodes, const global TraversalPrim *prims,
                  uint num_prims, float3 origin, float3 dir, float tmin, float tmax)
{
    (void)num_prims;
    return trace_bvh_query(nodes, prims, origin, dir, tmin, tmax, false);
}

bool trace_any(const global TraversalNode *nodes, const global TraversalPrim *prims, uint num_prims,
               float3 origin, float3 dir, float tmin, float tmax)
{
    (void)num_prims;
    return trace_bvh_query(nodes, prims, origin, dir, tmin, tmax, true).prim != HIT_NONE;
}
