/* SPDX-License-Identifier: MIT */
/* bvh_traverse_wide.cl: trace_closest, trace_any and trace_brute_force over the wide layout of
 * host/accel/bvh_wide.c (BVH_WIDTH 4 or 8: CPUs). A CPU runs each work item on one core, one operation
 * after another; here one floatW operation tests all of a node's child boxes, or all triangles of
 * a pack, so the SIMD units do the work in parallel that a GPU spreads over its lanes.
 * The tests are the 2-wide ones lane by lane: the same slab test with the same rounding slack
 * (box_test.cl) and the same watertight triangle test (intersect_triangle.cl), operation for
 * operation, so every layout reports the same hits. Hits are reported for tmin <= t < tmax. */
#if BVH_WIDTH != 2

#if BVH_WIDTH == 8
typedef float8 floatW;
typedef int8 intW;
typedef uint8 uintW;
#define VSTORE_W vstore8
#define LANE_BITS(m)                                                                               \
    (LANE_BIT(m, 0, s0) | LANE_BIT(m, 1, s1) | LANE_BIT(m, 2, s2) | LANE_BIT(m, 3, s3) |            \
     LANE_BIT(m, 4, s4) | LANE_BIT(m, 5, s5) | LANE_BIT(m, 6, s6) | LANE_BIT(m, 7, s7))
#else
typedef float4 floatW;
typedef int4 intW;
typedef uint4 uintW;
#define VSTORE_W vstore4
#define LANE_BITS(m) (LANE_BIT(m, 0, s0) | LANE_BIT(m, 1, s1) | LANE_BIT(m, 2, s2) | LANE_BIT(m, 3, s3))
#endif
#define LANE_BIT(m, i, lane) ((as_uint((m).lane) >> 31) << (i))

/* A comparison's lanes (all bits set where true) as a bit mask, lane i in bit i. OpenCL C has no
 * movemask; where the compiler is clang on AVX (PoCL on x86), its builtin is one instruction,
 * where the portable shifts and ORs took about ten per node and per pack (PoCL: Cornell box +10%,
 * dragon 4-8% fewer CPU seconds, bench/README.md "CPU (PoCL) throughput"). */
#if BVH_WIDTH == 8 && defined(__clang__) && defined(__AVX__) && !defined(PT_VENDOR_NVIDIA)
typedef float LaneMaskFloats __attribute__((vector_size(32)));
inline uint lane_bits(intW m) { return (uint)__builtin_ia32_movmskps256((LaneMaskFloats)as_float8(m)); }
#else
inline uint lane_bits(intW m) { return LANE_BITS(m); }
#endif

/* The lowest set bit's index (OpenCL 1.2 has clz but no ctz); bits != 0. */
inline uint lowest_lane(uint bits) { return 31u - clz(bits & (0u - bits)); }

/* max_into / min_into of box_test.cl, lane by lane: a NaN in x leaves acc. */
#ifdef PT_VENDOR_NVIDIA
inline floatW max_into_w(floatW x, floatW acc) { return fmax(x, acc); }
inline floatW min_into_w(floatW x, floatW acc) { return fmin(x, acc); }
#else
inline floatW max_into_w(floatW x, floatW acc) { return select(acc, x, x > acc); }
inline floatW min_into_w(floatW x, floatW acc) { return select(acc, x, x < acc); }
#endif

/* A node viewed as six rows of lanes: lo x, y, z, then hi x, y, z. Per axis the ray enters
 * through the lo row where it moves toward +, else through the hi row (box_entry's choice). */
typedef struct {
    float3 origin;
    float3 inv_dir;
    int entry_row[3], exit_row[3];
} WideRay;

inline WideRay wide_ray(float3 origin, float3 dir)
{
    WideRay ray;
    ray.origin = origin;
    ray.inv_dir = 1.0f / dir;
    int3 negative = signbit(ray.inv_dir);
    ray.entry_row[0] = negative.x ? 3 : 0, ray.exit_row[0] = negative.x ? 0 : 3;
    ray.entry_row[1] = negative.y ? 4 : 1, ray.exit_row[1] = negative.y ? 1 : 4;
    ray.entry_row[2] = negative.z ? 5 : 2, ray.exit_row[2] = negative.z ? 2 : 5;
    return ray;
}

