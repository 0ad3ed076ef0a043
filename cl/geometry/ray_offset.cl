/* SPDX-License-Identifier: MIT */
/* ray_offset.cl: origins for secondary rays that cannot re-hit the surface they leave (Wächter &
 * Binder 2019, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6).
 * The point moves along the geometric normal, toward the side the new ray leaves on, by a fixed
 * number of float ulps per coordinate: the offset scales with the point's magnitude, as the
 * rounding error of an interpolated hit point does. Near the world origin, where ulps get tiny,
 * a small absolute offset takes over. Callers then trace with tmin = 0. */

#define RAY_OFFSET_ULPS 256.0f              /* ulps per unit of the normal's component */
#define RAY_OFFSET_ABSOLUTE (1.0f / 65536.0f) /* used where |coordinate| < RAY_OFFSET_NEAR_ORIGIN */
#define RAY_OFFSET_NEAR_ORIGIN (1.0f / 32.0f)

/* p: a point on a surface; geometric_normal: its unit geometric normal (either orientation);
 * dir: the new ray's direction. */
float3 offset_ray_origin(float3 p, float3 geometric_normal, float3 dir)
{
    float3 n = dot(geometric_normal, dir) < 0.0f ? -geometric_normal : geometric_normal;
    /* Ulp steps: adding to the bits of a negative float moves it toward -inf, hence the flip. */
    int3 ulps = convert_int3(RAY_OFFSET_ULPS * n);
    int3 p_bits = as_int3(p);
    float3 p_ulps = as_float3(p_bits + select(ulps, -ulps, p_bits < 0));
    float3 p_absolute = p + RAY_OFFSET_ABSOLUTE * n;
    return select(p_ulps, p_absolute, fabs(p) < RAY_OFFSET_NEAR_ORIGIN);
}
