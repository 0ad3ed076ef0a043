/* SPDX-License-Identifier: MIT */
/* intersect_triangle.cl: ray-triangle test. Barycentrics: u weights v1, v weights v2. */

typedef struct {
    float t;
    float u, v;
    uint prim; /* original triangle index, HIT_NONE on a miss */
} Hit;

#define HIT_NONE 0xffffffffu

/* Möller-Trumbore; returns true for a hit with tmin <= t < tmax. */
inline bool intersect_triangle(float3 origin, float3 dir, float3 v0, float3 v1, float3 v2,
                               float tmin, float tmax, float *t_out, float *u_out, float *v_out)
{
    float3 e1 = v1 - v0, e2 = v2 - v0;
    float3 p = cross(dir, e2);
    float det = dot(e1, p);
    if (det == 0.0f)
        return false;
    float inv_det = 1.0f / det;
    float3 s = origin - v0;
    float u = dot(s, p) * inv_det;
    if (u < 0.0f || u > 1.0f)
        return false;
    float3 q = cross(s, e1);
    float v = dot(dir, q) * inv_det;
    if (v < 0.0f || u + v > 1.0f)
        return false;
    float t = dot(e2, q) * inv_det;
    if (!(t >= tmin && t < tmax))
        return false;
    *t_out = t, *u_out = u, *v_out = v;
    return true;
}
