/* SPDX-License-Identifier: MIT */
/* bvh_traverse.cl: closest-hit and any-hit queries used by every kernel that traces rays, and the
 * box-test rules that every layout shares. With BVH_WIDTH == 2 (GPUs) it walks
 * the 2-wide node array of host/accel/bvh_build.c (both child boxes in the parent, Aila & Laine 2009) with a
 * private stack: both child boxes are tested at once, leaf children are intersected right away
 * (nearer first), the nearer inner child is visited next and the farther one is pushed.
 * Hits are reported for tmin <= t < tmax; prim is the original triangle index. */

/* Per-ray constants of the box test. */
typedef struct {
    float3 origin;
    float3 inv_dir;  /* +-inf along axes the ray does not move on */
    int3 dir_negative; /* -1 (all bits) where the direction's sign bit is set, including -0 */
} BoxRay;

/* 1 + 2 gamma(3) (pbrt-v3, "Robust ray-bounds intersection"): widens the exit distance so that
 * rounding in the slab test never culls a box that the watertight triangle test would hit. The
 * quantised test rounds four times per distance (frame origin minus ray origin, times the inverse
 * direction, the fused step, and the inverse direction itself): 1 + 2 gamma(5). Its rounding that
 * is not relative to the distance (from the frame's origin to the plane) is at most 2^-14 of a
 * step, and host/accel/bvh_quantized.c rounds planes outwards by 2^-10 of a step to cover it. */
#if BVH_QUANTIZED
#define BOX_EXIT_SCALE_EXACT 1.0000012f
#else
#define BOX_EXIT_SCALE_EXACT 1.00000036f
#endif
/* Where division is not correctly rounded (NVIDIA without PT_EXACT_MATHS: host/device/program.c
 * passes PT_INEXACT_DIVIDE), the inverse direction may be 2.5 ulp off (OpenCL 1.2's bound)
 * instead of half an ulp: four more roundings' worth, 1 + 2 gamma(4) more. Only a wider box,
 * so the same hits. */
#ifndef PT_INEXACT_DIVIDE
#define PT_INEXACT_DIVIDE 0
#endif
#define BOX_EXIT_SCALE (BOX_EXIT_SCALE_EXACT * (PT_INEXACT_DIVIDE ? 1.00000048f : 1.0f))

inline BoxRay box_ray(float3 origin, float3 dir)
{
    BoxRay ray;
    ray.origin = origin;
    ray.inv_dir = 1.0f / dir;
    ray.dir_negative = signbit(ray.inv_dir);
    return ray;
}

/* max and min that drop a NaN in x (acc is never NaN). NVIDIA's fmax/fmin are single
 * instructions with that behaviour; elsewhere (PoCL on x86) OpenCL's fmax/fmin cost a
 * compare-unordered and a blend per call, and a comparison is one maxss/minss. */
#ifdef PT_VENDOR_NVIDIA
inline float max_into(float x, float acc) { return fmax(x, acc); }
inline float min_into(float x, float acc) { return fmin(x, acc); }
#else
inline float max_into(float x, float acc) { return x > acc ? x : acc; }
inline float min_into(float x, float acc) { return x < acc ? x : acc; }
#endif

/* Whether the ray meets [lo, hi] within [tmin, tmax]; *t_entry gets the clipped entry distance.
 * The entry and exit planes are chosen by the direction's sign, so (plane - origin) * inv_dir only
 * gives NaN (0 * inf) when the ray lies in that plane; max_into/min_into drop the NaN, which
 * treats the ray as inside the slab: boxes are closed. Scalar code: PoCL turns float3 selects
 * into shuffles and blends. */
inline bool box_entry(BoxRay ray, float4 lo, float4 hi, float tmin, float tmax, float *t_entry)
{
    float ex = ray.dir_negative.x ? hi.x : lo.x, xx = ray.dir_negative.x ? lo.x : hi.x;
    float ey = ray.dir_negative.y ? hi.y : lo.y, xy = ray.dir_negative.y ? lo.y : hi.y;
    float ez = ray.dir_negative.z ? hi.z : lo.z, xz = ray.dir_negative.z ? lo.z : hi.z;
    float t0 = max_into((ex - ray.origin.x) * ray.inv_dir.x, tmin);
    t0 = max_into((ey - ray.origin.y) * ray.inv_dir.y, t0);
    t0 = max_into((ez - ray.origin.z) * ray.inv_dir.z, t0);
    float t1 = min_into((xx - ray.origin.x) * ray.inv_dir.x, tmax);
    t1 = min_into((xy - ray.origin.y) * ray.inv_dir.y, t1);
    t1 = min_into((xz - ray.origin.z) * ray.inv_dir.z, t1);
    *t_entry = t0;
    return t0 <= t1 * BOX_EXIT_SCALE;
}

