/* SPDX-License-Identifier: MIT */
/* bsdf.cl: the v1 materials. Lambert (two-sided), perfect mirror, smooth dielectric with exact
 * Fresnel. Directions point away from the surface; n is the shading normal turned to wo's side. */

typedef struct {
    float3 wi;
    float3 weight; /* f * |cos| / pdf */
    float pdf_w;   /* 0 for delta lobes */
} BsdfSample;

/* Unpolarised Fresnel reflectance of a smooth dielectric; cos_i > 0 on the incident side, eta =
 * eta_t / eta_i. Returns 1 on total internal reflection and sets *cos_t otherwise. */
inline float fresnel_dielectric(float cos_i, float eta, float *cos_t)
{
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) {
        *cos_t = 0.0f;
        return 1.0f;
    }
    float ct = sqrt(fmax(0.0f, 1.0f - sin2_t));
    float r_s = (cos_i - eta * ct) / (cos_i + eta * ct);
    float r_p = (eta * cos_i - ct) / (eta * cos_i + ct);
    *cos_t = ct;
    return 0.5f * (r_s * r_s + r_p * r_p);
}

inline float3 reflect_about(float3 wo, float3 n) { return 2.0f * dot(wo, n) * n - wo; }

/* Lambert value f(wo, wi) * cos for a light sample (two-sided: both on wo's side of n). */
inline float3 diffuse_eval_cos(float3 albedo, float3 n, float3 wi, float *pdf_w)
{
    float cos_i = dot(wi, n);
    if (cos_i <= 0.0f) {
        *pdf_w = 0.0f;
        return (float3)(0.0f);
    }
    *pdf_w = cos_i * PT_INV_PI;
    return albedo * (cos_i * PT_INV_PI);
}

/* Samples the material. front: wo is on the side the geometric normal points to (the outside of a
 * dielectric). n: shading normal on wo's side. */
PT_INLINE BsdfSample bsdf_sample(Material m, float3 albedo, float3 wo, float3 n, bool front, float u1,
                       float u2, float u_lobe)
{
    BsdfSample s;
    if (m.type == MATERIAL_MIRROR) {
        s.wi = reflect_about(wo, n);
        s.weight = xyz(m.ks);
        s.pdf_w = 0.0f;
    } else if (m.type == MATERIAL_DIELECTRIC) {
        float eta = front ? m.ior : 1.0f / m.ior; /* eta_t / eta_i */
        float cos_i = dot(wo, n), cos_t;
        float reflectance = fresnel_dielectric(cos_i, eta, &cos_t);
        s.pdf_w = 0.0f;
        if (u_lobe < reflectance) {
            s.wi = reflect_about(wo, n);
            s.weight = (float3)(1.0f);
        } else {
            /* Snell: wi = -wo / eta + (cos_i / eta - cos_t) n. Radiance scales by 1 / eta^2 as the
             * solid angle compresses (Veach 1997, sec. 5.2). */
            s.wi = normalize(-wo / eta + (cos_i / eta - cos_t) * n);
            s.weight = xyz(m.tf) / (eta * eta);
        }
    } else {
        float3 v_local = sample_cosine_hemisphere(u1, u2);
        s.wi = to_world(v_local, n);
        s.weight = albedo;
        s.pdf_w = v_local.z * PT_INV_PI;
    }
    return s;
}
