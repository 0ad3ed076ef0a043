/* SPDX-License-Identifier: MIT */
/* microfacet.cl: the GGX (Trowbridge-Reitz) distribution, Smith masking-shadowing and the sampling
 * of visible normals, in the local shading frame (bsdf_common.cl): alpha_x is the roughness along
 * the tangent (local x), alpha_y along the bitangent (local y).
 * Sources: Walter et al. 2007 "Microfacet Models for Refraction through Rough Surfaces" (D, G1);
 * Heitz 2014 "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs" (anisotropic
 * Lambda, separable and height-correlated G); Heitz 2018 "Sampling the GGX Distribution of Visible
 * Normals" (the sampling routine and its pdf); pbrt-v4 sec. 9.6 (same formulas). */

/* True when a lobe with these roughnesses is a delta (bsdf_is_delta uses the same bound). */
inline bool microfacet_smooth(float alpha_x, float alpha_y)
{
    return fmax(alpha_x, alpha_y) < BSDF_SMOOTH_ALPHA;
}

/* D(m) = 1 / (pi ax ay (x^2/ax^2 + y^2/ay^2 + z^2)^2), m a unit microfacet normal; 0 below the
 * surface. Normalised so that the projected area integrates to one: int D(m) m.z dm = 1. */
inline float ggx_d(float3 m, float alpha_x, float alpha_y)
{
    if (m.z <= 0.0f)
        return 0.0f;
    float x = m.x / alpha_x, y = m.y / alpha_y;
    float t = x * x + y * y + m.z * m.z;
    return 1.0f / (M_PI_F * alpha_x * alpha_y * t * t);
}

/* Smith's Lambda for GGX: (-1 + sqrt(1 + (ax^2 x^2 + ay^2 y^2) / z^2)) / 2. Symmetric in z, so it
 * serves transmitted directions (z < 0) too. Infinite at grazing (z = 0): G1 = 0 there. */
inline float ggx_lambda(float3 w, float alpha_x, float alpha_y)
{
    float z2 = w.z * w.z;
    if (!(z2 > 0.0f))
        return INFINITY;
    float ax = alpha_x * w.x, ay = alpha_y * w.y;
    float tan2 = (ax * ax + ay * ay) / z2;
    return 0.5f * (sqrt(1.0f + tan2) - 1.0f);
}

inline float ggx_g1(float3 w, float alpha_x, float alpha_y)
{
    return 1.0f / (1.0f + ggx_lambda(w, alpha_x, alpha_y));
}

/* Separable masking-shadowing G1(wo) G1(wi) (Walter 2007; conductor and dielectric, as DESIGN). */
inline float ggx_g_separable(float3 wo, float3 wi, float alpha_x, float alpha_y)
{
    return ggx_g1(wo, alpha_x, alpha_y) * ggx_g1(wi, alpha_x, alpha_y);
}

/* Height-correlated masking-shadowing 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014 eq. 99;
 * glTF 2.0's V_GGX is this over 4 |n.l| |n.v|). */
inline float ggx_g_correlated(float3 wo, float3 wi, float alpha_x, float alpha_y)
{
    return 1.0f / (1.0f + ggx_lambda(wo, alpha_x, alpha_y) + ggx_lambda(wi, alpha_x, alpha_y));
}

/* Density of the visible normals seen from wo (wo.z > 0): D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z
 * (Heitz 2018 eq. 3). ggx_sample_visible draws m with this density. */
inline float ggx_pdf_visible(float3 wo, float3 m, float alpha_x, float alpha_y)
{
    float cos_om = dot(wo, m);
    if (!(cos_om > 0.0f) || !(wo.z > 0.0f))
        return 0.0f;
    return ggx_g1(wo, alpha_x, alpha_y) * cos_om * ggx_d(m, alpha_x, alpha_y) / wo.z;
}

/* A microfacet normal visible from wo (wo.z > 0), distributed as ggx_pdf_visible (Heitz 2018,
 * listing 1): stretch wo to the hemisphere configuration (alpha 1), sample the projected
 * hemisphere (a disc whose far half is squeezed by the visible fraction), unstretch. */
inline float3 ggx_sample_visible(float3 wo, float alpha_x, float alpha_y, float u1, float u2)
{
    float3 vh = normalize((float3)(alpha_x * wo.x, alpha_y * wo.y, wo.z));
    float len2 = vh.x * vh.x + vh.y * vh.y;
    float3 t1 = len2 > 0.0f ? (float3)(-vh.y, vh.x, 0.0f) * rsqrt(len2) : (float3)(1.0f, 0.0f, 0.0f);
    float3 t2 = cross(vh, t1);
    float r = sqrt(u1);
    float2 cs = cos_sin_turns(u2); /* phi = 2 pi u2 */
    float p1 = r * cs.x, p2 = r * cs.y;
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - p1 * p1)) + s * p2;
    float3 nh = p1 * t1 + p2 * t2 + sqrt(fmax(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return normalize((float3)(alpha_x * nh.x, alpha_y * nh.y, fmax(1e-7f, nh.z)));
}
