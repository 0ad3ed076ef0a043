/* SPDX-License-Identifier: MIT */
/* bvh_traverse.cl: closest-hit and any-hit queries used by every kernel that traces rays. With
 * BVH_WIDTH == 2 (GPUs) it walks the 2-wide node array of host/accel/bvh_build.c (both child boxes
 * in the parent, Aila & Laine 2009; bvh_node_2wide.cl reads them) with a private stack: both child
 * boxes are tested at once, leaf children are intersected right away (nearer first), the nearer
 * inner child is visited next and the farther one is pushed; one-level any-hit queries skip the
 * order (any_hit_visit). Hits are reported for tmin <= t < tmax; prim is the original triangle
 * index. */
#if BVH_WIDTH == 2 /* else cl/geometry/bvh_traverse_wide.cl; the queries: cl/geometry/bvh_query.cl */

/* Whether a hit at t on triangle prim of `instance` replaces *hit, given t <= hit->t (the tie
 * limit): a tie goes to the lower (instance, prim) pair, so ties do not depend on the order in
 * which the trees present triangles. One level: every instance is 0. */
inline bool hit_wins(Hit hit, float t, uint instance, uint prim)
{
    if (!PT_FEATURE(INSTANCES))
        return t < hit.t || prim < hit.prim;
    return t < hit.t || instance < hit.instance || (instance == hit.instance && prim < hit.prim);
}

/* Intersects the leaf's triangles (of `instance`, in the space the ray is given in), shrinking
 * hit->t; true when any hit (for early exit). A hit at exactly hit->t replaces it by hit_wins. */
inline bool intersect_leaf(const global BvhTriangle *tris, uint first, uint count,
                           WatertightRay ray, float tmin, bool any_hit, Hit *hit, uint instance)
{
    bool found = false;
    float limit = hit_tie_limit(*hit);
    for (uint i = first; i < first + count; i++) {
        COUNT_STEPS(*hit, 0u, 1u);
        float t, u, v;
        if (intersect_triangle_watertight(ray, xyz(tris[i].v0), xyz(tris[i].v1), xyz(tris[i].v2),
                                          tmin, limit, &t, &u, &v)) {
            uint prim = as_uint(tris[i].v0.w);
            if (hit_wins(*hit, t, instance, prim)) { /* t <= hit->t here */
                hit->t = t;
                hit->u = u;
                hit->v = v;
                hit->prim = prim;
                hit->instance = instance;
                limit = hit_tie_limit(*hit);
                found = true;
                if (any_hit)
                    break;
            }
        }
    }
    return found;
}

/* Intersects the triangles of the leaf child (ref, lane) of a node; true when any hit. */
inline bool intersect_child_leaf(const global BvhTriangle *tris, uint ref, uint lane,
                                 WatertightRay ray, float tmin, bool any_hit, Hit *hit,
                                 uint instance)
{
    return intersect_leaf(tris, leaf_first(ref, lane), leaf_count(ref, lane), ray, tmin, any_hit,
                          hit, instance);
}

/* Traversal state that visit_child updates: the best hit so far, the node to visit next (0, the
 * root, is never a child, so it means "pop") and the stack of farther inner children. */
typedef struct {
    Hit hit;
    uint next;
    uint stack_size;
    float slack; /* see box_slack */
} Walk;

/* Visits one child whose box the ray meets at t_entry: a leaf is intersected now, or with
 * defer_leaves (a TLAS's leaves, which name instances) visited like an inner node as a walk_leaf
 * entry; an inner node becomes the next node or, if there is one already, goes on the stack.
 * True when an any-hit query is answered. */
inline bool visit_child(const global BvhTriangle *tris, uint ref, uint lane, float t_entry,
                        WatertightRay ray, float tmin, bool any_hit, Walk *walk, uint *stack,
                        uint stack_limit, bool defer_leaves, uint instance)
{
    /* The sibling visited first may have moved the closest hit in front of this box. */
    if (!(t_entry <= (walk->hit.t + walk->slack) * BOX_EXIT_SCALE))
        return false;
    if (child_is_leaf(ref)) {
        if (!defer_leaves)
            return intersect_child_leaf(tris, ref, lane, ray, tmin, any_hit, &walk->hit,
                                        instance) &&
                   any_hit;
        /* The empty TLAS's leaf names no instance (a quantised empty box may pass the test). */
        if (leaf_count(ref, lane) == 0u)
            return false;
        ref = walk_entry(ref, lane);
    }
    if (walk->next == 0)
        walk->next = ref;
    else if (walk->stack_size < stack_limit) /* always true: the builder bounds the depth */
        stack[walk->stack_size++] = ref;
    return false;
}

