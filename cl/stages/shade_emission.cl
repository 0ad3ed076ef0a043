/* SPDX-License-Identifier: MIT */
/* shade_emission.cl: the light a path vertex gathers (shade_path, shade_surface.cl): an emitter or
 * the sky that the path's last segment sees, MIS-weighted against the light sampling of the vertex
 * it left (shade_next_event.cl), clamped as indirect light where --clamp asks, and added to the
 * sample's radiance. */

/* The solid-angle density with which light_sample would have chosen the emitter point that a ray
 * hit at distance t, cos_light to its normal (hit: its triangle and instance; surf: surface_at's). */
inline float emitter_light_pdf(constant RenderParams *p, const SceneView *scene, Material m,
                               Hit hit, const SurfaceHit *surf, float t, float cos_light)
{
    /* light_sample picks a triangle with probability area * emission.w / total power, then a point
     * with density 1 / area: per unit area that is emission.w / total power. */
    float light_pdf = m.emission.w / p->scene.emissive_power * t * t / cos_light;
    /* A moving instance's triangles were weighed by their area at shutter open (light_sample.cl). */
    if (PT_FEATURE(INSTANCES))
        light_pdf *= emitter_area_ratio(scene, hit.prim, hit.instance, surf->to_world);
    return light_pdf;
}

/* Emission seen along the ray, with the MIS weight against next-event estimation. */
inline float3 emission_seen(constant RenderParams *p, const SceneView *scene, Material m,
                            Hit hit, const SurfaceHit *surf, float t, float cos_light,
                            float prev_pdf_w, uint depth)
{
    if (m.emission.w <= 0.0f || cos_light <= 0.0f)
        return (float3)(0.0f);
    float3 L = xyz(m.emission);
    if (PT_FEATURE(EMISSION_TEXTURE) && m.tex[MATERIAL_TEX_EMISSION] != NO_TEXTURE)
        L *= xyz(texture_eval(scene, m.tex[MATERIAL_TEX_EMISSION], surf->uv, surf->object_position));
    /* Camera rays, specular bounces and BSDF-only rendering have no light-sampling rival. */
    if (depth == 1u || prev_pdf_w == 0.0f || (p->flags & RENDER_NO_NEE))
        return L;
    return L * mis_power(prev_pdf_w, emitter_light_pdf(p, scene, m, hit, surf, t, cos_light));
}

/* What an escaped ray sees: the constant background, or the environment map with the MIS weight
 * against next-event estimation (which picks the map with p->scene.env_pick_pdf, then samples
 * env_sample's density). */
inline float3 environment_seen(constant RenderParams *p, const EnvMap *env, float3 d,
                               float prev_pdf_w, uint depth)
{
    if (!PT_FEATURE(ENV) || p->scene.env_width == 0u)
        return xyz(p->background);
    float pdf_w;
    float3 L = env_lookup(env, d, &pdf_w);
    if (depth == 1u || prev_pdf_w == 0.0f || (p->flags & RENDER_NO_NEE))
        return L;
    return L * mis_power(prev_pdf_w, p->scene.env_pick_pdf * pdf_w);
}

/* radiance[k] += c, skipped when c is zero: most vertices gather nothing (no emitter hit), and the
 * window's radiance array is too large for the cache, so the read costs a miss (perf on PoCL: a
 * tenth of the shade kernel's time). A NaN still goes through to the film guard. */
inline void add_radiance(global float4 *restrict radiance, uint k, float3 c)
{
    if (c.x != 0.0f || c.y != 0.0f || c.z != 0.0f)
        radiance[k] += (float4)(c, 0.0f);
}

/* --clamp (RENDER_CLAMP_INDIRECT), Cycles' "clamp indirect": a contribution that reaches the camera
 * over two or more scattering vertices (an emitter or the sky hit by segment 3 or later, a light
 * connection from the second vertex on) is scaled down so that its largest channel is at most
 * clamp_indirect. Direct light (what the camera ray sees, the light at the first vertex by
 * connection or by the BSDF's ray) is never clamped. A NaN passes through to the film's guard. */
inline float3 clamp_indirect(constant RenderParams *p, float3 c, bool indirect)
{
    if (!(p->flags & RENDER_CLAMP_INDIRECT) || !indirect)
        return c;
    float largest = max3(c);
    return largest > p->clamp_indirect ? c * (p->clamp_indirect / largest) : c;
}

/* Escaped ray (Cycles' shade_background): the sky seen along direction (ray_direction's lane),
 * the environment and the suns, times beta, clamped as indirect light from segment 3 on. */
PT_INLINE float3 escaped_radiance(constant RenderParams *p, const SceneView *scene,
                                  const EnvMap *env, float4 direction, float3 beta, uint depth)
{
    float3 d = xyz(direction);
    float prev_pdf_w = ray_direction_pdf_w(direction);
    float3 sky = environment_seen(p, env, d, prev_pdf_w, depth);
    if (PT_FEATURE(ANALYTIC) && p->scene.num_analytic > 0u)
        sky += suns_seen(p, scene->analytic_lights, d, prev_pdf_w, depth);
    return clamp_indirect(p, beta * sky, depth >= 3u);
}

/* Emission with MIS (Cycles' surface_emission): what material m emits toward wo, times beta,
 * clamped as indirect light from segment 3 on. */
PT_INLINE float3 surface_emission(constant RenderParams *p, const SceneView *scene, Material m,
                                  Hit h, const ShadingPoint *sp, float prev_pdf_w, float3 beta,
                                  uint depth, float since_vertex)
{
    /* Light sampling saw the emitter from the last scattering vertex, which is since_vertex
     * before this segment's origin when the path passed interfaces on its way. */
    float3 L = emission_seen(p, scene, m, h, &sp->surf, since_vertex + h.t, sp->cos_o_geometric,
                             prev_pdf_w, depth);
    return clamp_indirect(p, beta * L, depth >= 3u);
}
