/* SPDX-License-Identifier: MIT */
/* bvh_test.cl: batch kernels for tests/test_bvh_*.c and tools/bench_bvh.c. Rays are two float4s:
 * (origin, tmin) and (direction, tmax). Closest hits are written as (t, u, v, as_float(prim)),
 * any-hit answers as 0/1. (The brute-force reference runs on the host: PoCL runs a plain loop over
 * 100k triangles about 30 times slower than the same C.) */

inline float4 bvh_test_hit_record(Hit hit) { return (float4)(hit.t, hit.u, hit.v, as_float(hit.prim)); }

/* The closest hit of ray i of the batch. */
inline Hit bvh_test_closest(const global TraversalNode *nodes, const global TraversalPrim *tris,
                            uint num_tris, const global float4 *rays, uint i)
{
    float4 origin = rays[2 * i], dir = rays[2 * i + 1];
    return trace_closest(nodes, tris, num_tris, xyz(origin), xyz(dir), origin.w, dir.w);
}

kernel void bvh_test_trace_closest(const global TraversalNode *restrict nodes,
                                   const global TraversalPrim *restrict tris, uint num_tris,
                                   const global float4 *restrict rays, uint num_rays,
                                   global float4 *restrict hits)
{
    uint i = get_global_id(0);
    if (i < num_rays)
        hits[i] = bvh_test_hit_record(bvh_test_closest(nodes, tris, num_tris, rays, i));
}

kernel void bvh_test_trace_any(const global TraversalNode *restrict nodes,
                               const global TraversalPrim *restrict tris, uint num_tris,
                               const global float4 *restrict rays, uint num_rays,
                               global uint *restrict occluded)
{
    uint i = get_global_id(0);
    if (i >= num_rays)
        return;
    float4 origin = rays[2 * i], dir = rays[2 * i + 1];
    occluded[i] = trace_any(nodes, tris, num_tris, xyz(origin), xyz(dir), origin.w, dir.w) ? 1u : 0u;
}

#if BVH_WIDTH == 8
/* Rays 8 i .. 8 i + 7 as one packet (trace_packet): closest hits as bvh_test_trace_closest writes
 * them, or any-hit answers as bvh_test_trace_any. */
inline HitPacket bvh_test_packet(const global TraversalNode *nodes, const global TraversalPrim *tris,
                                 const global float4 *rays, uint num_rays, uint i, bool any_hit)
{
    float3 origin[8], dir[8];
    float tmin[8], tmax[8];
    int live[8];
    for (uint k = 0; k < 8u; k++) {
        uint r = min(8u * i + k, num_rays - 1u);
        float4 o = rays[2 * r], d = rays[2 * r + 1];
        origin[k] = xyz(o), dir[k] = xyz(d), tmin[k] = o.w, tmax[k] = d.w;
        live[k] = 8u * i + k < num_rays ? -1 : 0;
    }
    RayPacket packet = ray_packet(nodes, origin, dir, tmin);
    return trace_packet(nodes, tris, &packet, vload8(0, live), vload8(0, tmax), any_hit);
}

kernel void bvh_test_trace_closest_packet(const global TraversalNode *restrict nodes,
                                          const global TraversalPrim *restrict tris, uint num_tris,
                                          const global float4 *restrict rays, uint num_rays,
                                          global float4 *restrict hits)
{
    uint i = get_global_id(0);
    if (8u * i >= num_rays)
        return;
    HitPacket h = bvh_test_packet(nodes, tris, rays, num_rays, i, false);
    float t[8], u[8], v[8];
    uint prim[8];
    vstore8(h.t, 0, t), vstore8(h.u, 0, u), vstore8(h.v, 0, v), vstore8(h.prim, 0, prim);
    for (uint k = 0; k < 8u && 8u * i + k < num_rays; k++)
        hits[8u * i + k] = (float4)(t[k], u[k], v[k], as_float(prim[k]));
}

kernel void bvh_test_trace_any_packet(const global TraversalNode *restrict nodes,
                                      const global TraversalPrim *restrict tris, uint num_tris,
                                      const global float4 *restrict rays, uint num_rays,
                                      global uint *restrict occluded)
{
    uint i = get_global_id(0);
    if (8u * i >= num_rays)
        return;
    HitPacket h = bvh_test_packet(nodes, tris, rays, num_rays, i, true);
    uint prim[8];
    vstore8(h.prim, 0, prim);
    for (uint k = 0; k < 8u && 8u * i + k < num_rays; k++)
        occluded[8u * i + k] = prim[k] != HIT_NONE ? 1u : 0u;
}
#endif