/* A walk in progress, split into steps so that a kernel can start a new ray in a SIMD lane whose
 * ray is done while the other lanes go on (bvh_test.cl's dynamic kernel); trace_bvh runs one walk
 * to the end. The stack stays with the caller, so that the struct is a few scalars that the
 * compiler keeps in registers. */
typedef struct {
    BoxRay box;
    WatertightRay tri;
    Walk walk;
    float tmin, box_tmin;
    uint node;
} Traversal;

inline void traversal_start(Traversal *tr, const global TraversalNode *nodes, float3 origin,
                            float3 dir, float tmin, float tmax)
{
    tr->box = box_ray(origin, dir);
    tr->tri = watertight_ray(origin, dir);
    Walk walk = {{tmax, 0.0f, 0.0f, HIT_NONE, 0u}, 0, 0, box_slack(nodes, origin, tr->tri)};
    tr->walk = walk;
    tr->tmin = tmin;
    tr->box_tmin = tmin - walk.slack;
    tr->node = 0;
}

/* Tests tr->node's two child boxes against the ray, within the closest hit so far. */
inline void traversal_test_children(Traversal *tr, const global TraversalNode *nodes, bool hit[2],
                                    float t[2], uint ref[2], uint lane[2])
{
    COUNT_STEPS(tr->walk.hit, 1u, 0u);
    test_children(&nodes[tr->node], tr->box, tr->box_tmin, tr->walk.hit.t + tr->walk.slack, hit, t,
                  ref, lane);
}

/* Tests tr->node's children and visits those the ray meets (nearer first), leaving the node to
 * visit next in tr->walk.next (0: pop one); true when an any-hit query is answered. */
inline bool traversal_visit_children(Traversal *tr, const global TraversalNode *nodes,
                                     const global BvhTriangle *tris, bool any_hit, uint *stack,
                                     uint stack_limit, bool defer_leaves, uint instance)
{
    bool hit[2];
    float t[2];
    uint ref[2], lane[2];
    traversal_test_children(tr, nodes, hit, t, ref, lane);
    /* Nearer child first: it is the more likely to shorten hit.t for the other. Selects, not
     * indices: a private array indexed at run time would live in memory. */
    bool swap = hit[1] && (!hit[0] || t[1] < t[0]);
    tr->walk.next = 0;
    if ((hit[0] || hit[1]) &&
        visit_child(tris, swap ? ref[1] : ref[0], swap ? lane[1] : lane[0], swap ? t[1] : t[0],
                    tr->tri, tr->tmin, any_hit, &tr->walk, stack, stack_limit, defer_leaves,
                    instance))
        return true;
    return hit[0] && hit[1] &&
           visit_child(tris, swap ? ref[0] : ref[1], swap ? lane[0] : lane[1], swap ? t[0] : t[1],
                       tr->tri, tr->tmin, any_hit, &tr->walk, stack, stack_limit, defer_leaves,
                       instance);
}

/* An any-hit visit: the query ends at its first hit, so hit.t never shrinks during the walk and
 * traversal_visit_children's second cull cannot fire, and the children need no order: leaf
 * children are intersected at once, the left inner child is next and the right one is pushed
 * (measured against the ordered visit: bench/README.md "Issue 41's table before and after"). */
inline bool any_hit_visit(Traversal *tr, const global TraversalNode *nodes,
                          const global BvhTriangle *tris, uint *stack)
{
    bool hit[2];
    float t[2];
    uint ref[2], lane[2];
    traversal_test_children(tr, nodes, hit, t, ref, lane);
    bool leaf0 = child_is_leaf(ref[0]), leaf1 = child_is_leaf(ref[1]);
    if ((hit[0] && leaf0 &&
         intersect_child_leaf(tris, ref[0], lane[0], tr->tri, tr->tmin, true, &tr->walk.hit, 0u)) ||
        (hit[1] && leaf1 &&
         intersect_child_leaf(tris, ref[1], lane[1], tr->tri, tr->tmin, true, &tr->walk.hit, 0u)))
        return true;
    bool inner0 = hit[0] && !leaf0, inner1 = hit[1] && !leaf1;
    /* The stack check always passes: the builder bounds the depth. */
    if (inner0 && inner1 && tr->walk.stack_size < BVH_STACK_SIZE)
        stack[tr->walk.stack_size++] = ref[1];
    tr->walk.next = inner0 ? ref[0] : inner1 ? ref[1] : 0u;
    return false;
}

/* Visits one node; true when the query is answered (the result is in tr->walk.hit): with any_hit
 * at the first hit found, otherwise when no node is left. */
