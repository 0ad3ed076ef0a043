/* SPDX-License-Identifier: MIT */
/* box_test.cl: the ray-box test that every BVH layout shares (bvh_node_2wide.cl,
 * bvh_traverse_wide.cl): per-ray constants, the slab test with NaN dropped, the margins that keep
 * its culling conservative against the watertight triangle test, and the slack on [tmin, tmax]. */

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
