/* SPDX-License-Identifier: MIT */
/* intersect_triangle.cl: watertight ray-triangle test (Woop, Benthin & Wald 2013, "Watertight
 * Ray/Triangle Intersection"). Rays that cross a shared edge or vertex of a closed mesh hit at
 * least one of the triangles that share it, whatever the rounding. Two-sided. Barycentrics: u
 * weights v1, v weights v2. */

typedef struct {
    float t;
    float u, v;
    uint prim; /* original triangle index, HIT_NONE on a miss */
    uint instance; /* the instance (shared.h Instance) whose triangle it is; 0 in one-level scenes */
#ifdef BVH_COUNT_STEPS
    uint visits, tests; /* node visits, triangle (or pack) tests: bench_bvh --count-steps */
#endif
} Hit;

/* The exclusive upper bound on t for the next triangle against the closest hit so far: the hit's
 * own distance is included (the next float up: the bits plus one, hit.t being positive and finite
 * once there is a hit), so that a tie can go to the lower original index, which the caller checks
 * on the rare hit. Every layout and tree then reports the same triangle. Before any hit, hit.t is
 * the ray's tmax, which stays excluded. */
inline float hit_tie_limit(Hit hit)
{
    return hit.prim != HIT_NONE ? as_float(as_uint(hit.t) + 1u) : hit.t;
}

/* Work counters for bench_bvh --count-steps, compiled out otherwise. */
#ifdef BVH_COUNT_STEPS
#define COUNT_STEPS(hit, nodes, triangles) ((hit).visits += (nodes), (hit).tests += (triangles))
#else
#define COUNT_STEPS(hit, nodes, triangles) ((void)0)
#endif

/* Per-ray constants: the axes are permuted so that z is the dominant direction axis, then the
 * shear (x - sx z, y - sy z, sz z) maps the ray onto the +z axis through the origin. */
typedef struct {
    float3 origin; /* as given, not permuted: the same registers as the box test's origin */
    float3 shear;  /* sx, sy, sz */
    int axis_z;    /* the dominant axis of the direction */
} WatertightRay;

/* (v[kx], v[ky], v[kz]) with kz = axis_z, kx = kz + 1, ky = kz + 2 (mod 3): exact. */
inline float3 permute_axes(float3 v, int axis_z)
{
    return axis_z == 0 ? v.yzx : (axis_z == 1 ? v.zxy : v);
}

inline WatertightRay watertight_ray(float3 origin, float3 dir)
{
    float3 a = fabs(dir);
    WatertightRay ray;
    ray.axis_z = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    float3 d = permute_axes(dir, ray.axis_z);
    ray.origin = origin;
    ray.shear = (float3)(d.x / d.z, d.y / d.z, 1.0f / d.z);
    return ray;
}

/* a*b - c*d with an exact sign (Kahan's algorithm: the error of c*d is recovered by an fma, so the
 * result is within 2 ulp of the exact value, and exactly 0 only when that is). This replaces the
 * paper's double-precision fallback, which needs cl_khr_fp64, and stays exact when the compiler
 * contracts with -cl-mad-enable because every rounding step is spelled out. */
inline float difference_of_products(float a, float b, float c, float d)
{
    float cd = c * d;
    float cd_error = fma(-c, d, cd);
    return fma(a, b, -cd) + cd_error;
}

/* Sheared 2-D position of a vertex (relative to the ray) and its scaled depth. Every triangle that
 * shares the vertex computes the same values, which is what makes the test watertight. */
inline float3 shear_vertex(WatertightRay ray, float3 vertex)
{
    float3 p = permute_axes(vertex - ray.origin, ray.axis_z); /* exact either way round */
    return (float3)(fma(-ray.shear.x, p.z, p.x), fma(-ray.shear.y, p.z, p.y), ray.shear.z * p.z);
}

/* True for a hit with tmin <= t < tmax; a ray in the triangle's plane (or a degenerate triangle)
 * misses. */
inline bool intersect_triangle_watertight(WatertightRay ray, float3 v0, float3 v1, float3 v2,
                                          float tmin, float tmax, float *t_out, float *u_out,
                                          float *v_out)
{
    float3 a = shear_vertex(ray, v0), b = shear_vertex(ray, v1), c = shear_vertex(ray, v2);
    /* Scaled barycentrics: edge functions of the ray's point (0, 0) against each edge. */
    float w0 = difference_of_products(c.x, b.y, c.y, b.x);
    float w1 = difference_of_products(a.x, c.y, a.y, c.x);
    float w2 = difference_of_products(b.x, a.y, b.y, a.x);
    if ((w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) && (w0 > 0.0f || w1 > 0.0f || w2 > 0.0f))
        return false;
    float det = w0 + w1 + w2;
    if (det == 0.0f)
        return false;
    /* Explicit fmas keep t bit-identical wherever this is inlined, so trace_closest, trace_any
     * and the brute-force reference agree on hits at exactly tmax. */
    float inv_det = 1.0f / det;
    float t = fma(w0, a.z, fma(w1, b.z, w2 * c.z)) * inv_det;
    if (!(t >= tmin && t < tmax))
        return false;
    *t_out = t;
    *u_out = w1 * inv_det;
    *v_out = w2 * inv_det;
    return true;
}

