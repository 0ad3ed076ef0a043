/* SPDX-License-Identifier: MIT */
/* conductor.cl: metals. GGX microfacet reflection (Walter et al. 2007 / pbrt-v4 ConductorBxDF)
 * with separable Smith G and visible-normal sampling (microfacet.cl); a perfect mirror below
 * BSDF_SMOOTH_ALPHA. */

/* Unpolarised Fresnel reflectance of a conductor of complex index n = eta + i k seen from a medium
 * of index 1, cos_i in [0, 1] (the exact form, as pbrt-v4 FrComplex / Born & Wolf): cos_t =
 * sqrt(1 - sin_i^2 / n^2), r_par = (n cos_i - cos_t) / (n cos_i + cos_t), r_perp = (cos_i - n cos_t)
 * / (cos_i + n cos_t), R = (|r_par|^2 + |r_perp|^2) / 2. Complex numbers are float2 (re, im). */
inline float2 complex_mul(float2 a, float2 b) { return (float2)(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
inline float2 complex_div(float2 a, float2 b)
{
    float d = b.x * b.x + b.y * b.y;
    return (float2)(a.x * b.x + a.y * b.y, a.y * b.x - a.x * b.y) / d;
}
inline float complex_norm2(float2 a) { return a.x * a.x + a.y * a.y; }
/* The principal square root (non-negative real part). */
inline float2 complex_sqrt(float2 z)
{
    float n = length(z);
    if (n == 0.0f)
        return (float2)(0.0f);
    float t1 = sqrt(0.5f * (n + fabs(z.x))), t2 = 0.5f * z.y / t1;
    return z.x >= 0.0f ? (float2)(t1, t2) : (float2)(fabs(t2), copysign(t1, z.y));
}

inline float fresnel_complex(float cos_i, float eta, float k)
{
    cos_i = clamp(cos_i, 0.0f, 1.0f);
    float2 n = (float2)(eta, k);
    float sin2_i = 1.0f - cos_i * cos_i;
    float2 sin2_t = complex_div((float2)(sin2_i, 0.0f), complex_mul(n, n));
    float2 cos_t = complex_sqrt((float2)(1.0f, 0.0f) - sin2_t);
    float2 n_cos_i = n * cos_i;
    float2 n_cos_t = complex_mul(n, cos_t);
    float2 ci = (float2)(cos_i, 0.0f);
    float r_par = complex_norm2(complex_div(n_cos_i - cos_t, n_cos_i + cos_t));
    float r_perp = complex_norm2(complex_div(ci - n_cos_t, ci + n_cos_t));
    return 0.5f * (r_par + r_perp);
}

/* Fresnel reflectance of a conductor with complex index eta + i k, per channel; Fresnel 1 when the
 * material gave neither (MATERIAL_FLAG_FRESNEL_ONE). */
inline float3 conductor_fresnel(const Bsdf *b, float cos_i)
{
    if (!PT_FEATURE(CONDUCTOR_FRESNEL) || (b->flags & MATERIAL_FLAG_FRESNEL_ONE))
        return (float3)(1.0f);
    return (float3)(fresnel_complex(cos_i, b->eta.x, b->k.x), fresnel_complex(cos_i, b->eta.y, b->k.y),
                    fresnel_complex(cos_i, b->eta.z, b->k.z));
}

/* A perfect mirror: below BSDF_SMOOTH_ALPHA, or in a program built for scenes without rough
 * conductors. */
inline bool conductor_is_smooth(const Bsdf *b)
{
    return !PT_FEATURE(ROUGH_CONDUCTOR) || microfacet_smooth(b->alpha_x, b->alpha_y);
}

/* f cos_i = base F(wo.m) D(m) G1(wo) G1(wi) / (4 cos_o), m the half vector; pdf = D_wo(m) / (4 wo.m)
 * (the reflection Jacobian dm/dwi = 1 / (4 wo.m), Walter 2007 eq. 14). Reflection only: wi.z > 0. */
inline float3 conductor_eval(const Bsdf *b, float3 wo, float3 wi, float *pdf_w)
{
    *pdf_w = 0.0f;
    if (conductor_is_smooth(b) || !(wo.z > 0.0f) || !(wi.z > 0.0f))
        return (float3)(0.0f);
    float3 m = wo + wi;
    float len = length(m);
    if (!(len > 0.0f))
        return (float3)(0.0f);
    m /= len;
    float cos_om = dot(wo, m);
    float d = ggx_d(m, b->alpha_x, b->alpha_y);
    float g1_o = ggx_g1(wo, b->alpha_x, b->alpha_y), g1_i = ggx_g1(wi, b->alpha_x, b->alpha_y);
    *pdf_w = g1_o * d / (4.0f * wo.z); /* D_wo(m) / (4 wo.m): the wo.m cancel */
    return b->base * conductor_fresnel(b, cos_om) * (d * g1_o * g1_i / (4.0f * wo.z));
}

inline BsdfSample conductor_sample(const Bsdf *b, float3 wo, float u1, float u2)
{
    BsdfSample s;
    if (conductor_is_smooth(b)) {
        s.wi = (float3)(-wo.x, -wo.y, wo.z);
        s.weight = b->base * conductor_fresnel(b, wo.z);
        s.pdf_w = 0.0f;
        s.flags = BSDF_REFLECTION | BSDF_DELTA;
        return s;
    }
    if (!(wo.z > 0.0f))
        return bsdf_sample_none();
    float3 m = ggx_sample_visible(wo, b->alpha_x, b->alpha_y, u1, u2);
    s.wi = reflect_about(wo, m);
    if (!(s.wi.z > 0.0f))
        return bsdf_sample_none();
    float3 f_cos = conductor_eval(b, wo, s.wi, &s.pdf_w);
    if (!(s.pdf_w > 0.0f))
        return bsdf_sample_none();
    /* Equals base F G1(wi) (Heitz 2018 eq. 19); computed through eval so both agree exactly. */
    s.weight = f_cos / s.pdf_w;
    s.flags = BSDF_REFLECTION;
    return s;
}
