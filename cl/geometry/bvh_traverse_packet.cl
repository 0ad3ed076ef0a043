/* SPDX-License-Identifier: MIT */
/* bvh_traverse_packet.cl: trace_packet, eight rays walked together through the 8-wide layout
 * (CPUs), one ray per lane of float8. Where the rays are coherent (one pixel's samples, their first
 * bounces) they visit the same nodes, and one visit serves all eight: its loads, its branches and
 * its stack traffic are shared, and the eight independent box and triangle tests keep the core's
 * pipelines full where one ray's walk waits on each step (Embree's packets, Wald et al. 2001).
 * Per ray the tests are trace_bvh's, operation for operation: the same slab test of each child box
 * with the same slack, the same watertight triangle test and the same tie rule, so each lane
 * reports the hit trace_bvh reports (the closest (t, triangle) in [tmin, tmax); any_hit: whether
 * one exists). Only the culling differs: an entry is skipped when it lies behind every live lane's
 * closest hit, which is conservative for each lane. One level only (no instances). */
#if BVH_WIDTH == 8

typedef struct {
    float8 t, u, v;
    uint8 prim;
} HitPacket;

/* Per lane x, y or z as axis is 0, 1 or 2. */
inline float8 pick_axis_w(intW axis, float8 x, float8 y, float8 z)
{
    return select(select(x, y, axis == 1), z, axis == 2);
}
inline float8 pick_axis(intW axis, float x, float y, float z)
{
    return pick_axis_w(axis, (float8)(x), (float8)(y), (float8)(z));
}

/* Eight rays: box test constants (wide_ray's, lane by lane), watertight test constants
 * (pack_ray's) and the box slack of each (wide_box_slack). */
typedef struct {
    float8 ox, oy, oz, ix, iy, iz;
    intW negx, negy, negz;
    intW kz;
    float8 px, py, pz; /* origins permuted as pack_ray permutes them */
    float8 sx, sy, sz; /* -shear.x, -shear.y, shear.z */
    float8 slack, box_tmin, tmin;
} RayPacket;

/* The packet of rays origin[i], dir[i], tmin[i] (lanes without a ray hold any ray: trace_packet's
 * live mask leaves them out). Lane by lane the values are those of wide_ray, watertight_ray,
 * pack_ray and wide_box_slack for the lane's ray: the same operations on eight lanes at once. */
inline RayPacket ray_packet(const global TraversalNode *root, const float3 *origin, const float3 *dir,
                            const float *tmin)
{
    float f[7][8];
    for (int i = 0; i < 8; i++) {
        f[0][i] = origin[i].x, f[1][i] = origin[i].y, f[2][i] = origin[i].z;
        f[3][i] = dir[i].x, f[4][i] = dir[i].y, f[5][i] = dir[i].z;
        f[6][i] = tmin[i];
    }
    RayPacket r;
    r.ox = vload8(0, f[0]), r.oy = vload8(0, f[1]), r.oz = vload8(0, f[2]);
    float8 dx = vload8(0, f[3]), dy = vload8(0, f[4]), dz = vload8(0, f[5]);
    r.tmin = vload8(0, f[6]);
    /* wide_ray */
    r.ix = 1.0f / dx, r.iy = 1.0f / dy, r.iz = 1.0f / dz;
    r.negx = signbit(r.ix), r.negy = signbit(r.iy), r.negz = signbit(r.iz);
    /* watertight_ray: axis_z the largest |d| (ties to x, then y), d permuted to (kx, ky, kz) */
    float8 ax = fabs(dx), ay = fabs(dy), az = fabs(dz);
    r.kz = select(select((intW)(2), (intW)(1), ay >= az), select((intW)(2), (intW)(0), ax >= az),
                  ax >= ay);
    float8 d_x = pick_axis_w(r.kz, dy, dz, dx), d_y = pick_axis_w(r.kz, dz, dx, dy);
    float8 d_z = pick_axis_w(r.kz, dx, dy, dz);
    r.sx = -(d_x / d_z), r.sy = -(d_y / d_z), r.sz = 1.0f / d_z;
    /* pack_ray: the origin permuted */
    r.px = pick_axis_w(r.kz, r.oy, r.oz, r.ox), r.py = pick_axis_w(r.kz, r.oz, r.ox, r.oy);
    r.pz = pick_axis_w(r.kz, r.ox, r.oy, r.oz);
    /* wide_box_slack: box_slack_of over the root's lanes */
    float lo_x = lane_min(root->lo[0]), lo_y = lane_min(root->lo[1]), lo_z = lane_min(root->lo[2]);
    float hi_x = lane_max(root->hi[0]), hi_y = lane_max(root->hi[1]), hi_z = lane_max(root->hi[2]);
    float8 reach_x = fmax(fabs(lo_x - r.ox), fabs(hi_x - r.ox));
    float8 reach_y = fmax(fabs(lo_y - r.oy), fabs(hi_y - r.oy));
    float8 reach_z = fmax(fabs(lo_z - r.oz), fabs(hi_z - r.oz));
    r.slack = BOX_SLACK_ULPS * FLT_EPSILON * fmax(reach_x, fmax(reach_y, reach_z)) * fabs(r.sz);
    r.box_tmin = r.tmin - r.slack;
    return r;
}

