/* SPDX-License-Identifier: MIT */
/* sampling.cl: warps from the unit square, their pdfs, and the MIS heuristic. */

/* cos(pi x) and sin(pi x) for |x| <= 1/4 (|pi x| <= pi/4): their Taylor series to the x^10 and
 * x^9 terms, whose remainders (below 2e-9) lie under float rounding there. A general sinpi/cospi
 * reduces its argument first: on PoCL that was most of bsdf_sample's 11% of a Cornell box render
 * (perf), and this made the render 7% faster (bench/README.md, "CPU (PoCL) throughput"). */
inline float2 cos_sin_pi_quarter(float x)
{
    float t = M_PI_F * x, t2 = t * t;
    float c = fma(fma(fma(fma(fma(t2, -2.7557319e-7f, 2.4801587e-5f), t2, -1.3888889e-3f), t2,
                          4.1666668e-2f),
                      t2, -0.5f),
                  t2, 1.0f);
    float s = t * fma(fma(fma(fma(t2, 2.7557319e-6f, -1.9841270e-4f), t2, 8.3333333e-3f), t2,
                          -1.6666667e-1f),
                      t2, 1.0f);
    return (float2)(c, s);
}

/* cos and sin of the angle 2 pi turns, for the angles that samples draw (2 pi u) in place of a
 * general cos and sin, whose argument reduction PoCL pays in full (perf: most of
 * ggx_sample_visible's time). The nearest quarter turn splits off exactly (4 turns and its
 * difference from the nearest integer are exact in float), and the rest, at most an eighth of a
 * turn, goes to cos_sin_pi_quarter. */
inline float2 cos_sin_turns(float turns)
{
    float quarters = 4.0f * turns, nearest = rint(quarters);
    float2 cs = cos_sin_pi_quarter(0.5f * (quarters - nearest));
    /* Rotated by the quarter turns (selects, not a switch: a GPU's lanes need not diverge). */
    int quadrant = (int)nearest & 3;
    float2 turned = quadrant & 1 ? (float2)(-cs.y, cs.x) : cs;
    return quadrant & 2 ? -turned : turned;
}

/* Uniform point on the unit disc (Shirley-Chiu concentric map), area-preserving. */
inline float2 sample_disk_concentric(float u1, float u2)
{
    float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    if (a == 0.0f && b == 0.0f)
        return (float2)(0.0f, 0.0f);
    /* The angle is pi/4 (b / a) in the wedges around the x axis, pi/2 - pi/4 (a / b) around the y
     * axis, where cos and sin trade places: one quarter-range evaluation serves both (selects, one
     * division and one polynomial: a GPU's lanes need not diverge). */
    bool x_wedge = fabs(a) > fabs(b);
    float r = x_wedge ? a : b;
    float2 cs = cos_sin_pi_quarter(0.25f * ((x_wedge ? b : a) / r));
    return r * (x_wedge ? cs : cs.yx);
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