/* The children whose boxes the ray meets within [tmin, tmax], as lane bits; t_entry[lane] gets the
 * clipped entry distances. Unused lanes hold empty boxes (+inf .. -inf) and never pass. */
inline uint wide_box_hits(const global TraversalNode *node, WideRay ray, float tmin, float tmax,
                          float *t_entry)
{
    const global floatW *rows = (const global floatW *)node;
    floatW t0 = max_into_w((rows[ray.entry_row[0]] - ray.origin.x) * ray.inv_dir.x, (floatW)(tmin));
    t0 = max_into_w((rows[ray.entry_row[1]] - ray.origin.y) * ray.inv_dir.y, t0);
    t0 = max_into_w((rows[ray.entry_row[2]] - ray.origin.z) * ray.inv_dir.z, t0);
    floatW t1 = min_into_w((rows[ray.exit_row[0]] - ray.origin.x) * ray.inv_dir.x, (floatW)(tmax));
    t1 = min_into_w((rows[ray.exit_row[1]] - ray.origin.y) * ray.inv_dir.y, t1);
    t1 = min_into_w((rows[ray.exit_row[2]] - ray.origin.z) * ray.inv_dir.z, t1);
    VSTORE_W(t0, 0, t_entry);
    return lane_bits(t0 <= t1 * BOX_EXIT_SCALE);
}

/* The smallest and largest lane (boxes hold no NaN); empty lanes, +inf .. -inf, drop out. */
inline float lane_min(floatW x)
{
#if BVH_WIDTH == 8
    float4 m = x.lo < x.hi ? x.lo : x.hi;
#else
    float4 m = x;
#endif
    float2 n = m.lo < m.hi ? m.lo : m.hi;
    return n.x < n.y ? n.x : n.y;
}
inline float lane_max(floatW x) { return -lane_min(-x); }

/* box_slack over the root's lanes. */
inline float wide_box_slack(const global TraversalNode *root, float3 origin, WatertightRay tray)
{
    float3 lo = (float3)(lane_min(root->lo[0]), lane_min(root->lo[1]), lane_min(root->lo[2]));
    float3 hi = (float3)(lane_max(root->hi[0]), lane_max(root->hi[1]), lane_max(root->hi[2]));
    return box_slack_of(lo, hi, origin, tray);
}

/* difference_of_products, lane by lane. */
inline floatW difference_of_products_w(floatW a, floatW b, floatW c, floatW d)
{
    floatW cd = c * d;
    floatW cd_error = fma(-c, d, cd);
    return fma(a, b, -cd) + cd_error;
}

/* intersect_triangle_watertight from the sheared corners (shear_vertex's x and y, z scaled by
 * shear.z), lane by lane: the edge functions w1 and w2 (w0 only decides), 1 / det and t; inside
 * where the edge functions share a sign and det != 0. The pack test (8 triangles, one ray) and
 * the packet test (one triangle, 8 rays, bvh_traverse_packet.cl) both end in it, so every lane of
 * either computes what the scalar test does. */
typedef struct {
    floatW w1, w2, inv_det, t;
    intW inside;
} EdgeTestW;

PT_INLINE EdgeTestW edge_test_w(floatW ax, floatW ay, floatW az, floatW bx, floatW by, floatW bz,
                                floatW cx, floatW cy, floatW cz)
{
    EdgeTestW e;
    floatW w0 = difference_of_products_w(cx, by, cy, bx);
    e.w1 = difference_of_products_w(ax, cy, ay, cx);
    e.w2 = difference_of_products_w(bx, ay, by, ax);
    intW negative = (w0 < 0.0f) | (e.w1 < 0.0f) | (e.w2 < 0.0f);
    intW positive = (w0 > 0.0f) | (e.w1 > 0.0f) | (e.w2 > 0.0f);
    floatW det = w0 + e.w1 + e.w2;
    e.inv_det = 1.0f / det;
    e.t = fma(w0, az, fma(e.w1, bz, e.w2 * cz)) * e.inv_det;
    e.inside = ~(negative & positive) & (det != 0.0f);
    return e;
}

/* The pack test's per-ray constants: watertight_ray's with the origin permuted once per ray, where
 * the scalar test permutes (vertex - origin) per vertex; the same values either way. */
typedef struct {
    float3 origin; /* permuted */
    float3 shear;
    int axis_z;
} PackRay;