/* Lane k of a float8 or int8 (in private memory). */
inline float lane_f(const float8 *v, uint k) { return ((const float *)v)[k]; }
inline int lane_i(const intW *v, uint k) { return ((const int *)v)[k]; }

/* Lane k's single-ray constants, for the subtrees a packet hands to its rays one by one. */
inline WideRay wide_ray_lane(const RayPacket *r, uint k)
{
    WideRay ray;
    ray.origin = (float3)(lane_f(&r->ox, k), lane_f(&r->oy, k), lane_f(&r->oz, k));
    ray.inv_dir = (float3)(lane_f(&r->ix, k), lane_f(&r->iy, k), lane_f(&r->iz, k));
    bool nx = lane_i(&r->negx, k) != 0, ny = lane_i(&r->negy, k) != 0, nz = lane_i(&r->negz, k) != 0;
    ray.entry_row[0] = nx ? 3 : 0, ray.exit_row[0] = nx ? 0 : 3;
    ray.entry_row[1] = ny ? 4 : 1, ray.exit_row[1] = ny ? 1 : 4;
    ray.entry_row[2] = nz ? 5 : 2, ray.exit_row[2] = nz ? 2 : 5;
    return ray;
}
inline PackRay pack_ray_lane(const RayPacket *r, uint k)
{
    PackRay ray;
    ray.origin = (float3)(lane_f(&r->px, k), lane_f(&r->py, k), lane_f(&r->pz, k));
    ray.shear = (float3)(-lane_f(&r->sx, k), -lane_f(&r->sy, k), lane_f(&r->sz, k));
    ray.axis_z = lane_i(&r->kz, k);
    return ray;
}

/* intersect_pack's test of one triangle (corners a, b, c) against every live lane; lanes with a
 * closer hit (the tie rule included) take it. Returns the lanes that did. */
PT_INLINE intW packet_triangle(const RayPacket *r, float3 a, float3 b, float3 c, uint prim,
                               intW live, HitPacket *hit)
{
    /* Per lane the axes kx, ky, kz of pack_ray: kz = axis_z, kx = kz + 1, ky = kx + 1 (mod 3). */
    intW kx = select(r->kz + 1, (intW)(0), r->kz == 2), ky = select(kx + 1, (intW)(0), kx == 2);
    float8 az = pick_axis(r->kz, a.x, a.y, a.z) - r->pz, bz = pick_axis(r->kz, b.x, b.y, b.z) - r->pz;
    float8 cz = pick_axis(r->kz, c.x, c.y, c.z) - r->pz;
    float8 ax = fma(r->sx, az, pick_axis(kx, a.x, a.y, a.z) - r->px);
    float8 ay = fma(r->sy, az, pick_axis(ky, a.x, a.y, a.z) - r->py);
    float8 bx = fma(r->sx, bz, pick_axis(kx, b.x, b.y, b.z) - r->px);
    float8 by = fma(r->sy, bz, pick_axis(ky, b.x, b.y, b.z) - r->py);
    float8 cx = fma(r->sx, cz, pick_axis(kx, c.x, c.y, c.z) - r->px);
    float8 cy = fma(r->sy, cz, pick_axis(ky, c.x, c.y, c.z) - r->py);
    EdgeTestW e = edge_test_w(ax, ay, az * r->sz, bx, by, bz * r->sz, cx, cy, cz * r->sz);
    uint8 tie_below = select(hit->prim, (uint8)(0u), hit->prim == (uint8)(HIT_NONE));
    intW closer = (e.t < hit->t) | ((e.t == hit->t) & ((uint8)(prim) < tie_below));
    intW take = live & e.inside & (e.t >= r->tmin) & closer;
    hit->t = select(hit->t, e.t, take);
    hit->u = select(hit->u, e.w1 * e.inv_det, take);
    hit->v = select(hit->v, e.w2 * e.inv_det, take);
    hit->prim = select(hit->prim, (uint8)(prim), as_uint8(take));
    return take;
}

