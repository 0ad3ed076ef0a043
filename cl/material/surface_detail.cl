/* SPDX-License-Identifier: MIT */
/* surface_detail.cl: what a material changes about the surface itself rather than its scattering:
 * the tangent frame (DESIGN "Conventions"), normal and bump maps (DESIGN "Materials"), and alpha
 * cut-outs (the stochastic pass-through that intersect_closest and intersect_shadow apply). */

/* A ray passes through at most this many cut-out layers; the next one stops it (a bound for the
 * GPU's sake: foliage has a few dozen layers at most). */
#define CUTOUT_MAX_LAYERS 64u

/* ---- Tangent frames, normal and bump maps ----------------------------------------------------- */

/* Whether shading needs the uv tangent frame: a normal or bump map on the hit's material, or an
 * anisotropic leaf. Everything else keeps frame_from_normal (no triangle reads). */
inline bool surface_needs_tangents(Material m, Material leaf)
{
    return PT_FEATURE(SURFACE_DETAIL) &&
           (m.tex[MATERIAL_TEX_NORMAL] != NO_TEXTURE || m.tex[MATERIAL_TEX_BUMP] != NO_TEXTURE ||
            leaf.anisotropy != 0.0f);
}

/* Bump mapping as pbrt-v4's BumpMap: the height h = bump_scale * red(texture) displaces the
 * surface along n; forward differences one texel apart in u and v (the host has no ray
 * differentials) give the displaced dp/du and dp/dv, whose cross product is the new normal,
 * turned to n's side. pbrt's h * dn/du term is left out (interpolated normals vary slowly over a
 * texel). dpdu, dpdv: the triangle's in world space, n: the unit shading normal on the geometric
 * front; position, object_dpdu, object_dpdv: the hit and the triangle's derivatives in object
 * space, where the texture is looked up (noise: the steps' neighbours). The height is in world
 * units (displacement is not scaled with the instance, as pbrt applies bump in render space). */
inline float3 bump_normal(const SceneView *scene, Material m, float2 uv, float3 position,
                          float3 object_dpdu, float3 object_dpdv, float3 n, float3 dpdu, float3 dpdv)
{
    uint tex = m.tex[MATERIAL_TEX_BUMP];
    TextureInfo info = scene->textures[tex];
    /* Noise has no texels: a step of 1/1024 in uv and the matching step along the surface. */
    bool noise = info.format == TEXTURE_NOISE;
    float du = noise ? 1.0f / 1024.0f : 1.0f / (float)info.width;
    float dv = noise ? 1.0f / 1024.0f : 1.0f / (float)info.height;
    float h = texture_eval(scene, tex, uv, position).x;
    float h_u = texture_eval(scene, tex, uv + (float2)(du, 0.0f), position + du * object_dpdu).x;
    float h_v = texture_eval(scene, tex, uv + (float2)(0.0f, dv), position + dv * object_dpdv).x;
    /* The shading dp/du and dp/dv: the triangle's, made tangent to the shading normal. */
    float3 su = dpdu - n * dot(n, dpdu), sv = dpdv - n * dot(n, dpdv);
    float3 bu = su + (m.bump_scale * (h_u - h) / du) * n;
    float3 bv = sv + (m.bump_scale * (h_v - h) / dv) * n;
    float3 b = cross(bu, bv);
    float len = length(b);
    if (!(len > 0.0f) || !isfinite(len))
        return n;
    b /= len;
    return dot(b, n) < 0.0f ? -b : b; /* mirrored uvs give the cross product the other way */
}

/* Normal mapping in tangent space, OpenGL convention: the texel's rgb (linear) maps to
 * (2 r - 1, 2 g - 1, 2 b - 1) along (t, b, n), t along increasing u and b along increasing v, so
 * a mirrored uv island gets a mirrored frame (MikkTSpace's bitangent sign), and so does a
 * mirrored instance. The map's xy is scaled by bump_scale (MTL's -bm; 1 when absent). n, dpdu,
 * dpdv in world space; position in object space (the texture lookup's). */
inline float3 normal_map_normal(const SceneView *scene, Material m, float2 uv, float3 position,
                                float3 n, float3 dpdu, float3 dpdv)
{
    float3 t = dpdu - n * dot(n, dpdu);
    float len = length(t);
    if (!(len > 0.0f) || !isfinite(len))
        return n;
    t /= len;
    float3 b = cross(n, t);
    if (dot(b, dpdv) < 0.0f)
        b = -b;
    float3 c = 2.0f * xyz(texture_eval(scene, m.tex[MATERIAL_TEX_NORMAL], uv, position)) - 1.0f;
    float3 mapped = m.bump_scale * (c.x * t + c.y * b) + c.z * n;
    float mapped_len = length(mapped);
    if (!(mapped_len > 0.0f) || !isfinite(mapped_len))
        return n;
    return mapped / mapped_len;
}

/* The shading frame of a hit whose material needs tangents (surface_needs_tangents): the normal
 * bumped and/or normal-mapped (bump first, then the normal map relative to it), turned to wo's
 * side (front: wo on the geometric normal's side); when it faces away from wo, the geometric
 * normal ng (already on wo's side) replaces it as for interpolated normals. x follows dp/du. All
 * in world space; textures are looked up in object space (surface.cl). */
