/* SPDX-License-Identifier: MIT */
/* shade_surface: one path vertex. Adds emission (MIS-weighted against light sampling), queues a
 * next-event shadow ray for non-delta materials, samples the BSDF for the next segment and applies
 * Russian roulette. depth = path_depth[slot] = segments traced so far (1 after the camera ray); paths
 * of different depths share a launch once slots are refilled.
 * Reads: hit, hit_instance (PT_FEATURE(INSTANCES)), path_time (PT_FEATURE(MOTION): where moving
 * instances and their emitters are), ray_*, throughput, path_depth, sample_id, scene. Writes:
 * radiance[sample_id], throughput, ray_* (next segment), shadow_* (waits when queued), path_depth
 * (depth + 1, or 0 when the path ends). Positions, normals and directions are world space;
 * textures are looked up at the hit's object-space point (surface.cl).
 * Next: intersect_shadow, then compaction. */

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

/* ---- shade_path's steps, in its order (the names of Cycles' integrator_shade_surface); the
 * vertex set-up it shares with render_aov (shading_point, resolve_leaf, surface_bsdf) is in
 * cl/material/shading_point.cl ---- */

/* Beer-Lambert: what of c survives `distance` inside the medium in slot `medium` when it only
 * absorbs (a dielectric's absorption, a medium without scattering); outside any (0), c itself. */
PT_INLINE float3 through_medium(const SceneView *scene, uint medium, float3 c, float distance)
{
    if (PT_FEATURE(ABSORPTION) && medium != 0u)
        c *= dielectric_transmittance(xyz(medium_at_slot(scene, medium)->sigma_a), distance);
    return c;
}

/* The medium slot a ray leaving the surface toward w runs in: the surface's exterior (w on the
 * side geometric_normal points to) or interior when its material tm bounds media, else the
 * path's own (shared/medium.h). */