/* The lanes of bits (bit i: lane i) as a comparison's all-ones. */
inline intW lanes_of(uint bits)
{
    return -(((intW)((int)bits) >> (intW)(0, 1, 2, 3, 4, 5, 6, 7)) & (intW)(1));
}

/* Lane k of the packet's hits as a Hit, and back. */
inline Hit hit_lane(const HitPacket *h, uint k)
{
    float t[8], u[8], v[8];
    uint prim[8];
    vstore8(h->t, 0, t), vstore8(h->u, 0, u), vstore8(h->v, 0, v), vstore8(h->prim, 0, prim);
    Hit one = {t[k], u[k], v[k], prim[k], 0u};
    return one;
}
inline void set_hit_lane(HitPacket *h, uint k, Hit one)
{
    intW lane = (intW)(k) == (intW)(0, 1, 2, 3, 4, 5, 6, 7);
    h->t = select(h->t, (float8)(one.t), lane);
    h->u = select(h->u, (float8)(one.u), lane);
    h->v = select(h->v, (float8)(one.v), lane);
    h->prim = select(h->prim, (uint8)(one.prim), as_uint8(lane));
}

/* Below this many rays a subtree is walked ray by ray (walk_wide): a packet's visit costs eight
 * rays' tests whether one ray or eight need it. */
#define PACKET_MIN_RAYS 3u

/* The walk of trace_bvh for eight rays at once. live: the lanes holding rays (all ones), tmax per
 * lane. Every stack entry carries the lanes that met its box (Embree's active masks), so a subtree
 * is tested for those only and, when fewer than PACKET_MIN_RAYS of them still need it, walked by
 * each of them alone from its current hit (Embree's hybrid switch). Entries are pushed nearest
 * (over their lanes) on top and skipped when they lie behind all their lanes' closest hits. With
 * any_hit a lane stops at its first hit and the walk when every lane has stopped. */