inline Frame surface_detail_frame(const SceneView *scene, uint prim, SurfaceHit surf, Material m,
                                  float3 wo, bool front, float3 ng)
{
    float3 dpdu, dpdv, object_dpdu, object_dpdv;
    surface_uv_derivatives(scene, prim, &surf, &dpdu, &dpdv, &object_dpdu, &object_dpdv);
    float3 n = surf.shading_normal;
    if (PT_FEATURE(BUMP_MAP) && m.tex[MATERIAL_TEX_BUMP] != NO_TEXTURE)
        n = bump_normal(scene, m, surf.uv, surf.object_position, object_dpdu, object_dpdv, n, dpdu,
                        dpdv);
    if (m.tex[MATERIAL_TEX_NORMAL] != NO_TEXTURE)
        n = normal_map_normal(scene, m, surf.uv, surf.object_position, n, dpdu, dpdv);
    if (!front)
        n = -n;
    if (dot(n, wo) <= 0.0f)
        n = ng;
    return frame_from_tangent(n, dpdu);
}

/* ---- Alpha cut-out ------------------------------------------------------------------------------ */

/* The opacity of material m at a point: its texture's red channel or the constant, times the base
 * texture's alpha with MATERIAL_FLAG_BASE_ALPHA; with MATERIAL_FLAG_ALPHA_MASK, 1 where that
 * reaches the cutoff base.w and 0 below (glTF's alphaMode MASK). */
inline float material_opacity(const SceneView *scene, Material m, float2 uv, float3 position)
{
    float opacity = PT_FEATURE(TEXTURE) && m.tex[MATERIAL_TEX_OPACITY] != NO_TEXTURE
                        ? texture_eval(scene, m.tex[MATERIAL_TEX_OPACITY], uv, position).x
                        : m.opacity;
    if (PT_FEATURE(TEXTURE) && (m.flags & MATERIAL_FLAG_BASE_ALPHA) &&
        m.tex[MATERIAL_TEX_BASE] != NO_TEXTURE)
        opacity *= texture_eval(scene, m.tex[MATERIAL_TEX_BASE], uv, position).w;
    if (m.flags & MATERIAL_FLAG_ALPHA_MASK)
        opacity = opacity >= m.base.w ? 1.0f : 0.0f;
    return opacity;
}

/* Whether a ray passes through the hit (barycentrics u, v) on triangle prim: never for opaque
 * materials; for a cut-out with probability 1 - opacity. The number is a hash of the ray's stream
 * (rng_bounce_bits of the path's key, bounce and DIM_OPACITY or DIM_SHADOW_OPACITY) and the
 * triangle, so that each layer a ray meets gets its own number and renders stay reproducible. */
inline bool cutout_passes(const SceneView *scene, uint instance, uint prim, float u, float v,
                          uint stream)
{
    Material m = scene->materials[scene->material_ids[prim]];
    if (!(m.flags & MATERIAL_FLAG_CUTOUT))
        return false;
    float3 position;
    float2 uv = surface_uv_at(scene, prim, u, v, &position);
    /* Instance 0 (every one-level scene's) leaves v1's numbers as they were. */
    float x = uint_to_unit(hash_pcg(stream ^ hash_pcg(prim ^ 0x5bd1e995u ^ instance * 0x9e3779b9u)));
    return x >= material_opacity(scene, m, uv, position);
}

/* Closest hit in [0, tmax) that the cut-outs let stop the ray: after a pass-through the same ray
 * is traced again from just past the layer (same origin and direction, so every triangle's t is
 * the same bits and the layer cannot be met again). A second triangle at exactly the same t is
 * skipped with it. brute_count: scene_trace.cl's (SCENE_BRUTE_FORCE_COUNT). */
inline Hit trace_closest_through(const SceneView *scene, uint brute_count, float3 o, float3 d,
                                 float tmin, float tmax, float time, bool brute_force, uint stream)
{
    for (uint layer = 0u;; layer++) {
        Hit h = brute_force ? scene_brute_force(scene, brute_count, o, d, tmin, tmax, false, time)
                            : scene_closest(scene, brute_count, o, d, tmin, tmax, time);
        if (h.prim == HIT_NONE || layer == CUTOUT_MAX_LAYERS ||
            !cutout_passes(scene, h.instance, h.prim, h.u, h.v, stream))
            return h;
        tmin = nextafter(h.t, INFINITY);
    }
}

/* Whether anything stops a shadow ray over [0, tmax): one any-hit query answers when the hit it
 * finds is opaque (or nothing is hit); a cut-out hit walks the layers front to back instead. */
inline bool trace_occluded_through(const SceneView *scene, uint brute_count, float3 o, float3 d,
                                   float tmax, float time, bool brute_force, uint stream)
{
    Hit any = brute_force ? scene_brute_force(scene, brute_count, o, d, 0.0f, tmax, true, time)
                          : scene_any(scene, brute_count, o, d, 0.0f, tmax, time);
    if (any.prim == HIT_NONE)
        return false;
    Material m = scene->materials[scene->material_ids[any.prim]];
    if (!(m.flags & MATERIAL_FLAG_CUTOUT))
        return true;
    return trace_closest_through(scene, brute_count, o, d, 0.0f, tmax, time, brute_force, stream)
               .prim != HIT_NONE;
}
