/* SPDX-License-Identifier: MIT */
/* principled.cl: glTF 2.0 metallic-roughness (Lambert diffuse plus GGX specular, Schlick Fresnel,
 * height-correlated Smith). */

/* TODO(materials, issue 16): the specular lobe; until then the diffuse base only. */
inline float3 principled_eval(const Bsdf *b, float3 wo, float3 wi, float *pdf_w)
{
    return diffuse_eval(b, wo, wi, pdf_w);
}

inline BsdfSample principled_sample(const Bsdf *b, float3 wo, float u1, float u2, float u3)
{
    return diffuse_sample(b, wo, u1, u2);
}
