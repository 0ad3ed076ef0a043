/* SPDX-License-Identifier: MIT */
/* principled.cl: glTF 2.0 metallic-roughness with KHR_materials_specular (glTF 2.0 spec, appendix
 * B "BRDF Implementation"; the KHR_materials_specular extension's fresnel_mix):
 *   specular_brdf = D G2 / (4 |n.l| |n.v|)    GGX, height-correlated Smith G2 (microfacet.cl)
 *   dielectric    = W base_color / pi + specular Fd specular_brdf,
 *                   Fd = F0d + (1 - F0d) (1 - |v.h|)^5, F0d = min(((ior - 1) / (ior + 1))^2
 *                   specular_color, 1)
 *   metal         = Fm specular_brdf, Fm = base_color + (1 - base_color) (1 - |v.h|)^5
 *   f             = mix(dielectric, metal, metallic).
 * One deliberate departure: glTF's fresnel_mix weights the base by W = 1 - specular max(Fd(v.h)),
 * which is not energy-conserving (a white smooth dielectric seen at 85 degrees returns 1.59: the
 * mirror takes F(n.v) while the diffuse directions, whose half vectors face the viewer, keep
 * nearly all). Here W = (1 - specular max(Fd(n.v))) (1 - specular max(Fd(n.l))), the same
 * Schlick Fresnel evaluated at the macro-normal on the way in and out (as Kelemen and
 * Szirmay-Kalos 2001 and Ashikhmin-Shirley 2000 couple their layers): reciprocal, within 1 for a
 * smooth coat, and equal to glTF's at normal view and light up to F^2 terms. Reflection only
 * (wi.z > 0), except with subsurface scattering:
 *
 * Subsurface (b->subsurface = s > 0; shared/DESIGN.md "Media"): the share s of the diffuse lobe
 * enters the object instead of reflecting: a cosine-weighted transmission (1 - s') (1 - metallic)
 * |cos| / pi with s' = specular max Fd(wo.z), the same coat weight as on the way in, and no colour:
 * the colour is the random walk's inside the object's medium (its albedo inverted from the base
 * colour by the host). A path that meets the surface from inside (!front) leaves through it with
 * a Lambertian lobe of weight 1 (Cycles' random walk leaves the same way): f = 1 / pi for wi on the
 * outside, nothing reflects back in. A white base with s = 1 then keeps the furnace's energy: what
 * the coat does not reflect enters, walks without loss and leaves whole. */

/* Roughness 0 is not a delta here (bsdf_is_delta): keep GGX evaluable. */
inline float principled_alpha(float alpha) { return fmax(alpha, BSDF_SMOOTH_ALPHA); }

inline float schlick_weight(float cos_theta)
{
    float m = clamp(1.0f - cos_theta, 0.0f, 1.0f), m2 = m * m;
    return m2 * m2 * m;
}

inline float3 principled_f0_dielectric(const Bsdf *b)
{
    float r = (b->ior - 1.0f) / (b->ior + 1.0f);
    return fmin(r * r * b->specular_color, (float3)(1.0f));
}

/* Probability of sampling the specular lobe: its approximate share of the reflected energy at wo
 * (Fresnel at wo.z), kept within [0.1, 0.9] while both lobes exist so that neither is starved. */
inline float principled_specular_probability(const Bsdf *b, float cos_o)
{
    float w = schlick_weight(cos_o);
    float3 fd = principled_f0_dielectric(b);
    float fd_max = max3(fd + (1.0f - fd) * w);
    float3 fm = b->base + (1.0f - b->base) * w;
    float specular = b->metallic * max3(fm) + (1.0f - b->metallic) * b->specular * fd_max;
    float diffuse = (1.0f - b->metallic) * (1.0f - b->specular * fd_max) * max3(b->base);
    bool has_specular = b->metallic > 0.0f || b->specular > 0.0f;
    bool has_diffuse = b->metallic < 1.0f && max3(b->base) > 0.0f;
    if (!has_specular)
        return 0.0f;
    if (!has_diffuse)
        return 1.0f;
    return clamp(specular / fmax(specular + diffuse, 1e-20f), 0.1f, 0.9f);
}

/* The exit of a subsurface walk (!front): Lambertian toward the outside, wi.z < 0 in the frame
 * turned to wo's (the inside's) side. */
inline float3 principled_exit_eval(float3 wi, float *pdf_w)
{
    *pdf_w = wi.z < 0.0f ? -wi.z * PT_INV_PI : 0.0f;
    return (float3)(*pdf_w);
}

/* The probability that the principled sampler picks the entering lobe (with the specular and
 * diffuse ones: principled_sample). */
inline float principled_enter_probability(const Bsdf *b, float p_spec)
{
    return (1.0f - p_spec) * b->subsurface * (1.0f - b->metallic);
}

