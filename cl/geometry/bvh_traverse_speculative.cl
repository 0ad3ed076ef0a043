/* SPDX-License-Identifier: MIT */
/* bvh_traverse_speculative.cl: closest hits on the 2-wide tree with leaves postponed (Aila & Laine
 * 2009, "Understanding the Efficiency of Ray Traversal on GPUs": while-while with speculative
 * traversal). trace_bvh intersects a leaf child as soon as its box is hit, so a SIMD group pays
 * at every step for the longest leaf that any of its lanes met. Here a lane that meets a leaf
 * holds it and walks on (speculative_visit: leaves become walk_leaf entries); the lanes
 * intersect their leaves together once every lane still walking holds one (all_lanes), or when
 * a lane meets a second leaf or runs out of nodes. The hits are trace_bvh's: hit_wins breaks ties
 * whatever order the leaves come in. Any-hit queries keep trace_bvh: a postponed leaf postpones
 * the hit that would end the query (bvh_query.cl). */
#if BVH_WIDTH == 2

/* No entry left (as a walk_leaf, 15 triangles: more than a leaf holds). */
#define WALK_DONE 0xffffffffu
#define NO_LEAF 0u            /* the root, never a leaf */

/* Whether x holds in every lane of the SIMD group that runs this call. On NVIDIA a vote over the
 * lanes converged here (activemask); elsewhere a work item is its own group. -DPT_EXP_NO_VOTE
 * takes the vote out on NVIDIA too (plain while-while: 1-8% slower, bench/README.md). */
#if defined(PT_VENDOR_NVIDIA) && !defined(PT_EXP_NO_VOTE)
inline bool all_lanes(bool x)
{
    uint r;
    asm volatile("{\n\t.reg .pred p;\n\t.reg .b32 m;\n\tactivemask.b32 m;\n\t"
                 "setp.ne.u32 p, %1, 0;\n\tvote.sync.all.pred p, p, m;\n\t"
                 "selp.u32 %0, 1, 0, p;\n\t}"
                 : "=r"(r)
                 : "r"((uint)x));
    return r != 0u;
}
#else
inline bool all_lanes(bool x) { return x; }
#endif

inline uint walk_pop(Walk *walk, const uint *stack)
{
    return walk->stack_size ? stack[--walk->stack_size] : WALK_DONE;
}

/* Visits tr->node for this walk, where no leaf is intersected during a visit: hit.t cannot move
 * between the two children, so the box test's cull is the only one (traversal_visit_children's
 * second, before each child, cannot fire here), and the nearer child is next while the farther
 * goes on the stack, chosen by selects (measured against the visit through
 * traversal_visit_children: bench/README.md "Texture code per scene, the tight walk"). */
inline void speculative_visit(Traversal *tr, const global TraversalNode *nodes, uint *stack)
{
    bool hit[2];
    float t[2];
    uint ref[2], lane[2];
    traversal_test_children(tr, nodes, hit, t, ref, lane);
    bool swap = hit[1] && (!hit[0] || t[1] < t[0]);
    uint near = walk_entry(swap ? ref[1] : ref[0], swap ? lane[1] : lane[0]);
    uint far = walk_entry(swap ? ref[0] : ref[1], swap ? lane[0] : lane[1]);
    if (hit[0] && hit[1] && tr->walk.stack_size < BVH_STACK_SIZE) /* always: the builder bounds it */
        stack[tr->walk.stack_size++] = far;
    tr->walk.next = hit[0] || hit[1] ? near : 0u;
}

/* trace_bvh's closest hit. */
inline Hit trace_bvh_speculative(const global TraversalNode *nodes, const global BvhTriangle *tris,
                                 float3 origin, float3 dir, float tmin, float tmax)
{
    Traversal tr;
    uint stack[BVH_STACK_SIZE];
    traversal_start(&tr, nodes, origin, dir, tmin, tmax);
    uint leaf = NO_LEAF; /* tr.node: the node to visit next, a leaf entry or WALK_DONE */
    for (;;) {
        /* Inner nodes, until this lane meets a second leaf or runs out, or every lane still
         * here holds a leaf. */
        while (!child_is_leaf(tr.node)) {
            speculative_visit(&tr, nodes, stack);
            tr.node = tr.walk.next ? tr.walk.next : walk_pop(&tr.walk, stack);
            if (leaf == NO_LEAF && child_is_leaf(tr.node) && tr.node != WALK_DONE) {
                leaf = tr.node;
                tr.node = walk_pop(&tr.walk, stack);
            }
            if (all_lanes(leaf != NO_LEAF))
                break;
        }
        /* The held leaf, then node while it is a leaf too. */
        while (leaf != NO_LEAF) {
            intersect_leaf(tris, walk_leaf_first(leaf), walk_leaf_count(leaf), tr.tri, tr.tmin,
                           false, &tr.walk.hit, 0u);
            leaf = NO_LEAF;
            if (child_is_leaf(tr.node) && tr.node != WALK_DONE) {
                leaf = tr.node;
                tr.node = walk_pop(&tr.walk, stack);
            }
        }
        if (tr.node == WALK_DONE)
            return tr.walk.hit;
    }
}
#endif /* BVH_WIDTH == 2 */
