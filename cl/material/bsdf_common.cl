/* SPDX-License-Identifier: MIT */
/* bsdf_common.cl: what every BSDF lobe shares. A BSDF works in the local shading frame: z is the
 * shading normal turned to wo's side (so wo.z > 0 always), x the tangent along increasing u.
 * `front` says whether wo is on the side the geometric normal points to (the outside of a
 * dielectric). Directions point away from the surface. */

typedef struct {
    float3 t, b, n; /* orthonormal: tangent, bitangent, normal */
} Frame;

inline Frame frame_from_normal(float3 n)
{
    Frame f;
    make_basis(n, &f.t, &f.b);
    f.n = n;
    return f;
}

/* A frame whose x follows `tangent` (any vector not parallel to n; orthonormalised here). */
inline Frame frame_from_tangent(float3 n, float3 tangent)
{
    float3 t = tangent - n * dot(n, tangent);
    float len = length(t);
    if (!(len > 1e-20f) || !isfinite(len))
        return frame_from_normal(n);
    Frame f;
    f.n = n;
    f.t = t / len;
    f.b = cross(n, f.t);
    return f;
}

inline float3 frame_to_local(Frame f, float3 v) { return (float3)(dot(v, f.t), dot(v, f.b), dot(v, f.n)); }
inline float3 frame_to_world(Frame f, float3 v) { return v.x * f.t + v.y * f.b + v.z * f.n; }

/* The material at one hit with its textures looked up: what the lobes read. */
typedef struct {
    uint type;     /* MATERIAL_* (never MIX: bsdf_at resolves mixes) */
    uint flags;    /* MATERIAL_FLAG_* */
    float3 base;   /* albedo, reflectance, tint or base_color */
    float3 eta, k; /* conductor */
    float3 specular_color;
    float alpha_x, alpha_y; /* GGX roughness along t and b */
    float ior, metallic, specular;
    float subsurface; /* principled: the share of the diffuse lobe that enters (principled.cl) */
} Bsdf;

#define BSDF_REFLECTION 1u
#define BSDF_TRANSMISSION 2u
#define BSDF_DELTA 4u

typedef struct {
    float3 wi;     /* local frame */
    float3 weight; /* f * |cos(wi)| / pdf; for delta lobes the lobe's value over its probability */
    float pdf_w;   /* solid-angle density; 0 for delta lobes */
    uint flags;    /* BSDF_REFLECTION or BSDF_TRANSMISSION, | BSDF_DELTA */
} BsdfSample;

inline BsdfSample bsdf_sample_none(void)
{
    BsdfSample s = {(float3)(0.0f, 0.0f, 1.0f), (float3)(0.0f), 0.0f, 0u};
    return s;
}

/* Below this GGX alpha a surface is smooth (a delta lobe): the microfacet terms lose precision
 * (pbrt-v4's EffectivelySmooth uses the same bound). */
#define BSDF_SMOOTH_ALPHA 1e-3f

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