inline PackRay pack_ray(WatertightRay ray)
{
    PackRay pray = {permute_axes(ray.origin, ray.axis_z), ray.shear, ray.axis_z};
    return pray;
}

/* intersect_triangle_watertight on every lane of a pack (of `instance`); the nearest lane that
 * hits within [tmin, hit->t) replaces *hit (with any_hit, the first one). True when one did. */
PT_INLINE bool intersect_pack(const global TraversalPrim *pack, PackRay ray, float tmin,
                           bool any_hit, Hit *hit, uint instance)
{
    const global floatW *v = pack->v;
    int kz = ray.axis_z, kx = kz == 2 ? 0 : kz + 1, ky = kx == 2 ? 0 : kx + 1;
    floatW sx = (floatW)(-ray.shear.x), sy = (floatW)(-ray.shear.y);
    /* shear_vertex for corners a, b, c (rows 0-2, 3-5, 6-8). */
    floatW az = v[kz] - ray.origin.z, bz = v[3 + kz] - ray.origin.z, cz = v[6 + kz] - ray.origin.z;
    floatW ax = fma(sx, az, v[kx] - ray.origin.x), ay = fma(sy, az, v[ky] - ray.origin.y);
    floatW bx = fma(sx, bz, v[3 + kx] - ray.origin.x), by = fma(sy, bz, v[3 + ky] - ray.origin.y);
    floatW cx = fma(sx, cz, v[6 + kx] - ray.origin.x), cy = fma(sy, cz, v[6 + ky] - ray.origin.y);
    EdgeTestW e = edge_test_w(ax, ay, az * ray.shear.z, bx, by, bz * ray.shear.z, cx, cy,
                              cz * ray.shear.z);
    floatW t = e.t;
    /* Ties at exactly hit->t go to the lower (instance, original index) (hit_tie_limit,
     * hit_wins); before any hit nothing ties, hit->t being the ray's tmax. */
    uintW prims = pack->prim;
    uint tie_below = hit->prim == HIT_NONE ? 0u : hit->prim;
    if (PT_FEATURE(INSTANCES) && hit->prim != HIT_NONE && instance != hit->instance)
        tie_below = instance < hit->instance ? HIT_NONE : 0u;
    intW closer = (t < hit->t) | ((t == hit->t) & (prims < (uintW)(tie_below)));
    uint bits = lane_bits(e.inside & (t >= tmin) & closer);
    if (bits == 0u)
        return false;
    float ts[BVH_WIDTH], us[BVH_WIDTH], vs[BVH_WIDTH];
    const global uint *lane_prim = (const global uint *)&pack->prim;
    VSTORE_W(t, 0, ts);
    uint best = lowest_lane(bits);
    if (!any_hit)
        for (bits &= bits - 1u; bits != 0u; bits &= bits - 1u) {
            uint lane = lowest_lane(bits);
            if (ts[lane] < ts[best] || (ts[lane] == ts[best] && lane_prim[lane] < lane_prim[best]))
                best = lane;
        }
    VSTORE_W(e.w1 * e.inv_det, 0, us);
    VSTORE_W(e.w2 * e.inv_det, 0, vs);
    hit->t = ts[best];
    hit->u = us[best];
    hit->v = vs[best];
    hit->prim = lane_prim[best];
    hit->instance = instance;
    return true;
}

/* A leaf reference ~(first_pack << BVH_WIDE_LEAF_PACK_BITS | (pack_count - 1)). */
PT_INLINE bool intersect_wide_leaf(const global TraversalPrim *packs, uint ref, PackRay ray,
                                float tmin, bool any_hit, Hit *hit, uint instance)
{
    uint code = ~ref;
    uint first = code >> BVH_WIDE_LEAF_PACK_BITS;
    uint last = first + (code & ((1u << BVH_WIDE_LEAF_PACK_BITS) - 1u));
    bool found = false;
    for (uint p = first; p <= last; p++) {
        COUNT_STEPS(*hit, 0u, 1u);
        if (intersect_pack(&packs[p], ray, tmin, any_hit, hit, instance)) {
            found = true;
            if (any_hit)
                break;
        }
    }
    return found;
}

inline bool is_leaf_ref(uint ref) { return (int)ref < 0; }