#ifdef BVH_COUNT_STEPS
/* bench_bvh --count-steps: each closest-hit query's node visits and triangle (or pack) tests. */
kernel void bvh_test_count_steps(const global TraversalNode *restrict nodes,
                                 const global TraversalPrim *restrict tris, uint num_tris,
                                 const global float4 *restrict rays, uint num_rays,
                                 global uint2 *restrict counts)
{
    uint i = get_global_id(0);
    if (i < num_rays) {
        Hit hit = bvh_test_closest(nodes, tris, num_tris, rays, i);
        counts[i] = (uint2)(hit.visits, hit.tests);
    }
}
#endif

/* Secondary rays from the closest hits of `rays`, as an integrator makes them: the hit point is
 * interpolated from the barycentrics (as surface_at does), the direction is cosine-distributed
 * about the geometric normal on the side the ray came from (reflect = 1) or the far side
 * (reflect = 0), and the origin is moved by offset_ray_origin; tmin = 0, tmax = INFINITY. Misses
 * give a zero direction. corners: three positions per original triangle. */
kernel void bvh_test_bounce_rays(const global float4 *corners, const global float4 *rays,
                                 const global float4 *hits, uint num_rays, uint seed, uint reflect,
                                 global float4 *bounce)
{
    uint i = get_global_id(0);
    if (i >= num_rays)
        return;
    float4 hit = hits[i];
    uint prim = as_uint(hit.w);
    if (prim == HIT_NONE) {
        bounce[2 * i] = (float4)(0.0f);
        bounce[2 * i + 1] = (float4)(0.0f);
        return;
    }
    float3 p0 = xyz(corners[3 * prim]), p1 = xyz(corners[3 * prim + 1]);
    float3 p2 = xyz(corners[3 * prim + 2]);
    float3 p = (1.0f - hit.y - hit.z) * p0 + hit.y * p1 + hit.z * p2;
    float3 n = normalize(cross(p1 - p0, p2 - p0));
    float3 incoming = xyz(rays[2 * i + 1]);
    float3 side = dot(n, incoming) < 0.0f ? n : -n;
    if (!reflect)
        side = -side;
    float3 dir_local = sample_cosine_hemisphere(rng_uniform(i, 0u, 0u, seed), rng_uniform(i, 0u, 1u, seed));
    float3 dir = normalize(to_world(dir_local, side));
    bounce[2 * i] = (float4)(offset_ray_origin(p, n, dir), 0.0f);
    bounce[2 * i + 1] = (float4)(dir, INFINITY);
}

/* Persistent threads (Aila & Laine 2009): a fixed number of work items each take the next ray from
 * a global counter until none is left, so the slow incoherent rays of a launch's last wave run
 * beside fresh ones instead of leaving most of the GPU idle. On NVIDIA the active lanes of a warp
 * take consecutive indices with one atomic (inline PTX: activemask and a shuffle from the lowest
 * active lane); elsewhere each work item does its own atomic. */
#if defined(PT_VENDOR_NVIDIA) && !defined(PT_NO_WARP_ASM)
inline uint next_ray_index(volatile global uint *counter)
{
    uint mask, lane;
    asm volatile("activemask.b32 %0;" : "=r"(mask));
    asm volatile("mov.u32 %0, %%laneid;" : "=r"(lane));
    uint leader = 31u - clz(mask & (0u - mask));
    uint rank = popcount(mask & ((1u << lane) - 1u));
    uint base = 0u;
    if (lane == leader)
        base = atomic_add(counter, popcount(mask));
    asm volatile("shfl.sync.idx.b32 %0, %1, %2, 0x1f, %3;"
                 : "=r"(base)
                 : "r"(base), "r"(leader), "r"(mask));
    return base + rank;
}
#else
inline uint next_ray_index(volatile global uint *counter) { return atomic_inc(counter); }
#endif

kernel void bvh_test_trace_closest_persistent(const global TraversalNode *restrict nodes,
                                              const global TraversalPrim *restrict tris,
                                              uint num_tris, const global float4 *restrict rays,
                                              uint num_rays, global float4 *restrict hits,
                                              volatile global uint *next)
{
    for (uint i = next_ray_index(next); i < num_rays; i = next_ray_index(next))
        hits[i] = bvh_test_hit_record(bvh_test_closest(nodes, tris, num_tris, rays, i));
}

#if BVH_WIDTH == 2
/* Dynamic fetch (Aila & Laine 2009, "replacing terminated rays"): persistent work items that start
 * a new ray once their own is done, one node step at a time, instead of waiting for the slowest
 * ray of their warp. Diffuse rays differ several-fold in length: on the dragon a warp's longest
 * walk is about twice its mean (47% of the lanes busy, bench_bvh --count-steps). A refetch costs an
 * atomic and a ray load, so on NVIDIA the idle lanes of a warp wait until DYNAMIC_FETCH_THRESHOLD
 * of them are idle and fetch together (a warp vote by inline PTX); elsewhere each fetches at once.
 * 24 was the best of 8, 16, 24 and 32 on the H100, and no faster than the plain kernel. */