inline HitPacket trace_packet(const global TraversalNode *nodes, const global TraversalPrim *packs,
                              const RayPacket *r, intW live, float8 tmax, bool any_hit)
{
    HitPacket hit = {tmax, (float8)(0.0f), (float8)(0.0f), (uint8)(HIT_NONE)};
    uint stack_ref[BVH_WIDE_STACK_SIZE], stack_mask[BVH_WIDE_STACK_SIZE];
    float stack_t[BVH_WIDE_STACK_SIZE];
    uint stack_size = 0;
    uint ref = 0, mask = lane_bits(live);
    for (;;) {
        if (popcount(mask) < PACKET_MIN_RAYS) {
            for (uint bits = mask; bits != 0u; bits &= bits - 1u) {
                uint k = lowest_lane(bits);
                set_hit_lane(&hit, k, walk_wide(nodes, packs, wide_ray_lane(r, k), pack_ray_lane(r, k),
                                                lane_f(&r->slack, k), lane_f(&r->tmin, k), ref,
                                                hit_lane(&hit, k), any_hit));
            }
            if (any_hit)
                live &= ~lanes_of(mask & lane_bits(hit.prim != (uint8)(HIT_NONE)));
        } else if (!is_leaf_ref(ref)) {
            const global TraversalNode *node = &nodes[ref];
            const global float *row = (const global float *)node;
            const global uint *child = (const global uint *)&node->child;
            intW in = lanes_of(mask);
            float8 t_far = hit.t + r->slack;
            uint near_ref = 0, near_mask = 0, base = stack_size;
            float near_t = INFINITY;
            for (uint c = 0; c < BVH_WIDTH; c++) {
                float lx = row[c], ly = row[8 + c], lz = row[16 + c];
                float hx = row[24 + c], hy = row[32 + c], hz = row[40 + c];
                if (!(lx <= hx)) /* an unused lane's empty box */
                    continue;
                /* wide_box_hits per lane: entry through lo where the ray moves toward +. */
                float8 in_x = select((float8)(lx), (float8)(hx), r->negx);
                float8 in_y = select((float8)(ly), (float8)(hy), r->negy);
                float8 in_z = select((float8)(lz), (float8)(hz), r->negz);
                float8 out_x = select((float8)(hx), (float8)(lx), r->negx);
                float8 out_y = select((float8)(hy), (float8)(ly), r->negy);
                float8 out_z = select((float8)(hz), (float8)(lz), r->negz);
                float8 t0 = max_into_w((in_x - r->ox) * r->ix, r->box_tmin);
                t0 = max_into_w((in_y - r->oy) * r->iy, t0);
                t0 = max_into_w((in_z - r->oz) * r->iz, t0);
                float8 t1 = min_into_w((out_x - r->ox) * r->ix, t_far);
                t1 = min_into_w((out_y - r->oy) * r->iy, t1);
                t1 = min_into_w((out_z - r->oz) * r->iz, t1);
                intW meets = in & (t0 <= t1 * BOX_EXIT_SCALE);
                uint m = lane_bits(meets);
                if (m == 0u)
                    continue;
                uint cref = child[c];
                float t = lane_min(select((float8)(INFINITY), t0, meets));
                if (t < near_t || near_mask == 0u) { /* the new nearest: the old one is pushed */
                    uint swap_ref = near_ref, swap_mask = near_mask;
                    float swap_t = near_t;
                    near_ref = cref, near_mask = m, near_t = t;
                    cref = swap_ref, m = swap_mask, t = swap_t;
                }
                if (m == 0u)
                    continue;
                uint j = stack_size++;
                if (!any_hit)
                    for (; j > base && stack_t[j - 1] < t; j--) {
                        stack_ref[j] = stack_ref[j - 1];
                        stack_mask[j] = stack_mask[j - 1];
                        stack_t[j] = stack_t[j - 1];
                    }
                stack_ref[j] = cref;
                stack_mask[j] = m;
                stack_t[j] = t;
            }
            if (near_mask != 0u) {
                ref = near_ref, mask = near_mask;
                continue;
            }
        } else {
            intW in = live & lanes_of(mask);
            uint code = ~ref;
            uint first = code >> BVH_WIDE_LEAF_PACK_BITS;
            uint last = first + (code & ((1u << BVH_WIDE_LEAF_PACK_BITS) - 1u));
            for (uint p = first; p <= last; p++) {
                const global float *v = (const global float *)packs[p].v;
                const global uint *prim = (const global uint *)&packs[p].prim;
                for (uint j = 0; j < BVH_WIDTH; j++) {
                    if (j > 0u && prim[j] == prim[j - 1u]) /* the last triangle, repeated */
                        break;
                    float3 a = (float3)(v[j], v[8 + j], v[16 + j]);
                    float3 b = (float3)(v[24 + j], v[32 + j], v[40 + j]);
                    float3 c = (float3)(v[48 + j], v[56 + j], v[64 + j]);
                    intW took = packet_triangle(r, a, b, c, prim[j], in, &hit);
                    if (any_hit) {
                        in &= ~took;
                        live &= ~took;
                    }
                }
            }
        }
        if (any_hit && lane_bits(live) == 0u)
            return hit;
        /* Pop the nearest entry that one of its live lanes may still find a hit in front of. */
        float8 reach = (hit.t + r->slack) * BOX_EXIT_SCALE;
        for (;;) {
            if (stack_size == 0u)
                return hit;
            stack_size--;
            mask = stack_mask[stack_size] & lane_bits(live);
            if (mask != 0u &&
                stack_t[stack_size] <= lane_max(select((float8)(-INFINITY), reach, lanes_of(mask))))
                break;
        }
        ref = stack_ref[stack_size];
    }
}

#endif /* BVH_WIDTH == 8 */