/* The children of a node whose boxes the ray meets (bits, entry distances t_entry): returns the
 * nearest, to visit next, and pushes the others among this node's pushes nearest on top (with
 * any_hit unsorted). capacity is never reached: the layouts bound the stack. */
PT_INLINE uint visit_children(const global TraversalNode *node, uint bits, const float *t_entry,
                              bool any_hit, uint *stack_ref, float *stack_t, uint *stack_size,
                              uint capacity)
{
    const global uint *child = (const global uint *)&node->child;
    uint lane = lowest_lane(bits);
    uint near_ref = child[lane];
    float near_t = t_entry[lane];
    uint base = *stack_size, size = *stack_size;
    for (bits &= bits - 1u; bits != 0u; bits &= bits - 1u) {
        lane = lowest_lane(bits);
        uint r = child[lane];
        float t = t_entry[lane];
        if (!any_hit && t < near_t) {
            uint swap_ref = near_ref;
            float swap_t = near_t;
            near_ref = r, near_t = t;
            r = swap_ref, t = swap_t;
        }
        uint j = size;
        if (j == capacity)
            break;
        size++;
        if (!any_hit)
            for (; j > base && stack_t[j - 1] < t; j--) {
                stack_ref[j] = stack_ref[j - 1];
                stack_t[j] = stack_t[j - 1];
            }
        stack_ref[j] = r;
        stack_t[j] = t;
    }
    *stack_size = size;
    return near_ref;
}

/* The walk of the subtree at ref, from the hit found so far: the nearest child that the ray meets
 * is visited next and the others are pushed with their entry distances, farther ones deeper, so
 * pops come nearest first; a popped entry that now lies behind the closest hit is skipped. With
 * any_hit it returns at the first hit, unsorted. trace_bvh walks the whole tree, trace_packet
 * (bvh_traverse_packet.cl) hands its rays subtrees that too few of them enter. */
PT_INLINE Hit walk_wide(const global TraversalNode *nodes, const global TraversalPrim *packs,
                        WideRay bray, PackRay pray, float slack, float tmin, uint ref, Hit hit,
                        bool any_hit)
{
    float box_tmin = tmin - slack;
    uint stack_ref[BVH_WIDE_STACK_SIZE];
    float stack_t[BVH_WIDE_STACK_SIZE];
    uint stack_size = 0;
    for (;;) {
        if (!is_leaf_ref(ref)) {
            COUNT_STEPS(hit, 1u, 0u);
            float t_entry[BVH_WIDTH];
            uint bits = wide_box_hits(&nodes[ref], bray, box_tmin, hit.t + slack, t_entry);
            if (bits != 0u) {
                ref = visit_children(&nodes[ref], bits, t_entry, any_hit, stack_ref, stack_t,
                                     &stack_size, BVH_WIDE_STACK_SIZE);
                continue;
            }
        } else if (intersect_wide_leaf(packs, ref, pray, tmin, any_hit, &hit, 0u) && any_hit) {
            return hit;
        }
        /* Pop the nearest entry that may still hold a hit in front of the closest one. */
        do {
            if (stack_size == 0u)
                return hit;
            stack_size--;
        } while (!(stack_t[stack_size] <= (hit.t + slack) * BOX_EXIT_SCALE));
        ref = stack_ref[stack_size];
    }
}

inline Hit trace_bvh(const global TraversalNode *nodes, const global TraversalPrim *packs,
                      float3 origin, float3 dir, float tmin, float tmax, bool any_hit)
{
    WatertightRay tray = watertight_ray(origin, dir);
    Hit hit = {tmax, 0.0f, 0.0f, HIT_NONE, 0u};
    return walk_wide(nodes, packs, wide_ray(origin, dir), pack_ray(tray),
                     wide_box_slack(nodes, origin, tray), tmin, 0u /* the root */, hit, any_hit);
}

/* Every pack, no tree: the baseline of the brute-force ablation (the *_brute_force stages). */
inline Hit trace_brute_force(const global TraversalPrim *packs, uint num_packs, float3 origin,
                             float3 dir, float tmin, float tmax, bool any_hit)
{
    Hit hit = {tmax, 0.0f, 0.0f, HIT_NONE, 0u};
    PackRay ray = pack_ray(watertight_ray(origin, dir));
    for (uint p = 0; p < num_packs; p++)
        if (intersect_pack(&packs[p], ray, tmin, any_hit, &hit, 0u) && any_hit)
            break;
    return hit;
}

