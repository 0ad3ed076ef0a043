/* SPDX-License-Identifier: MIT */
/* diffuse.cl: Lambert, two-sided (the frame's z is on wo's side). */

inline float3 diffuse_eval(const Bsdf *b, float3 wo, float3 wi, float *pdf_w)
{
    if (wi.z <= 0.0f) {
        *pdf_w = 0.0f;
        return (float3)(0.0f);
    }
    *pdf_w = wi.z * PT_INV_PI;
    return b->base * (wi.z * PT_INV_PI);
}

inline BsdfSample diffuse_sample(const Bsdf *b, float3 wo, float u1, float u2)
{
    BsdfSample s;
    s.wi = sample_cosine_hemisphere(u1, u2);
    s.weight = b->base;
    s.pdf_w = s.wi.z * PT_INV_PI;
    s.flags = BSDF_REFLECTION;
    return s;
}