#ifndef DYNAMIC_FETCH_THRESHOLD
#define DYNAMIC_FETCH_THRESHOLD 24
#endif
#if defined(PT_VENDOR_NVIDIA) && !defined(PT_NO_WARP_ASM)
inline bool warp_should_fetch(bool idle)
{
    uint mask, votes;
    asm volatile("activemask.b32 %0;" : "=r"(mask));
    asm volatile("{ .reg .pred p; setp.ne.u32 p, %1, 0; vote.sync.ballot.b32 %0, p, %2; }"
                 : "=r"(votes)
                 : "r"((uint)idle), "r"(mask));
    return popcount(votes) >= DYNAMIC_FETCH_THRESHOLD || votes == mask;
}
#else
inline bool warp_should_fetch(bool idle) { return true; }
#endif

kernel void bvh_test_trace_closest_dynamic(const global TraversalNode *restrict nodes,
                                           const global TraversalPrim *restrict tris,
                                           uint num_tris, const global float4 *restrict rays,
                                           uint num_rays, global float4 *restrict hits,
                                           volatile global uint *next)
{
    uint stack[BVH_STACK_SIZE];
    Traversal tr;
    uint i = 0;
    bool active = false;
    for (;;) {
        if (warp_should_fetch(!active) && !active) {
            i = next_ray_index(next);
            if (i >= num_rays)
                break;
            float4 origin = rays[2 * i], dir = rays[2 * i + 1];
            traversal_start(&tr, nodes, xyz(origin), xyz(dir), origin.w, dir.w);
            active = true;
        }
        if (active && traversal_step(&tr, nodes, tris, false, stack)) {
            hits[i] = bvh_test_hit_record(tr.walk.hit);
            active = false;
        }
    }
}
#endif

#if PT_FEATURE(INSTANCES)
/* Two-level queries (tests/test_accel_instances_bvh.c): ray i at shutter fraction times[i]; mode 0:
 * closest (scene_closest's walk), 1: any hit, 2: brute-force closest, 3: brute-force any hit.
 * hits[i] as bvh_test_hit_record, instances_hit[i] the hit's instance. */
kernel void bvh_test_scene_trace(const global TraversalNode *restrict nodes,
                                 const global TraversalPrim *restrict tris,
                                 const global Instance *restrict instances,
                                 const global InstanceMotion *restrict motions, uint num_instances,
                                 const global float4 *restrict rays, const global float *restrict times,
                                 uint num_rays, uint mode, global float4 *restrict hits,
                                 global uint *restrict instances_hit)
{
    uint i = get_global_id(0);
    if (i >= num_rays)
        return;
    float3 o = xyz(rays[2 * i]), d = xyz(rays[2 * i + 1]);
    float tmin = rays[2 * i].w, tmax = rays[2 * i + 1].w;
    Hit h = mode < 2u ? trace_scene_bvh(nodes, tris, instances, motions, o, d, tmin, tmax, times[i],
                                        mode == 1u)
                      : trace_scene_brute_force(tris, instances, motions, num_instances, o, d, tmin,
                                                tmax, times[i], mode == 3u);
    hits[i] = bvh_test_hit_record(h);
    instances_hit[i] = h.instance;
}

/* The same queries of a flat BVH (host/accel/scene_bvh.h BVH_FLAT): the one-level walk, or every
 * baked triangle (num_prims entries of tris), with hits unbaked as scene_trace unbakes them. */
kernel void bvh_test_flat_trace(const global TraversalNode *restrict nodes,
                                const global TraversalPrim *restrict tris,
                                const global uint2 *restrict flat_prims, uint num_prims,
                                const global float4 *restrict rays, uint num_rays, uint mode,
                                global float4 *restrict hits, global uint *restrict instances_hit)
{
    uint i = get_global_id(0);
    if (i >= num_rays)
        return;
    float3 o = xyz(rays[2 * i]), d = xyz(rays[2 * i + 1]);
    float tmin = rays[2 * i].w, tmax = rays[2 * i + 1].w;
    Hit h = mode < 2u ? trace_bvh(nodes, tris, o, d, tmin, tmax, mode == 1u)
                      : trace_brute_force(tris, num_prims, o, d, tmin, tmax, mode == 3u);
    h = flat_hit_unbaked(flat_prims, h);
    hits[i] = bvh_test_hit_record(h);
    instances_hit[i] = h.instance;
}
#endif