/* Two levels (host/accel/tlas.c): trace_bvh's walk from the TLAS at node 0, whose leaves
 * (~instance) are visited like inner nodes: visiting one moves the ray into the instance's object
 * space (direction not normalised: t means the same in both spaces) and goes on at its BLAS root
 * on the same stack; when the BLAS's entries are used up (blas_base) the world ray comes back. */
inline Hit trace_scene_bvh(const global TraversalNode *nodes, const global TraversalPrim *packs,
                           const global Instance *instances, const global InstanceMotion *motions,
                           float3 origin, float3 dir, float tmin, float tmax, float time,
                           bool any_hit)
{
    WideRay bray = wide_ray(origin, dir);
    WatertightRay tray = watertight_ray(origin, dir);
    PackRay pray = pack_ray(tray);
    Hit hit = {tmax, 0.0f, 0.0f, HIT_NONE, 0u};
    float world_slack = wide_box_slack(nodes, origin, tray);
    float slack = world_slack, box_tmin = tmin - slack;
    uint stack_ref[BVH_WIDE_SCENE_STACK_SIZE];
    float stack_t[BVH_WIDE_SCENE_STACK_SIZE];
    uint stack_size = 0, blas_base = 0;
    uint instance = HIT_NONE; /* HIT_NONE: walking the TLAS */
    uint ref = 0;
    for (;;) {
        if (is_leaf_ref(ref) && instance == HIT_NONE) {
            instance = ~ref;
            Affine m = instance_to_object(instances, motions, instance, time);
            float3 o = affine_point(m, origin), d = affine_vector(m, dir);
            ref = instances[instance].blas_root;
            bray = wide_ray(o, d);
            tray = watertight_ray(o, d);
            pray = pack_ray(tray);
            slack = wide_box_slack(&nodes[ref], o, tray);
            box_tmin = tmin - slack;
            blas_base = stack_size;
        }
        if (!is_leaf_ref(ref)) {
            COUNT_STEPS(hit, 1u, 0u);
            float t_entry[BVH_WIDTH];
            uint bits = wide_box_hits(&nodes[ref], bray, box_tmin, hit.t + slack, t_entry);
            if (bits != 0u) {
                ref = visit_children(&nodes[ref], bits, t_entry, any_hit, stack_ref, stack_t,
                                     &stack_size, BVH_WIDE_SCENE_STACK_SIZE);
                continue;
            }
        } else if (intersect_wide_leaf(packs, ref, pray, tmin, any_hit, &hit, instance) && any_hit) {
            return hit;
        }
        /* Pop the nearest entry that may still hold a hit in front of the closest one; below the
         * BLAS's entries, the TLAS's with the world ray. */
        for (;;) {
            if (instance != HIT_NONE && stack_size == blas_base) {
                instance = HIT_NONE;
                bray = wide_ray(origin, dir);
                tray = watertight_ray(origin, dir);
                pray = pack_ray(tray);
                slack = world_slack;
                box_tmin = tmin - slack;
            }
            if (stack_size == 0u)
                return hit;
            stack_size--;
            if (stack_t[stack_size] <= (hit.t + slack) * BOX_EXIT_SCALE)
                break;
        }
        ref = stack_ref[stack_size];
    }
}

/* Every pack of every instance, in its object space: the brute-force ablation's two levels. */
inline Hit trace_scene_brute_force(const global TraversalPrim *packs,
                                   const global Instance *instances,
                                   const global InstanceMotion *motions, uint num_instances,
                                   float3 origin, float3 dir, float tmin, float tmax, float time,
                                   bool any_hit)
{
    Hit hit = {tmax, 0.0f, 0.0f, HIT_NONE, 0u};
    for (uint i = 0; i < num_instances; i++) {
        Affine m = instance_to_object(instances, motions, i, time);
        PackRay ray = pack_ray(watertight_ray(affine_point(m, origin), affine_vector(m, dir)));
        uint first = instances[i].first_prim, end = first + instances[i].num_prims;
        for (uint p = first; p < end; p++)
            if (intersect_pack(&packs[p], ray, tmin, any_hit, &hit, i) && any_hit)
                return hit;
    }
    return hit;
}

#endif /* BVH_WIDTH != 2 */
