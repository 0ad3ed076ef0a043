/* SPDX-License-Identifier: MIT */
/* dielectric.cl: glass. Smooth below BSDF_SMOOTH_ALPHA, exact Fresnel. */

inline float3 dielectric_eval(const Bsdf *b, float3 wo, float3 wi, bool front, float *pdf_w)
{
    *pdf_w = 0.0f;
    return (float3)(0.0f);
}

inline BsdfSample dielectric_sample(const Bsdf *b, float3 wo, bool front, float u1, float u2,
                                    float u_lobe)
{
    BsdfSample s;
    float eta = front ? b->ior : 1.0f / b->ior; /* eta_t / eta_i */
    float cos_t;
    float reflectance = fresnel_dielectric(wo.z, eta, &cos_t);
    s.pdf_w = 0.0f;
    if (u_lobe < reflectance) {
        s.wi = (float3)(-wo.x, -wo.y, wo.z);
        s.weight = (float3)(1.0f);
        s.flags = BSDF_REFLECTION | BSDF_DELTA;
    } else {
        /* Snell: wi = -wo / eta + (cos_i / eta - cos_t) n. Radiance scales by 1 / eta^2 as the
         * solid angle compresses (Veach 1997, sec. 5.2). */
        s.wi = normalize((float3)(-wo.x / eta, -wo.y / eta, -cos_t));
        s.weight = b->base / (eta * eta);
        s.flags = BSDF_TRANSMISSION | BSDF_DELTA;
    }
    return s;
}
