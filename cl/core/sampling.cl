/* SPDX-License-Identifier: MIT */
/* sampling.cl: warps from the unit square, their pdfs, and the MIS heuristic. */

/* Uniform point on the unit disc (Shirley-Chiu concentric map), area-preserving. */
inline float2 sample_disk_concentric(float u1, float u2)
{
    float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f)
        return (float2)(0.0f, 0.0f);
    /* The angle in units of pi: sinpi/cospi reduce it exactly and cheaply, where sin/cos spent
     * 6% of a PoCL render in their general argument reduction. */
    float r, phi_over_pi;
    if (fabs(a) > fabs(b))
        r = a, phi_over_pi = 0.25f * (b / a);
    else
        r = b, phi_over_pi = 0.5f - 0.25f * (a / b);
    return (float2)(r * cospi(phi_over_pi), r * sinpi(phi_over_pi));
}

/* Cosine-weighted direction in the local frame (z = normal); pdf_w = cos(theta) / pi. */
inline float3 sample_cosine_hemisphere(float u1, float u2)
{
    float2 d = sample_disk_concentric(u1, u2);
    float z = sqrt(fmax(0.0f, 1.0f - d.x * d.x - d.y * d.y));
    return (float3)(d.x, d.y, z);
}

/* Uniform point on a triangle as barycentrics (b1, b2) weighting v1 and v2 (Shirley's warp). */
inline float2 sample_triangle_uniform(float u1, float u2)
{
    float su = sqrt(u1);
    return (float2)(su * (1.0f - u2), su * u2);
}

/* Power heuristic with beta = 2 (Veach 1997). */
inline float mis_power(float pdf_a, float pdf_b)
{
    float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a + b > 0.0f ? a / (a + b) : 0.0f;
}