PT_INLINE uint medium_toward(constant RenderParams *p, Material tm, float3 geometric_normal,
                             float3 w, uint medium)
{
    /* A scene without media has no medium interface: its programs carry none of this. */
    if (!(PT_FEATURE(ABSORPTION) || PT_FEATURE(MEDIA)) ||
        !(tm.flags & MATERIAL_FLAG_MEDIUM_INTERFACE))
        return medium;
    uint next = dot(w, geometric_normal) > 0.0f ? tm.exterior : tm.interior;
    return next == MEDIUM_SLOT_WORLD ? p->scene.world_medium : next;
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

/* A next-event shadow ray as shade_path queues it (queue_shadow_ray): intersect_shadow adds
 * contribution to the sample's radiance unless something lies along direction before tmax. */
typedef struct {
    float3 origin, direction, contribution;
    float tmax;
    uint medium; /* the slot of the medium it starts in (intersect_shadow tracks it with media) */
    bool queued; /* false: no ray, the other fields undefined */
} ShadowRay;

/* The ray from origin (off the surface toward wi) to light sample ls. It ends at the light point
 * moved off the light by the same robust offset, toward the shaded point: it reaches everything
 * in front of the light, however close, and never the light's own triangle (the test is
 * half-open, t < tmax). */
PT_INLINE ShadowRay shadow_ray_to(LightSample ls, float3 origin, float3 wi)
{
    ShadowRay ray;
    ray.origin = origin;
    ray.tmax = INFINITY;
    ray.direction = wi;
    if (ls.delta && !ls.at_infinity) {
        /* A point or spot light has no surface: the ray ends exactly at it. */
        ray.tmax = length(ls.position - origin);
        ray.direction = (ls.position - origin) / ray.tmax;
    } else if (!ls.at_infinity) {
        float3 target = offset_ray_origin(ls.position, ls.normal, origin - ls.position);
        ray.tmax = length(target - origin);
        ray.direction = (target - origin) / ray.tmax;
    }
    return ray;
}

/* Light connection (Cycles' surface_direct_light): next-event estimation for every non-delta
 * BSDF, one light sample weighed against BSDF sampling; a ray not queued when there is none. */
PT_INLINE ShadowRay connect_light(constant RenderParams *p, const SceneView *scene,
                                  const EnvMap *env, const ShadingPoint *sp, const SurfaceBsdf *sb,
                                  Material tm, float3 beta, uint medium, float time, RngKey key,
                                  uint bounce, uint depth)
{
    ShadowRay none;
    none.queued = false;
    if (bsdf_is_delta(&sb->bsdf) || p->scene.num_emissive == 0u || (p->flags & RENDER_NO_NEE))
        return none;
    float3 position = sp->surf.position;
    LightSample ls = light_sample(scene, env, p->scene.num_emissive, position, time, key, bounce);
    float3 wi = ls.direction;
    float3 wi_local = frame_to_local(sb->frame, wi);
    float bsdf_pdf;
    float3 f_cos = bsdf_eval(&sb->bsdf, sb->wo_local, wi_local, sp->front, &bsdf_pdf);
    /* The light must lie on the side of the true surface that the shading frame puts it on
     * (reflection above, transmission below): shading normals never leak light. */
    bool same_side = (dot(wi, sp->ng) > 0.0f) == (wi_local.z > 0.0f);
    if (!(ls.pdf_w > 0.0f && max3(f_cos) > 0.0f && same_side))
        return none;
    /* A delta light cannot be hit by the BSDF's rays: no MIS. */
    float weight = ls.delta ? 1.0f : mis_power(ls.pdf_w, bsdf_pdf);
    float3 contribution = beta * f_cos * ls.radiance * (weight / ls.pdf_w);
    /* With media, intersect_shadow tracks the ray from the medium on wi's side; without, a light
     * seen from inside an absorbing dielectric (rare: a lamp inside glass) is dimmed here. */
    uint shadow_medium = medium_toward(p, tm, sp->surf.geometric_normal, wi, medium);
    if (!PT_FEATURE(MEDIA) && wi_local.z > 0.0f)
        contribution = through_medium(scene, medium, contribution,
                                      ls.at_infinity ? INFINITY : length(ls.position - position));
    float3 origin = offset_ray_origin(position, sp->surf.geometric_normal, wi);
    ShadowRay ray = shadow_ray_to(ls, origin, wi);
    ray.medium = shadow_medium;
    ray.contribution = clamp_indirect(p, contribution, depth >= 2u);
    ray.queued = true;
    return ray;
}

/* Stores a queued shadow ray in slot's shadow lanes (bounce: for its cut-out stream); true when
 * queued. */
PT_INLINE bool queue_shadow_ray(PATH_STATE_PARAMS uint slot, ShadowRay ray, uint bounce)
{
    if (!ray.queued)
        return false;
    shadow_origin[slot] = shadow_origin_pack(ray.origin, ray.tmax);
    shadow_direction[slot] = shadow_direction_pack(ray.direction, bounce, ray.medium);
    shadow_contribution[slot] = shadow_contribution_pack(ray.contribution, true);
    return true;
}

/* Russian roulette (Cycles' path_terminate), driven by the throughput: false when the path ends,
 * else beta is divided by the survival probability. It may end paths from the vertex
 * PT_ROULETTE_DEPTH on (depth counts segments; Mitsuba's default rr_depth 5 is PT_ROULETTE_DEPTH
 * 5). The fifth, not the third: the error per second measured lower so (bench/README.md "Sampler
 * and estimator"). A build option so that the estimator studies can set it through PT_CL_OPTIONS. */
#ifndef PT_ROULETTE_DEPTH
#define PT_ROULETTE_DEPTH 5u
#endif
PT_INLINE bool survives_roulette(float3 *beta, float eta_scale, float u)
{
    /* The throughput without the radiance compression of the refractions so far (eta_scale:
     * ray_origin_pack), as Mitsuba's and pbrt's roulettes: inside glass beta carries 1 / eta^2,
     * and judging that would end twice the paths of a medium of ior 1.4 for no gain in
     * efficiency (bench/README.md "Media against Mitsuba 3"). */
    float q = fmin(max3(*beta) * eta_scale, 0.95f);
    if (u >= q)
        return false;
    *beta /= q;
    return true;
}

/* Continuation (Cycles' surface_bounce): samples the BSDF, then roulette (PT_ROULETTE_DEPTH);
 * when the path goes on, writes the next segment's ray and throughput (in the medium on the new
 * direction's side of tm, medium_toward) and returns true. */
PT_INLINE bool continue_path(constant RenderParams *p, PATH_STATE_PARAMS uint slot,
                             const ShadingPoint *sp, const SurfaceBsdf *sb, Material tm,
                             float3 beta, float eta_scale, uint medium, uint crossings, RngKey key,
                             uint bounce, uint depth)
{
    /* DIM_BSDF_U, _V, _LOBE, DIM_ROULETTE: one Sobol tuple (the lobe stratified with the direction) */
    uint4 u = rng_bounce_bits4(key, bounce, DIM_BSDF_U);
    BsdfSample bs = bsdf_sample(&sb->bsdf, sb->wo_local, sp->front, uint_to_unit(u.x), uint_to_unit(u.y),
                                uint_to_unit(u.z));
    float3 wi = frame_to_world(sb->frame, bs.wi);
    beta *= bs.weight;
    /* A sample on the other side of the true surface than its lobe says (possible with shading
     * normals) is lost, never counted on the wrong side. */
    bool reflects = (bs.flags & BSDF_REFLECTION) != 0u;
    if (bs.flags == 0u || (dot(wi, sp->ng) > 0.0f) != reflects)
        return false;
    /* A refraction compressed the radiance by 1 / eta^2 (dielectric.cl). */
    if (PT_FEATURE(REFRACTION) && (bs.flags & BSDF_TRANSMISSION) &&
        sb->bsdf.type == MATERIAL_DIELECTRIC) {
        float eta = dielectric_eta(&sb->bsdf, sp->front);
        eta_scale *= eta * eta;
    }
    if (depth >= PT_ROULETTE_DEPTH && !survives_roulette(&beta, eta_scale, uint_to_unit(u.w)))
        return false;
    if (!(max3(beta) > 0.0f))
        return false;
    float3 origin = offset_ray_origin(sp->surf.position, sp->surf.geometric_normal, wi);
    ray_origin[slot] = ray_origin_pack_eta(p, origin, eta_scale);
    ray_direction[slot] = ray_direction_pack(wi, bs.pdf_w);
    uint next = medium_toward(p, tm, sp->surf.geometric_normal, wi, medium);
    throughput[slot] = throughput_pack(beta, medium_state(next, crossings));
    return true;
}

/* ---- Media (cl/medium/): the vertex where a path scatters inside a medium, and the pass
 * through an `interface` surface ---- */

/* A scattering at position inside medium slot `medium` (the path arrived along d with weight
 * beta): next-event estimation with the phase function weighed against phase sampling, then the
 * phase sample and roulette, as a surface vertex does with its BSDF. True when it queued a shadow
 * ray. The vertex counts toward max_depth. */
PT_INLINE bool shade_medium_vertex(constant RenderParams *p, const SceneView *scene,
                                   const EnvMap *env, PATH_STATE_PARAMS uint slot, float3 position,
                                   float3 d, float3 beta, float eta_scale, uint state, float time,
                                   RngKey key, uint bounce, uint depth)
{
    shadow_contribution[slot] = shadow_contribution_pack((float3)(0.0f), false);
    if (depth >= p->max_depth) {
        path_depth[slot] = 0u;
        return false;
    }
    uint medium = medium_state_slot(state);
    float g = medium_at_slot(scene, medium)->sigma_a.w;
    bool queued = false;
    if (p->scene.num_emissive > 0u && !(p->flags & RENDER_NO_NEE)) {
        LightSample ls = light_sample(scene, env, p->scene.num_emissive, position, time, key, bounce);
        float phase = phase_hg(g, dot(d, ls.direction));
        if (ls.pdf_w > 0.0f && phase > 0.0f) {
            float weight = ls.delta ? 1.0f : mis_power(ls.pdf_w, phase);
            ShadowRay ray = shadow_ray_to(ls, position, ls.direction);
            ray.contribution =
                clamp_indirect(p, beta * phase * ls.radiance * (weight / ls.pdf_w), depth >= 2u);
            ray.medium = medium;
            ray.queued = true;
            queued = queue_shadow_ray(PATH_STATE_ARGS slot, ray, bounce);
        }
    }
    uint4 u = rng_bounce_bits4(key, bounce, DIM_BSDF_U);
    float pdf_w;
    float3 wi = phase_hg_sample(g, d, uint_to_unit(u.x), uint_to_unit(u.y), &pdf_w);
    bool survives = !(depth >= PT_ROULETTE_DEPTH &&
                      !survives_roulette(&beta, eta_scale, uint_to_unit(u.w)));
    if (!(survives && max3(beta) > 0.0f)) {
        path_depth[slot] = 0u;
        return queued;
    }
    ray_origin[slot] = ray_origin_pack_eta(p, position, eta_scale);
    ray_direction[slot] = ray_direction_pack(wi, pdf_w);
    throughput[slot] = throughput_pack(beta, medium_state(medium, medium_state_crossings(state)));
    path_depth[slot] = depth + 1u;
    return queued;
}

/* An `interface` surface, reached after since_vertex + t from the last scattering vertex: the path
 * goes on along d from just past it, in the medium on the far side, with the same MIS density
 * (the last scattering's) and depth; the crossing count grows and since_vertex keeps the distance
 * (medium_state). */
PT_INLINE void cross_interface(constant RenderParams *p, PATH_STATE_PARAMS uint slot,
                               const ShadingPoint *sp, Material m, float4 direction, float3 beta,
                               float eta_scale, uint medium, uint crossings, float distance)
{
    float3 d = xyz(direction);
    shadow_contribution[slot] = shadow_contribution_pack((float3)(0.0f), false);
    if (crossings >= MEDIUM_CROSSING_LIMIT) {
        path_depth[slot] = 0u;
        return;
    }
    uint next = medium_toward(p, m, sp->surf.geometric_normal, d, medium);
    float3 origin = offset_ray_origin(sp->surf.position, sp->surf.geometric_normal, d);
    ray_origin[slot] = ray_origin_pack_eta(p, origin, eta_scale);
    throughput[slot] = throughput_pack(beta, medium_state_after_crossing(next, crossings + 1u));
    since_vertex[slot] = distance;
}

/* Shades the path in slot; true when it queued a shadow ray. */
PT_INLINE bool shade_path(constant RenderParams *p, const SceneView *scene,
                          PATH_STATE_PARAMS uint slot)
{
    uint depth = path_depth[slot];
    if (depth == 0u)
        return false;
    uint k = sample_id[slot];
    float4 hit4 = hit[slot], direction = ray_direction[slot], throughput4 = throughput[slot];
    uint state = throughput_medium(throughput4);
    uint medium = medium_state_slot(state), crossings = medium_state_crossings(state);
    /* The vertex's numbers (crossings: medium_state). */
    uint bounce = depth - 1u + crossings;
    float3 beta = xyz(throughput4);
    EnvMap env = env_map(p, scene);
    float time = PT_FEATURE(MOTION) ? path_time[slot] : 0.0f;
    /* Read only where a refraction can have changed it (the camera ray's is 1). */
    float eta_scale = PT_FEATURE(REFRACTION) && depth > 1u
                          ? ray_origin_eta_scale(p, ray_origin[slot]) : 1.0f;
    if (PT_FEATURE(MEDIA) && medium_tracks(scene, medium)) {
        /* The segment just traced runs through a medium that scatters or emits: it may end in
         * the medium before the surface (or the sky). */
        RngKey key = path_rng_key(p, active_pixels, k);
        float3 origin = xyz(ray_origin[slot]), emitted = (float3)(0.0f);
        float t_event;
        MediumRng rng = medium_rng(rng_bounce_bits(key, bounce, DIM_MEDIUM), 0x6d2b79f5u);
        float tmax = hit_prim(hit4) == HIT_NONE ? INFINITY : hit_t(hit4);
        uint event = medium_track(scene, medium_at_slot(scene, medium), origin, xyz(direction),
                                  tmax, &rng, &beta, &emitted, &t_event);
        add_radiance(radiance, k, clamp_indirect(p, emitted, depth >= 3u));
        if (event == MEDIUM_EVENT_SCATTER)
            return shade_medium_vertex(p, scene, &env, PATH_STATE_ARGS slot,
                                       origin + t_event * xyz(direction), xyz(direction), beta,
                                       eta_scale, state, time, key, bounce, depth);
        if (event == MEDIUM_EVENT_ABSORB) {
            shadow_contribution[slot] = shadow_contribution_pack((float3)(0.0f), false);
            path_depth[slot] = 0u;
            return false;
        }
    } else {
        /* Absorption along the segment just traced. */
        beta = through_medium(scene, medium, beta, hit_t(hit4));
    }
    if (hit_prim(hit4) == HIT_NONE) {
        add_radiance(radiance, k, escaped_radiance(p, scene, &env, direction, beta, depth));
        path_depth[slot] = 0u;
        return false;
    }
    Hit h = path_hit(hit4, PT_FEATURE(INSTANCES) ? hit_instance[slot] : 0u);
    ShadingPoint sp = shading_point(scene, h, time, xyz(direction));
    Material m = scene->materials[sp.surf.material];
    /* The distance from the last scattering vertex to this segment's origin (medium_state). */
    float before = PT_FEATURE(MEDIA) && medium_state_crossed(state) ? since_vertex[slot] : 0.0f;
    if (PT_FEATURE(MEDIA) && m.type == MATERIAL_INTERFACE) {
        cross_interface(p, PATH_STATE_ARGS slot, &sp, m, direction, beta, eta_scale, medium,
                        crossings, before + h.t);
        return false;
    }
    float prev_pdf_w = ray_direction_pdf_w(direction);
    float3 gathered = surface_emission(p, scene, m, h, &sp, prev_pdf_w, beta, depth, before);

    bool path_continues = depth < p->max_depth;
    bool queued = false;
    shadow_contribution[slot] = shadow_contribution_pack((float3)(0.0f), false);
    if (path_continues) {
        RngKey key = path_rng_key(p, active_pixels, k);
        uint leaf_index = resolve_leaf(scene, m, &sp.surf, key, bounce);
        Material leaf = material_is_mix(m.type) ? scene->materials[leaf_index] : m;
        /* The media a mix's leaf bounds (a dielectric's absorption) are the leaf's. */
        Material tm = (leaf.flags & MATERIAL_FLAG_MEDIUM_INTERFACE) ? leaf : m;
        SurfaceBsdf sb = surface_bsdf(scene, &sp, h.prim, m, leaf);
        ShadowRay shadow =
            connect_light(p, scene, &env, &sp, &sb, tm, beta, medium, time, key, bounce, depth);
        queued = queue_shadow_ray(PATH_STATE_ARGS slot, shadow, bounce);
        path_continues = continue_path(p, PATH_STATE_ARGS slot, &sp, &sb, tm, beta, eta_scale,
                                       medium, crossings, key, bounce, depth);
    }
    add_radiance(radiance, k, gathered);
    path_depth[slot] = path_continues ? depth + 1u : 0u;
    return queued;
}

/* With shadow_queue != 0 (RENDER_SHADOW_QUEUE), the slots that queued a shadow ray are appended to
 * shadow_queue[] (one global atomic per work-group, on shadow_count[0]) so that intersect_shadow
 * runs over those only; otherwise intersect_shadow checks every active slot's flag. */
#if PT_PART(CORE)
kernel void shade_surface(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                          const global uint *active, uint n_active, global uint *shadow_queue,
                          global uint *shadow_count)
{
    local uint group_count, group_base;
    SceneView scene = SCENE_VIEW;
    uint i = get_global_id(0);
    uint slot = i < n_active ? active[i] : 0u;
    bool queued = i < n_active && shade_path(p, &scene, PATH_STATE_ARGS slot);
    if (!(p->flags & RENDER_SHADOW_QUEUE))
        return; /* uniform: no barrier below is reached by anyone */
    if (get_local_id(0) == 0)
        group_count = 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    uint rank = queued ? atomic_inc(&group_count) : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (get_local_id(0) == 0 && group_count > 0)
        group_base = atomic_add(shadow_count, group_count);
    barrier(CLK_LOCAL_MEM_FENCE);
    if (queued)
        shadow_queue[group_base + rank] = slot;
}
#endif
