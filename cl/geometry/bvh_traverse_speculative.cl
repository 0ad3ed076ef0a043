/* SPDX-License-Identifier: MIT */
/* bvh_traverse_speculative.cl: closest hits on the 2-wide tree with leaves postponed (Aila & Laine
 * 2009, "Understanding the Efficiency of Ray Traversal on GPUs": while-while with speculative
 * traversal). trace_bvh intersects a leaf child as soon as its box is hit, so a SIMD group pays
 * at every step for the longest leaf that any of its lanes met. Here a lane that meets a leaf
 * holds it and walks on; the lanes intersect their leaves together once every lane still walking
 * holds one (all_lanes), or when a lane meets a second leaf or runs out of nodes. The hits are
 * trace_bvh's: hit_wins breaks ties whatever order the leaves come in. Any-hit queries keep
 * trace_bvh: a postponed leaf postpones the hit that would end the query (bvh_query.cl). */
#if BVH_WIDTH == 2

/* A leaf as a walk entry: sign bit, first triangle << 4, count (the quantised layout's reference,
 * bvh_quantized.h; the float layout's leaves are packed alike, which bounds its triangles as the
 * quantised layout's: host/accel/scene_bvh.c). */
inline uint walk_leaf(uint first, uint count)
{
    return BVH_QUANTIZED_LEAF | (first << BVH_QUANTIZED_COUNT_BITS) | count;
}
inline uint walk_leaf_first(uint entry)
{
    return (entry & ~BVH_QUANTIZED_LEAF) >> BVH_QUANTIZED_COUNT_BITS;
}
inline uint walk_leaf_count(uint entry)
{
    return entry & ((1u << BVH_QUANTIZED_COUNT_BITS) - 1u);
}
#define WALK_DONE 0xffffffffu /* no entry left: a leaf of 15 triangles at the limit, which none is */
#define NO_LEAF 0u            /* the root, never a leaf */

/* Whether x holds in every lane of the SIMD group that runs this call. On NVIDIA a vote over the
 * lanes converged here (activemask); elsewhere a work item is its own group. -DPT_EXP_NO_VOTE
 * takes the vote out on NVIDIA too (plain while-while: 1-8% slower, bench/README.md). */
#if defined(PT_VENDOR_NVIDIA) && !defined(PT_EXP_NO_VOTE)
inline bool all_lanes(bool x)
{
    uint r;
    asm volatile("{\n\t.reg .pred p;\n\t.reg .b32 m;\n\tactivemask.b32 m;\n\t"
                 "setp.ne.u32 p, %1, 0;\n\tvote.sync.all.pred p, p, m;\n\tselp.u32 %0, 1, 0, p;\n\t}"
                 : "=r"(r)
                 : "r"((uint)x));
    return r != 0u;
}
#else
inline bool all_lanes(bool x) { return x; }
#endif

/* visit_child for this walk: a leaf becomes an entry like an inner node. */
inline void visit_child_postponed(uint ref, uint lane, float t_entry, Walk *walk, uint *stack)
{
    if (!(t_entry <= (walk->hit.t + walk->slack) * BOX_EXIT_SCALE))
        return;
    if (child_is_leaf(ref)) {
        uint count = leaf_count(ref, lane);
        if (count == 0u)
            return;
        ref = walk_leaf(leaf_first(ref, lane), count);
    }
    if (walk->next == 0)
        walk->next = ref;
    else if (walk->stack_size < BVH_STACK_SIZE) /* always true: the builder bounds the depth */
        stack[walk->stack_size++] = ref;
}

inline uint walk_pop(Walk *walk, const uint *stack)
{
    return walk->stack_size ? stack[--walk->stack_size] : WALK_DONE;
}

/* trace_bvh's closest hit. */
inline Hit trace_bvh_speculative(const global TraversalNode *nodes, const global BvhTriangle *tris,
                                 float3 origin, float3 dir, float tmin, float tmax)
{
    Traversal tr;
    uint stack[BVH_STACK_SIZE];
    traversal_start(&tr, nodes, origin, dir, tmin, tmax);
    uint node = 0u, leaf = NO_LEAF;
    for (;;) {
        /* Inner nodes, until this lane meets a second leaf or runs out, or every lane still
         * here holds a leaf. */
        while (!child_is_leaf(node)) {
            COUNT_STEPS(tr.walk.hit, 1u, 0u);
            bool hit[2];
            float t[2];
            uint ref[2], lane[2];
            test_children(&nodes[node], tr.box, tr.box_tmin, tr.walk.hit.t + tr.walk.slack, hit,
                          t, ref, lane);
            bool swap = hit[1] && (!hit[0] || t[1] < t[0]); /* nearer first, as trace_bvh */
            tr.walk.next = 0;
            if (hit[0] || hit[1])
                visit_child_postponed(swap ? ref[1] : ref[0], swap ? lane[1] : lane[0],
                                      swap ? t[1] : t[0], &tr.walk, stack);
            if (hit[0] && hit[1])
                visit_child_postponed(swap ? ref[0] : ref[1], swap ? lane[0] : lane[1],
                                      swap ? t[0] : t[1], &tr.walk, stack);
            node = tr.walk.next ? tr.walk.next : walk_pop(&tr.walk, stack);
            if (leaf == NO_LEAF && child_is_leaf(node) && node != WALK_DONE) {
                leaf = node;
                node = walk_pop(&tr.walk, stack);
            }
            if (all_lanes(leaf != NO_LEAF))
                break;
        }
        /* The held leaf, then node while it is a leaf too. */
        while (leaf != NO_LEAF) {
            intersect_leaf(tris, walk_leaf_first(leaf), walk_leaf_count(leaf), tr.tri, tr.tmin,
                           false, &tr.walk.hit, 0u);
            leaf = NO_LEAF;
            if (child_is_leaf(node) && node != WALK_DONE) {
                leaf = node;
                node = walk_pop(&tr.walk, stack);
            }
        }
        if (node == WALK_DONE)
            return tr.walk.hit;
    }
}
#endif /* BVH_WIDTH == 2 */