/* Absolute slack on the [tmin, tmax] that boxes are tested against. The watertight test's t has a
 * rounding error proportional to its vertices' distance from the origin (along the dominant
 * axis), not to t: a ray 0.05 into a wall 2 units wide gets t to about 1e-5 relative. A box whose
 * exact entry lies just past tmax (or exit just before tmin) may so hold a triangle reported
 * inside [tmin, tmax); widening by a bound on that error, from the scene's box, keeps the culling
 * conservative at a cost of a few ulps of the scene's size. */
#define BOX_SLACK_ULPS 16.0f
inline float box_slack_of(float3 lo, float3 hi, float3 origin, WatertightRay tray)
{
    float3 reach = fmax(fabs(lo - origin), fabs(hi - origin));
    return BOX_SLACK_ULPS * FLT_EPSILON * fmax(reach.x, fmax(reach.y, reach.z)) * fabs(tray.shear.z);
}

#if BVH_WIDTH == 2 /* else cl/geometry/bvh_traverse_wide.cl; the queries: cl/geometry/bvh_query.cl */
/* A child reference is an inner node index, or a leaf (sign bit set) whose triangle range is
 * spelled differently by the two node formats: the float node has ~first in the reference and the
 * count in a lane of its own (`lane`), the quantised one packs both into the reference. */
inline bool child_is_leaf(uint ref) { return as_int(ref) < 0; }

/* A leaf as an entry of a walk (its next node, its stack, trace_scene_bvh's node) when it is not
 * intersected at once: sign bit, first triangle (a TLAS's: instance) << 4, count. The quantised
 * reference is already this; the float node's leaf is packed so on entry, which bounds its
 * triangles and instances as the quantised layout's (host/accel/scene_bvh.c). */
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

#if BVH_QUANTIZED
inline uint leaf_first(uint ref, uint lane) { return walk_leaf_first(ref); }
inline uint leaf_count(uint ref, uint lane) { return walk_leaf_count(ref); }

/* The frame of a quantised node, as seen by one ray: the distance to the frame's origin planes
 * and the distance per step, per axis (plane = origin + q * step, so t = q * per_step + at_origin). */
typedef struct {
    float3 at_origin, per_step;
} QuantizedFrame;

inline float3 frame_origin(uint4 frame)
{
    return (float3)(as_float(frame.x & ~0xffu), as_float(frame.y & ~0xffu), as_float(frame.z & ~0xffu));
}
inline float3 frame_step(uint4 frame)
{
    return (float3)(as_float((frame.x & 0xffu) << 23), as_float((frame.y & 0xffu) << 23),
                    as_float((frame.z & 0xffu) << 23));
}

inline float box_slack(const global BvhNodeQuantized *root, float3 origin, WatertightRay tray)
{
    float3 lo = frame_origin(root->frame);
    return box_slack_of(lo, lo + 255.0f * frame_step(root->frame), origin, tray);
}

inline float quantized_plane(uint word, uint shift) { return (float)((word >> shift) & 0xffu); }

/* box_entry for the child whose plane bytes start at bit `base` of each axis word (0: left, 16:
 * right). Byte base + 0 is the box's low plane, base + 8 its high one: the entry plane is the
 * high one where the direction is negative. NaN (a ray in a plane, or 0 steps times an infinite
 * inverse direction) is dropped as in box_entry: the box is kept, never wrongly culled. */
inline bool quantized_box_entry(BoxRay ray, QuantizedFrame f, uint3 words, uint base, float tmin,
                                float tmax, float *t_entry)
{
    uint sx = base + ((uint)ray.dir_negative.x & 8u);
    uint sy = base + ((uint)ray.dir_negative.y & 8u);
    uint sz = base + ((uint)ray.dir_negative.z & 8u);
    float t0 = max_into(fma(quantized_plane(words.x, sx), f.per_step.x, f.at_origin.x), tmin);
    t0 = max_into(fma(quantized_plane(words.y, sy), f.per_step.y, f.at_origin.y), t0);
    t0 = max_into(fma(quantized_plane(words.z, sz), f.per_step.z, f.at_origin.z), t0);
    float t1 = min_into(fma(quantized_plane(words.x, sx ^ 8u), f.per_step.x, f.at_origin.x), tmax);
    t1 = min_into(fma(quantized_plane(words.y, sy ^ 8u), f.per_step.y, f.at_origin.y), t1);
    t1 = min_into(fma(quantized_plane(words.z, sz ^ 8u), f.per_step.z, f.at_origin.z), t1);
    *t_entry = t0;
    return t0 <= t1 * BOX_EXIT_SCALE;
}

/* Both children of a node: whether the ray meets each box within [tmin, tmax], where it enters,
 * and the child's reference (lane unused). */
