/* SPDX-License-Identifier: MIT */
/* dielectric.cl: glass. Rough: GGX reflection and transmission after Walter et al. 2007 (the
 * generalised half vector, exact Fresnel, separable Smith G), sampled through visible normals and
 * chosen between by Fresnel, as pbrt-v4's DielectricBxDF in TransportMode::Radiance; smooth below
 * BSDF_SMOOTH_ALPHA (delta lobes). wo.z > 0 always (bsdf_common.cl); wi.z > 0 is reflection,
 * wi.z < 0 transmission. The tint (base) multiplies transmission only. */

/* eta_t / eta_i for light crossing from wo's side: `front` = wo outside the glass. */
inline float dielectric_eta(const Bsdf *b, bool front) { return front ? b->ior : 1.0f / b->ior; }

/* Delta lobes: a smooth surface, or an index-matched one (ior 1), which the generalised half
 * vector cannot describe (wo + wi = 0 for the only transmitted direction); pbrt-v4 does the same. */
inline bool dielectric_is_smooth(const Bsdf *b)
{
    return !PT_FEATURE(ROUGH_DIELECTRIC) || b->ior == 1.0f ||
           microfacet_smooth(b->alpha_x, b->alpha_y);
}

/* Reflection: f = F D G / (4 |cos_o cos_i|), pdf = D_wo(m) / (4 wo.m) * F (Walter eq. 20, 14).
 * Transmission (Walter eq. 21, 17), with eta = eta_t / eta_i, m = -normalize(wo + eta wi):
 *   f = (1 - F) D G |wi.m| |wo.m| / (|cos_o cos_i| (wi.m + wo.m / eta)^2) / eta^2,
 *   pdf = D_wo(m) |wi.m| / (wi.m + wo.m / eta)^2 * (1 - F).
 * The 1 / eta^2 is radiance's compression into the narrower solid angle (Veach 1997 sec. 5.2;
 * pbrt-v4 divides by etap^2 in radiance mode). It breaks plain reciprocity into the generalised
 * one (Veach eq. 5.14): f_t(wo, wi) n_wi^2 = f_t(wi, wo) n_wo^2, n_w the index on w's side. */
inline float3 dielectric_eval(const Bsdf *b, float3 wo, float3 wi, bool front, float *pdf_w)
{
    *pdf_w = 0.0f;
    if (dielectric_is_smooth(b) || !(wo.z > 0.0f) || wi.z == 0.0f)
        return (float3)(0.0f);
    float eta = dielectric_eta(b, front);
    bool reflect = wi.z > 0.0f;
    float etap = reflect ? 1.0f : eta;
    float3 m = wo + wi * etap;
    float len = length(m);
    if (!(len > 0.0f))
        return (float3)(0.0f);
    m /= len;
    if (m.z < 0.0f)
        m = -m;
    float cos_om = dot(wo, m), cos_im = dot(wi, m);
    /* Microfacets seen from behind by either direction contribute nothing. */
    if (!(cos_om > 0.0f) || cos_im * wi.z <= 0.0f)
        return (float3)(0.0f);
    float cos_t;
    float fr = fresnel_dielectric(cos_om, eta, &cos_t);
    float d = ggx_d(m, b->alpha_x, b->alpha_y);
    float g = ggx_g_separable(wo, wi, b->alpha_x, b->alpha_y);
    float pdf_m = ggx_pdf_visible(wo, m, b->alpha_x, b->alpha_y);
    if (reflect) {
        *pdf_w = pdf_m / (4.0f * cos_om) * fr;
        return (float3)(fr * d * g / (4.0f * wo.z));
    }
    float denom = cos_im + cos_om / eta;
    denom *= denom;
    if (!(denom > 0.0f))
        return (float3)(0.0f);
    float jacobian = fabs(cos_im) / denom; /* dm / dwi */
    *pdf_w = pdf_m * jacobian * (1.0f - fr);
    float f_cos = (1.0f - fr) * d * g * fabs(cos_im) * cos_om / (wo.z * denom) / (eta * eta);
    return b->base * f_cos;
}

inline BsdfSample dielectric_sample(const Bsdf *b, float3 wo, bool front, float u1, float u2,
                                    float u_lobe)
{
    BsdfSample s;
    float eta = dielectric_eta(b, front);
    float cos_t;
    if (dielectric_is_smooth(b)) {
        float reflectance = fresnel_dielectric(wo.z, eta, &cos_t);
        s.pdf_w = 0.0f;
        if (u_lobe < reflectance) {
            s.wi = (float3)(-wo.x, -wo.y, wo.z);
            s.weight = (float3)(1.0f);
            s.flags = BSDF_REFLECTION | BSDF_DELTA;
        } else {
            /* Snell: wi = -wo / eta + (cos_i / eta - cos_t) n. Radiance scales by 1 / eta^2 as
             * the solid angle compresses (Veach 1997, sec. 5.2). */
            s.wi = normalize((float3)(-wo.x / eta, -wo.y / eta, -cos_t));
            s.weight = b->base / (eta * eta);
            s.flags = BSDF_TRANSMISSION | BSDF_DELTA;
        }
        return s;
    }
    if (!(wo.z > 0.0f))
        return bsdf_sample_none();
    float3 m = ggx_sample_visible(wo, b->alpha_x, b->alpha_y, u1, u2);
    float cos_om = dot(wo, m);
    if (!(cos_om > 0.0f))
        return bsdf_sample_none();
    float reflectance = fresnel_dielectric(cos_om, eta, &cos_t);
    if (u_lobe < reflectance) {
        s.wi = reflect_about(wo, m);
        if (!(s.wi.z > 0.0f))
            return bsdf_sample_none();
        s.flags = BSDF_REFLECTION;
    } else {
        /* Refraction through m (Snell about the microfacet normal). */
        s.wi = normalize(-wo / eta + (cos_om / eta - cos_t) * m);
        if (!(s.wi.z < 0.0f))
            return bsdf_sample_none();
        s.flags = BSDF_TRANSMISSION;
    }
    /* Through eval, so that weight, pdf and the value NEE sees agree exactly. */
    float3 f_cos = dielectric_eval(b, wo, s.wi, front, &s.pdf_w);
    if (!(s.pdf_w > 0.0f))
        return bsdf_sample_none();
    s.weight = f_cos / s.pdf_w;
    return s;
}

/* Beer-Lambert transmittance exp(-sigma t) over a segment of length t inside an absorbing
 * dielectric; t may be infinite (a ray that leaves an open mesh into nothing): channels that
 * absorb go to 0, the others stay 1 (exp(-0 * inf) would be NaN). */
inline float3 dielectric_transmittance(float3 sigma, float t)
{
    return (float3)(sigma.x > 0.0f ? exp(-sigma.x * t) : 1.0f, sigma.y > 0.0f ? exp(-sigma.y * t) : 1.0f,
                    sigma.z > 0.0f ? exp(-sigma.z * t) : 1.0f);
}
