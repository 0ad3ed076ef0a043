/* SPDX-License-Identifier: MIT */
/* conductor.cl: metals. Smooth (a perfect mirror) below BSDF_SMOOTH_ALPHA. */

/* Fresnel reflectance of a conductor with complex index eta + i k, per channel; Fresnel 1 when the
 * material gave neither (MATERIAL_FLAG_FRESNEL_ONE). */
inline float3 conductor_fresnel(const Bsdf *b, float cos_i)
{
    if (b->flags & MATERIAL_FLAG_FRESNEL_ONE)
        return (float3)(1.0f);
    /* TODO(materials): complex Fresnel (issue 16). */
    return (float3)(1.0f);
}

inline float3 conductor_eval(const Bsdf *b, float3 wo, float3 wi, float *pdf_w)
{
    *pdf_w = 0.0f;
    return (float3)(0.0f);
}

inline BsdfSample conductor_sample(const Bsdf *b, float3 wo, float u1, float u2)
{
    BsdfSample s;
    s.wi = (float3)(-wo.x, -wo.y, wo.z);
    s.weight = b->base * conductor_fresnel(b, wo.z);
    s.pdf_w = 0.0f;
    s.flags = BSDF_REFLECTION | BSDF_DELTA;
    return s;
}