inline void test_children(const global BvhNodeQuantized *node, BoxRay ray, float tmin, float tmax,
                          bool hit[2], float t[2], uint ref[2], uint lane[2])
{
    uint4 frame = node->frame, refs = node->refs;
    QuantizedFrame f;
    f.at_origin = (frame_origin(frame) - ray.origin) * ray.inv_dir;
    f.per_step = frame_step(frame) * ray.inv_dir;
    uint3 words = (uint3)(frame.w, refs.x, refs.y);
    hit[0] = quantized_box_entry(ray, f, words, 0u, tmin, tmax, &t[0]);
    hit[1] = quantized_box_entry(ray, f, words, 16u, tmin, tmax, &t[1]);
    ref[0] = refs.z;
    ref[1] = refs.w;
    lane[0] = lane[1] = 0u;
}
#else
inline uint leaf_first(uint ref, uint lane) { return ~ref; }
inline uint leaf_count(uint ref, uint lane) { return lane; }

inline float box_slack(const global BvhNode *root, float3 origin, WatertightRay tray)
{
    float3 lo = fmin(xyz(root->lmin), xyz(root->rmin));
    float3 hi = fmax(xyz(root->lmax), xyz(root->rmax));
    return box_slack_of(lo, hi, origin, tray);
}

/* The float node: references in the w lanes of the box minima, leaf counts in those of the maxima. */
inline void test_children(const global BvhNode *node, BoxRay ray, float tmin, float tmax,
                          bool hit[2], float t[2], uint ref[2], uint lane[2])
{
    float4 lmin = node->lmin, lmax = node->lmax, rmin = node->rmin, rmax = node->rmax;
    hit[0] = box_entry(ray, lmin, lmax, tmin, tmax, &t[0]);
    hit[1] = box_entry(ray, rmin, rmax, tmin, tmax, &t[1]);
    ref[0] = as_uint(lmin.w);
    ref[1] = as_uint(rmin.w);
    lane[0] = as_uint(lmax.w);
    lane[1] = as_uint(rmax.w);
}
#endif

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
            return intersect_leaf(tris, leaf_first(ref, lane), leaf_count(ref, lane), ray, tmin,
                                  any_hit, &walk->hit, instance) &&
                   any_hit;
        /* The empty TLAS's leaf names no instance (a quantised empty box may pass the test). */
        uint count = leaf_count(ref, lane);
        if (count == 0u)
            return false;
        ref = walk_leaf(leaf_first(ref, lane), count);
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

/* Visits one node; true when the query is answered (the result is in tr->walk.hit): with any_hit
 * at the first hit found, otherwise when no node is left. */
#ifdef PT_EXP_TIGHT_ANY
/* Experiment (-DPT_EXP_TIGHT_ANY, bench/results/throughput-41/session13/next-call.sh): an any-hit
 * visit without what only closest hits need. The query ends at its first hit, so hit.t never
 * shrinks during the walk and the second cull cannot fire, and the children need no order: leaf
 * children are intersected at once, the left inner child is next and the right one pushed. */
inline bool any_hit_visit(Traversal *tr, const global TraversalNode *nodes,
                          const global BvhTriangle *tris, uint *stack)
{
    bool hit[2];
    float t[2];
    uint ref[2], lane[2];
    traversal_test_children(tr, nodes, hit, t, ref, lane);
    bool leaf0 = child_is_leaf(ref[0]), leaf1 = child_is_leaf(ref[1]);
    if (hit[0] && leaf0 &&
        intersect_leaf(tris, leaf_first(ref[0], lane[0]), leaf_count(ref[0], lane[0]), tr->tri,
                       tr->tmin, true, &tr->walk.hit, 0u))
        return true;
    if (hit[1] && leaf1 &&
        intersect_leaf(tris, leaf_first(ref[1], lane[1]), leaf_count(ref[1], lane[1]), tr->tri,
                       tr->tmin, true, &tr->walk.hit, 0u))
        return true;
    bool inner0 = hit[0] && !leaf0, inner1 = hit[1] && !leaf1;
    if (inner0 && inner1 && tr->walk.stack_size < BVH_STACK_SIZE)
        stack[tr->walk.stack_size++] = ref[1];
    tr->walk.next = inner0 ? ref[0] : inner1 ? ref[1] : 0u;
    return false;
}
#endif

inline bool traversal_step(Traversal *tr, const global TraversalNode *nodes,
                           const global BvhTriangle *tris, bool any_hit, uint *stack)
{
#ifdef PT_EXP_TIGHT_ANY
    if (any_hit ? any_hit_visit(tr, nodes, tris, stack)
                : traversal_visit_children(tr, nodes, tris, false, stack, BVH_STACK_SIZE, false, 0u))
        return true;
#else
    if (traversal_visit_children(tr, nodes, tris, any_hit, stack, BVH_STACK_SIZE, false, 0u))
        return true;
#endif
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