inline float3 principled_eval(const Bsdf *b, float3 wo, float3 wi, bool front, float *pdf_w)
{
    *pdf_w = 0.0f;
    if (b->subsurface > 0.0f && !front)
        return principled_exit_eval(wi, pdf_w);
    if (b->subsurface > 0.0f && wo.z > 0.0f && wi.z < 0.0f) {
        float p_enter = principled_enter_probability(b, principled_specular_probability(b, wo.z));
        float3 fd0 = principled_f0_dielectric(b);
        float coat = 1.0f - b->specular * max3(fd0 + (1.0f - fd0) * schlick_weight(wo.z));
        *pdf_w = p_enter * -wi.z * PT_INV_PI;
        return (float3)(b->subsurface * (1.0f - b->metallic) * coat * -wi.z * PT_INV_PI);
    }
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f))
        return (float3)(0.0f);
    float3 h = wo + wi;
    float len = length(h);
    if (!(len > 0.0f))
        return (float3)(0.0f);
    h /= len;
    float ax = principled_alpha(b->alpha_x), ay = principled_alpha(b->alpha_y);
    float cos_oh = dot(wo, h), w = schlick_weight(cos_oh);
    float d = ggx_d(h, ax, ay);
    /* specular_brdf * cos_i = D G2 / (4 cos_o). */
    float spec_cos = d * ggx_g_correlated(wo, wi, ax, ay) / (4.0f * wo.z);
    float3 fd0 = principled_f0_dielectric(b);
    float3 fd = fd0 + (1.0f - fd0) * w;
    float3 fm = b->base + (1.0f - b->base) * w;
    /* The diffuse base keeps what the specular layer leaves on the way in and on the way out. */
    float3 fd_o = fd0 + (1.0f - fd0) * schlick_weight(wo.z), fd_i = fd0 + (1.0f - fd0) * schlick_weight(wi.z);
    float base_weight = (1.0f - b->specular * max3(fd_o)) * (1.0f - b->specular * max3(fd_i));
    float3 dielectric = (1.0f - b->subsurface) * base_weight * b->base * (wi.z * PT_INV_PI) +
                        b->specular * fd * spec_cos;
    float3 metal = fm * spec_cos;
    float p_spec = principled_specular_probability(b, wo.z);
    /* pdf of the VNDF reflection: D_wo(h) / (4 wo.h) = G1(wo) D / (4 wo.z). */
    float pdf_spec = ggx_g1(wo, ax, ay) * d / (4.0f * wo.z);
    float p_diffuse = 1.0f - p_spec - principled_enter_probability(b, p_spec);
    *pdf_w = p_spec * pdf_spec + p_diffuse * wi.z * PT_INV_PI;
    return mix(dielectric, metal, b->metallic);
}

inline BsdfSample principled_sample(const Bsdf *b, float3 wo, bool front, float u1, float u2,
                                    float u3)
{
    BsdfSample s;
    if (b->subsurface > 0.0f && !front) {
        /* Leaving the walk: cosine-weighted to the outside; the weight f |cos| / pdf is 1. */
        s.wi = sample_cosine_hemisphere(u1, u2);
        s.wi.z = -s.wi.z;
        s.pdf_w = -s.wi.z * PT_INV_PI;
        if (!(s.pdf_w > 0.0f))
            return bsdf_sample_none();
        s.weight = (float3)(1.0f);
        s.flags = BSDF_TRANSMISSION;
        return s;
    }
    if (!(wo.z > 0.0f))
        return bsdf_sample_none();
    float p_spec = principled_specular_probability(b, wo.z);
    /* The entering lobe takes the top of the diffuse lobes' share of u3. */
    bool enter = u3 >= 1.0f - principled_enter_probability(b, p_spec);
    if (u3 < p_spec) {
        float ax = principled_alpha(b->alpha_x), ay = principled_alpha(b->alpha_y);
        s.wi = reflect_about(wo, ggx_sample_visible(wo, ax, ay, u1, u2));
    } else {
        s.wi = sample_cosine_hemisphere(u1, u2);
        if (enter)
            s.wi.z = -s.wi.z;
    }
    if (!(enter ? s.wi.z < 0.0f : s.wi.z > 0.0f))
        return bsdf_sample_none();
    /* The mixture pdf and the full value: one-sample MIS over the lobes. */
    float3 f_cos = principled_eval(b, wo, s.wi, front, &s.pdf_w);
    if (!(s.pdf_w > 0.0f))
        return bsdf_sample_none();
    s.weight = f_cos / s.pdf_w;
    s.flags = s.wi.z > 0.0f ? BSDF_REFLECTION : BSDF_TRANSMISSION;
    return s;
}