inline bool traversal_step(Traversal *tr, const global TraversalNode *nodes,
                           const global BvhTriangle *tris, bool any_hit, uint *stack)
{
    bool answered = any_hit ? any_hit_visit(tr, nodes, tris, stack)
                            : traversal_visit_children(tr, nodes, tris, false, stack,
                                                       BVH_STACK_SIZE, false, 0u);
    if (answered)
        return true;
    if (tr->walk.next == 0) {
        if (tr->walk.stack_size == 0)
            return true;
        tr->walk.next = stack[--tr->walk.stack_size];
    }
    tr->node = tr->walk.next;
    return false;
}

/* The shared walk: with any_hit it returns at the first hit found, otherwise the closest. */
inline Hit trace_bvh(const global TraversalNode *nodes, const global BvhTriangle *tris,
                     float3 origin, float3 dir, float tmin, float tmax, bool any_hit)
{
    Traversal tr;
    uint stack[BVH_STACK_SIZE];
    traversal_start(&tr, nodes, origin, dir, tmin, tmax);
    while (!traversal_step(&tr, nodes, tris, any_hit, stack))
        ;
    return tr.walk.hit;
}

/* Two levels (host/accel/tlas.c): the TLAS from node 0, whose leaves name instances. One loop,
 * not a walk inside a walk, so that a GPU's lanes in different levels still step together: a
 * TLAS leaf is visited like an inner node, and visiting it moves the ray into the instance's
 * object space (its direction not normalised: t means the same in both spaces) and goes on at the
 * BLAS root, on the same stack; when the BLAS's part of the stack is used up (blas_base), the
 * world ray comes back and the TLAS walk goes on. */
inline Hit trace_scene_bvh(const global TraversalNode *nodes, const global BvhTriangle *tris,
                           const global Instance *instances, const global InstanceMotion *motions,
                           float3 origin, float3 dir, float tmin, float tmax, float time,
                           bool any_hit)
{
    Traversal tr;
    uint stack[BVH_SCENE_STACK_SIZE];
    traversal_start(&tr, nodes, origin, dir, tmin, tmax);
    float world_slack = tr.walk.slack;
    uint instance = HIT_NONE; /* HIT_NONE: walking the TLAS */
    uint blas_base = 0;
    for (;;) {
        if (child_is_leaf(tr.node)) {
            instance = walk_leaf_first(tr.node);
            Affine m = instance_to_object(instances, motions, instance, time);
            float3 o = affine_point(m, origin), d = affine_vector(m, dir);
            uint root = instances[instance].blas_root;
            tr.box = box_ray(o, d);
            tr.tri = watertight_ray(o, d);
            tr.walk.slack = box_slack(&nodes[root], o, tr.tri);
            tr.box_tmin = tmin - tr.walk.slack;
            tr.node = root;
            blas_base = tr.walk.stack_size;
        }
        if (traversal_visit_children(&tr, nodes, tris, any_hit, stack, BVH_SCENE_STACK_SIZE,
                                     instance == HIT_NONE, instance))
            return tr.walk.hit;
        if (tr.walk.next == 0) {
            if (instance != HIT_NONE && tr.walk.stack_size == blas_base) {
                instance = HIT_NONE;
                tr.box = box_ray(origin, dir);
                tr.tri = watertight_ray(origin, dir);
                tr.walk.slack = world_slack;
                tr.box_tmin = tmin - world_slack;
            }
            if (tr.walk.stack_size == 0)
                return tr.walk.hit;
            tr.walk.next = stack[--tr.walk.stack_size];
        }
        tr.node = tr.walk.next;
    }
}

/* Every triangle of every instance, in its object space: the brute-force ablation's two levels. */
inline Hit trace_scene_brute_force(const global BvhTriangle *tris, const global Instance *instances,
                                   const global InstanceMotion *motions, uint num_instances,
                                   float3 origin, float3 dir, float tmin, float tmax, float time,
                                   bool any_hit)
{
    Hit hit = {tmax, 0.0f, 0.0f, HIT_NONE, 0u};
    for (uint i = 0; i < num_instances; i++) {
        Affine m = instance_to_object(instances, motions, i, time);
        WatertightRay ray = watertight_ray(affine_point(m, origin), affine_vector(m, dir));
        if (intersect_leaf(tris, instances[i].first_prim, instances[i].num_prims, ray, tmin, any_hit,
                           &hit, i) &&
            any_hit)
            break;
    }
    return hit;
}

/* Every triangle, no BVH: the baseline of the brute-force ablation (the *_brute_force stages). */
inline Hit trace_brute_force(const global BvhTriangle *tris, uint num_tris, float3 origin,
                             float3 dir, float tmin, float tmax, bool any_hit)
{
    Hit hit = {tmax, 0.0f, 0.0f, HIT_NONE, 0u};
    intersect_leaf(tris, 0u, num_tris, watertight_ray(origin, dir), tmin, any_hit, &hit, 0u);
    return hit;
}

#endif /* BVH_WIDTH == 2 */
