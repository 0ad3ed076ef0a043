/* SPDX-License-Identifier: MIT */
/* bsdf.cl: the material at a hit (textures looked up, mixes resolved) and the dispatch of eval,
 * pdf and sample to its lobes (diffuse.cl, conductor.cl, dielectric.cl, principled.cl). All in
 * the local shading frame of bsdf_common.cl. */

/* A scalar parameter: the constant, or its texture's red channel. Textures are looked up at uv,
 * procedural ones at the hit's position (texture_eval). */
inline float material_scalar(const SceneView *scene, uint texture, float value, float2 uv,
                             float3 position)
{
    return texture == NO_TEXTURE ? value : texture_eval(scene, texture, uv, position).x;
}

/* Resolves material `index` to one of its leaves when it is a mix, choosing b with probability
 * weight at each level: the expected BSDF is then (1 - w) f_a + w f_b, and next-event estimation
 * and BSDF sampling at this vertex both use the chosen leaf, so MIS stays consistent. u is reused
 * (rescaled) per level; the host bounds the nesting (MATERIAL_MIX_DEPTH_LIMIT) and refuses cycles.
 * Returns the leaf's index: the loop carries an index, not a 176-byte Material. */
inline uint material_resolve_mix(const SceneView *scene, uint index, float2 uv, float3 position,
                                 float u)
{
    for (uint level = 0u; level < MATERIAL_MIX_DEPTH_LIMIT; level++) {
        const global Material *m = &scene->materials[index];
        if (m->type != MATERIAL_MIX)
            break;
        float w = PT_FEATURE(TEXTURED_SCALARS)
                      ? material_scalar(scene, m->tex[MATERIAL_TEX_WEIGHT], m->weight, uv, position)
                      : m->weight;
        w = clamp(w, 0.0f, 1.0f);
        if (u < w) {
            u = u / w;
            index = m->mix_b;
        } else {
            u = (u - w) / (1.0f - w);
            index = m->mix_a;
        }
        u = fmin(u, 0x1.fffffep-1f);
    }
    return index;
}

/* The leaf material m (not a mix) at uv and position, textures looked up. */
inline Bsdf bsdf_at(const SceneView *scene, Material m, float2 uv, float3 position)
{
    Bsdf b;
    b.type = m.type;
    b.flags = m.flags;
    b.base = xyz(m.base);
    if (PT_FEATURE(TEXTURE) && m.tex[MATERIAL_TEX_BASE] != NO_TEXTURE)
        b.base *= xyz(texture_eval(scene, m.tex[MATERIAL_TEX_BASE], uv, position));
    b.eta = xyz(m.eta);
    b.k = xyz(m.k);
    b.specular_color = xyz(m.specular_color);
    b.ior = m.ior;
    b.metallic = m.metallic;
    b.specular = m.specular;
    b.subsurface = PT_FEATURE(MEDIA) ? m.subsurface : 0.0f;
    float r = m.roughness, aniso = m.anisotropy;
    if (PT_FEATURE(TEXTURED_SCALARS) && m.tex[MATERIAL_TEX_ROUGHNESS] != NO_TEXTURE)
        r = clamp(texture_eval(scene, m.tex[MATERIAL_TEX_ROUGHNESS], uv, position).x, 0.0f, 1.0f);
    if (PT_FEATURE(TEXTURED_SCALARS) && m.tex[MATERIAL_TEX_METALLIC] != NO_TEXTURE)
        b.metallic = clamp(texture_eval(scene, m.tex[MATERIAL_TEX_METALLIC], uv, position).x, 0.0f, 1.0f);
    /* DESIGN: alpha = r^2; anisotropy a stretches it along u and shrinks it along v. */
    float alpha = r * r, stretch = aniso > 0.0f ? sqrt(1.0f - 0.9f * aniso) : 1.0f;
    b.alpha_x = alpha / stretch;
    b.alpha_y = alpha * stretch;
    return b;
}

/* True when every lobe is a delta (no light sample can meet it: next-event estimation is skipped). */
inline bool bsdf_is_delta(const Bsdf *b)
{
    if (b->type == MATERIAL_CONDUCTOR)
        return conductor_is_smooth(b);
    if (b->type == MATERIAL_DIELECTRIC)
        return dielectric_is_smooth(b);
    return false;
}

/* f(wo, wi) * |cos(wi)| and the density bsdf_sample has of returning wi (0 for delta lobes). */
inline float3 bsdf_eval(const Bsdf *b, float3 wo, float3 wi, bool front, float *pdf_w)
{
    switch (b->type) {
    case MATERIAL_CONDUCTOR:
        return conductor_eval(b, wo, wi, pdf_w);
    case MATERIAL_DIELECTRIC:
        return dielectric_eval(b, wo, wi, front, pdf_w);
    case MATERIAL_PRINCIPLED:
        if (PT_FEATURE(PRINCIPLED))
            return principled_eval(b, wo, wi, front, pdf_w);
        return diffuse_eval(b, wo, wi, pdf_w);
    default:
        return diffuse_eval(b, wo, wi, pdf_w);
    }
}

inline BsdfSample bsdf_sample(const Bsdf *b, float3 wo, bool front, float u1, float u2, float u3)
{
    switch (b->type) {
    case MATERIAL_CONDUCTOR:
        return conductor_sample(b, wo, u1, u2);
    case MATERIAL_DIELECTRIC:
        return dielectric_sample(b, wo, front, u1, u2, u3);
    case MATERIAL_PRINCIPLED:
        if (PT_FEATURE(PRINCIPLED))
            return principled_sample(b, wo, front, u1, u2, u3);
        return diffuse_sample(b, wo, u1, u2);
    default:
        return diffuse_sample(b, wo, u1, u2);
    }
}

/* The albedo AOV: the colour a denoiser wants (base colour of the leaf). */
inline float3 bsdf_albedo(const Bsdf *b) { return b->base; }
