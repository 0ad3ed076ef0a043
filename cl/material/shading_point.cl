/* SPDX-License-Identifier: MIT */
/* shading_point.cl: the set-up of a path vertex before anything is sampled there, the steps that
 * shade_surface's shade_path and render_aov share so that both see the same surface: sidedness
 * (shading_point), leaf resolution (resolve_leaf) and the BSDF in its frame (surface_bsdf). */

/* The shaded vertex as the arriving ray sees it (a small Cycles ShaderData). */
typedef struct {
    SurfaceHit surf;
    float3 wo;             /* unit, back along the arriving ray */
    float3 ng, ns;         /* geometric and shading normals, turned to wo's side */
    float cos_o_geometric; /* dot(wo, surf.geometric_normal): the emitter's cosine */
    bool front;            /* the ray arrived on the side surf.geometric_normal points to */
} ShadingPoint;

/* Sidedness: the surface at h, its normals turned toward the ray of direction d. */
PT_INLINE ShadingPoint shading_point(const SceneView *scene, Hit h, float time, float3 d)
{
    ShadingPoint sp;
    sp.surf = surface_at(scene, h, time);
    sp.wo = -d;
    sp.cos_o_geometric = dot(sp.wo, sp.surf.geometric_normal);
    sp.front = sp.cos_o_geometric > 0.0f;
    sp.ng = sp.front ? sp.surf.geometric_normal : -sp.surf.geometric_normal;
    sp.ns = sp.front ? sp.surf.shading_normal : -sp.surf.shading_normal;
    /* An interpolated normal facing away from the viewer gives way to the true one. */
    if (dot(sp.ns, sp.wo) <= 0.0f)
        sp.ns = sp.ng;
    return sp;
}

/* A mix material (resolve_leaf picks one of its leaves at each vertex). */
inline bool material_is_mix(uint type) { return PT_FEATURE(MIX) && type == MATERIAL_MIX; }

/* Leaf resolution: the index of the material whose BSDF scatters at the vertex, the hit's or the
 * leaf its mix resolves to (DIM_MIX). Emission, opacity and surface detail stay the hit
 * material's. The caller reads the leaf's Material itself (m unless m is a mix): returned
 * inside a struct, NVIDIA's compiler copied it from global memory byte by byte, with more
 * registers live in shade_surface (bench/README.md, "Architecture v3"). */
PT_INLINE uint resolve_leaf(const SceneView *scene, Material m, const SurfaceHit *surf, RngKey key,
                            uint bounce)
{
    if (!material_is_mix(m.type))
        return surf->material;
    return material_resolve_mix(scene, surf->material, surf->uv, surf->object_position,
                                rng_bounce(key, bounce, DIM_MIX));
}

/* The leaf's BSDF in its shading frame, and wo in that frame. */
typedef struct {
    Bsdf bsdf;
    Frame frame;
    float3 wo_local;
} SurfaceBsdf;

/* Textures are looked up in object space, the rest is world space (surface.cl). Normal and bump
 * maps and anisotropy need the uv tangent frame (surface_detail.cl); plain materials keep the
 * cheap one. */
PT_INLINE SurfaceBsdf surface_bsdf(const SceneView *scene, const ShadingPoint *sp, uint prim,
                                   Material m, Material leaf)
{
    SurfaceBsdf sb;
    sb.bsdf = bsdf_at(scene, leaf, sp->surf.uv, sp->surf.object_position);
    sb.frame = surface_needs_tangents(m, leaf)
                   ? surface_detail_frame(scene, prim, sp->surf, m, sp->wo, sp->front, sp->ng)
                   : frame_from_normal(sp->ns);
    sb.wo_local = frame_to_local(sb.frame, sp->wo);
    return sb;
}
