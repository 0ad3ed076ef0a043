/* SPDX-License-Identifier: MIT */
/* bvh_traverse.cl: closest-hit and any-hit queries used by every kernel that traces rays, and the
 * box-test rules that every layout shares. With BVH_WIDTH == 2 (GPUs) it walks
 * the 2-wide node array of host/bvh.c (both child boxes in the parent, Aila & Laine 2009) with a
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
 * rounding in the slab test never culls a box that the watertight triangle test would hit. */
#define BOX_EXIT_SCALE 1.00000036f

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

#if BVH_WIDTH == 2 /* else cl/bvh_traverse_wide.cl; trace_closest and trace_any follow it */
inline float box_slack(const global BvhNode *root, float3 origin, WatertightRay tray)
{
    float3 lo = fmin(xyz(root->lmin), xyz(root->rmin));
    float3 hi = fmax(xyz(root->lmax), xyz(root->rmax));
    return box_slack_of(lo, hi, origin, tray);
}

/* Leaf children carry ~first_triangle (a negative int) in the box-min w lane and their triangle
 * count in the box-max w lane. */
inline bool child_is_leaf(float4 lo) { return as_int(lo.w) < 0; }
inline uint leaf_first(float4 lo) { return ~as_uint(lo.w); }
inline uint leaf_count(float4 hi) { return as_uint(hi.w); }

/* Intersects the leaf's triangles, shrinking hit->t; true when any hit (for early exit). */
inline bool intersect_leaf(const global BvhTriangle *tris, uint first, uint count,
                           WatertightRay ray, float tmin, bool any_hit, Hit *hit)
{
    bool found = false;
    for (uint i = first; i < first + count; i++) {
        COUNT_STEPS(*hit, 0u, 1u);
        float t, u, v;
        if (intersect_triangle_watertight(ray, xyz(tris[i].v0), xyz(tris[i].v1), xyz(tris[i].v2),
                                          tmin, hit->t, &t, &u, &v)) {
            hit->t = t;
            hit->u = u;
            hit->v = v;
            hit->prim = as_uint(tris[i].v0.w);
            found = true;
            if (any_hit)
                break;
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

/* Visits one child whose box the ray meets at t_entry: a leaf is intersected now, an inner node
 * becomes the next node or, if there is one already, goes on the stack. True when an any-hit query
 * is answered. */
inline bool visit_child(const global BvhTriangle *tris, float4 lo, float4 hi, float t_entry,
                        WatertightRay ray, float tmin, bool any_hit, Walk *walk, uint *stack)
{
    /* The sibling visited first may have moved the closest hit in front of this box. */
    if (!(t_entry <= (walk->hit.t + walk->slack) * BOX_EXIT_SCALE))
        return false;
    if (child_is_leaf(lo))
        return intersect_leaf(tris, leaf_first(lo), leaf_count(hi), ray, tmin, any_hit, &walk->hit) &&
               any_hit;
    if (walk->next == 0)
        walk->next = as_uint(lo.w);
    else if (walk->stack_size < BVH_STACK_SIZE) /* always true: the builder bounds the depth */
        stack[walk->stack_size++] = as_uint(lo.w);
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

inline void traversal_start(Traversal *tr, const global BvhNode *nodes, float3 origin, float3 dir,
                            float tmin, float tmax)
{
    tr->box = box_ray(origin, dir);
    tr->tri = watertight_ray(origin, dir);
    Walk walk = {{tmax, 0.0f, 0.0f, HIT_NONE}, 0, 0, box_slack(nodes, origin, tr->tri)};
    tr->walk = walk;
    tr->tmin = tmin;
    tr->box_tmin = tmin - walk.slack;
    tr->node = 0;
}

/* Visits one node; true when the query is answered (the result is in tr->walk.hit): with any_hit
 * at the first hit found, otherwise when no node is left. */
inline bool traversal_step(Traversal *tr, const global BvhNode *nodes, const global BvhTriangle *tris,
                           bool any_hit, uint *stack)
{
    COUNT_STEPS(tr->walk.hit, 1u, 0u);
    float4 near_lo = nodes[tr->node].lmin, near_hi = nodes[tr->node].lmax;
    float4 far_lo = nodes[tr->node].rmin, far_hi = nodes[tr->node].rmax;
    float t_near, t_far;
    float box_tmax = tr->walk.hit.t + tr->walk.slack;
    bool hit_near = box_entry(tr->box, near_lo, near_hi, tr->box_tmin, box_tmax, &t_near);
    bool hit_far = box_entry(tr->box, far_lo, far_hi, tr->box_tmin, box_tmax, &t_far);
    /* Nearer child first: it is the more likely to shorten hit.t for the other. */
    if (hit_far && (!hit_near || t_far < t_near)) {
        float4 lo = near_lo;
        float4 hi = near_hi;
        float t = t_near;
        near_lo = far_lo;
        near_hi = far_hi;
        t_near = t_far;
        far_lo = lo;
        far_hi = hi;
        t_far = t;
        hit_far = hit_near;
        hit_near = true;
    }
    tr->walk.next = 0;
    if (hit_near &&
        visit_child(tris, near_lo, near_hi, t_near, tr->tri, tr->tmin, any_hit, &tr->walk, stack))
        return true;
    if (hit_far &&
        visit_child(tris, far_lo, far_hi, t_far, tr->tri, tr->tmin, any_hit, &tr->walk, stack))
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
inline Hit trace_bvh(const global BvhNode *nodes, const global BvhTriangle *tris, float3 origin,
                     float3 dir, float tmin, float tmax, bool any_hit)
{
    Traversal tr;
    uint stack[BVH_STACK_SIZE];
    traversal_start(&tr, nodes, origin, dir, tmin, tmax);
    while (!traversal_step(&tr, nodes, tris, any_hit, stack))
        ;
    return tr.walk.hit;
}

/* Every triangle, no BVH: the baseline of the brute-force ablation (RENDER_BRUTE_FORCE). */
inline Hit trace_brute_force(const global BvhTriangle *tris, uint num_tris, float3 origin,
                             float3 dir, float tmin, float tmax, bool any_hit)
{
    Hit hit = {tmax, 0.0f, 0.0f, HIT_NONE};
    intersect_leaf(tris, 0u, num_tris, watertight_ray(origin, dir), tmin, any_hit, &hit);
    return hit;
}

#endif /* BVH_WIDTH == 2 */
