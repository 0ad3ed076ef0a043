/* SPDX-License-Identifier: MIT */
/* shade_surface: one path vertex. Adds emission (MIS-weighted against light sampling), queues a
 * next-event shadow ray for non-delta materials, samples the BSDF for the next segment and applies
 * Russian roulette. depth = path_depth[slot] = segments traced so far (1 after the camera ray); paths
 * of different depths share a launch once slots are refilled.
 * Reads: hit, hit_instance (PT_FEATURE_INSTANCES), path_time (PT_FEATURE_MOTION: where moving
 * instances and their emitters are), ray_*, throughput, path_depth, sample_id, scene. Writes:
 * radiance[sample_id], throughput, ray_* (next segment), shadow_* (w = 1 when queued), path_depth
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
#if PT_FEATURE_INSTANCES
    /* A moving instance's triangles were weighed by their area at shutter open (light_sample.cl). */
    light_pdf *= emitter_area_ratio(scene, hit.prim, hit.instance, surf->to_world);
#else
    (void)scene, (void)hit, (void)surf;
#endif
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
    if (PT_HAS_MATERIAL_FEATURE(EMISSION_TEXTURE) && m.tex[MATERIAL_TEX_EMISSION] != NO_TEXTURE)
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
    if (!PT_FEATURE_ENV || p->scene.env_width == 0u)
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

/* Shades the path in slot; true when it queued a shadow ray. */
PT_INLINE bool shade_path(constant RenderParams *p, const SceneView *scene, PATH_STATE_PARAMS uint slot)
{
    uint depth = path_depth[slot];
    if (depth == 0u)
        return false;
    uint k = sample_id[slot];
    float4 h = hit[slot];
    float4 dir4 = ray_direction[slot];
    float4 throughput4 = throughput[slot];
    float3 beta = xyz(throughput4);
    /* throughput.w: 1 + the absorbing dielectric the segment ran inside, 0 outside any (the
     * camera starts outside). Beer-Lambert over the segment just traced. */
    uint medium = as_uint(throughput4.w);
    if (PT_HAS_MATERIAL_FEATURE(ABSORPTION) && medium != 0u)
        beta *= dielectric_transmittance(xyz(scene->materials[medium - 1u].absorption), h.x);
    uint prim = as_uint(h.w);
    EnvMap env = env_map(p, scene);
    if (prim == HIT_NONE) {
        float3 sky = environment_seen(p, &env, xyz(dir4), dir4.w, depth);
        if (PT_FEATURE_ANALYTIC && p->scene.num_analytic > 0u)
            sky += suns_seen(p, scene->analytic_lights, xyz(dir4), dir4.w, depth);
        add_radiance(radiance, k, clamp_indirect(p, beta * sky, depth >= 3u));
        path_depth[slot] = 0u;
        return false;
    }
    Hit hh = {h.x, h.y, h.z, prim, PT_FEATURE_INSTANCES ? hit_instance[slot] : 0u};
    float time = PT_FEATURE_MOTION ? path_time[slot] : 0.0f;
    SurfaceHit surf = surface_at(scene, hh, time);
    Material m = scene->materials[surf.material];
    float3 wo = -xyz(dir4);
    float cos_o_geometric = dot(wo, surf.geometric_normal);
    bool front = cos_o_geometric > 0.0f;
    float3 ng = front ? surf.geometric_normal : -surf.geometric_normal;
    float3 ns = front ? surf.shading_normal : -surf.shading_normal;
    if (dot(ns, wo) <= 0.0f) /* interpolated normal facing away from the viewer: use the true one */
        ns = ng;

    float3 L = emission_seen(p, scene, m, hh, &surf, h.x, cos_o_geometric, dir4.w, depth);
    float3 gathered = clamp_indirect(p, beta * L, depth >= 3u);

    bool path_continues = depth < p->max_depth;
    bool queued = false;
    shadow_contribution[slot] = (float4)(0.0f);
    if (path_continues) {
        RngKey key = rng_path_key(window_pixel(p, active_pixels, k), window_sample(p, k), p->seed);
        uint bounce = depth - 1u;
        /* Emission, opacity and surface detail belong to the hit's material; the BSDF to the leaf
         * a mix resolves to. */
        bool is_mix = PT_HAS_MATERIAL_FEATURE(MIX) && m.type == MATERIAL_MIX;
        uint leaf_index = is_mix
                              ? material_resolve_mix(scene, surf.material, surf.uv,
                                                     surf.object_position,
                                                     rng_bounce(key, bounce, DIM_MIX))
                              : surf.material;
        Material leaf = is_mix ? scene->materials[leaf_index] : m;
        /* Textures are looked up in object space, the rest is world space (surface.cl). */
        Bsdf bsdf = bsdf_at(scene, leaf, surf.uv, surf.object_position);
        /* Normal and bump maps and anisotropy need the uv tangent frame (surface_detail.cl); plain
         * materials keep the cheap one. */
        Frame frame = surface_needs_tangents(m, leaf)
                          ? surface_detail_frame(scene, prim, surf, m, wo, front, ng)
                          : frame_from_normal(ns);
        float3 wo_local = frame_to_local(frame, wo);

        /* Next-event estimation for every non-delta lobe. */
        if (!bsdf_is_delta(&bsdf) && p->scene.num_emissive > 0u && !(p->flags & RENDER_NO_NEE)) {
            LightSample ls = light_sample(scene, &env, p->scene.num_emissive, surf.position, time,
                                          rng_bounce_bits(key, bounce, DIM_LIGHT_PICK),
                                          rng_bounce(key, bounce, DIM_LIGHT_COIN),
                                          rng_bounce_bits(key, bounce, DIM_ENV_PICK),
                                          rng_bounce(key, bounce, DIM_ENV_COIN),
                                          rng_bounce(key, bounce, DIM_LIGHT_U),
                                          rng_bounce(key, bounce, DIM_LIGHT_V));
            float3 wi = ls.direction;
            float3 wi_local = frame_to_local(frame, wi);
            float bsdf_pdf;
            float3 f_cos = bsdf_eval(&bsdf, wo_local, wi_local, front, &bsdf_pdf);
            /* The light must lie on the side of the true surface that the shading frame puts it
             * on (reflection above, transmission below): shading normals never leak light. */
            bool same_side = (dot(wi, ng) > 0.0f) == (wi_local.z > 0.0f);
            if (ls.pdf_w > 0.0f && max3(f_cos) > 0.0f && same_side) {
                /* A delta light cannot be hit by the BSDF's rays: no MIS. */
                float weight = ls.delta ? 1.0f : mis_power(ls.pdf_w, bsdf_pdf);
                float3 contribution = beta * f_cos * ls.radiance * (weight / ls.pdf_w);
                /* A light seen from inside an absorbing medium (rare: a lamp inside glass). */
                if (PT_HAS_MATERIAL_FEATURE(ABSORPTION) && medium != 0u && wi_local.z > 0.0f)
                    contribution *= dielectric_transmittance(
                        xyz(scene->materials[medium - 1u].absorption),
                        ls.at_infinity ? INFINITY : length(ls.position - surf.position));
                float3 origin = offset_ray_origin(surf.position, surf.geometric_normal, wi);
                float dist = INFINITY;
                float3 to_target = wi;
                /* The ray ends at the light point moved off the light by the same robust offset,
                 * toward the shaded point: it reaches everything in front of the light, however
                 * close, and never the light's own triangle (the test is half-open, t < tmax). */
                if (ls.delta && !ls.at_infinity) {
                    /* A point or spot light has no surface: the ray ends exactly at it. */
                    dist = length(ls.position - origin);
                    to_target = (ls.position - origin) / dist;
                } else if (!ls.at_infinity) {
                    float3 target = offset_ray_origin(ls.position, ls.normal, origin - ls.position);
                    dist = length(target - origin);
                    to_target = (target - origin) / dist;
                }
                shadow_origin[slot] = (float4)(origin, dist);
                shadow_direction[slot] = (float4)(to_target, as_float(bounce));
                shadow_contribution[slot] =
                    (float4)(clamp_indirect(p, contribution, depth >= 2u), 1.0f);
                queued = true;
            }
        }

        BsdfSample bs = bsdf_sample(&bsdf, wo_local, front, rng_bounce(key, bounce, DIM_BSDF_U),
                                    rng_bounce(key, bounce, DIM_BSDF_V),
                                    rng_bounce(key, bounce, DIM_BSDF_LOBE));
        float3 wi = frame_to_world(frame, bs.wi);
        beta *= bs.weight;
        /* A sample on the other side of the true surface than its lobe says (possible with
         * shading normals) is lost, never counted on the wrong side. */
        bool reflects = (bs.flags & BSDF_REFLECTION) != 0u;
        if (bs.flags == 0u || (dot(wi, ng) > 0.0f) != reflects)
            path_continues = false;
        /* Russian roulette from the third vertex on, driven by the throughput. */
        if (path_continues && depth >= 3u) {
            float q = fmin(max3(beta), 0.95f);
            if (rng_bounce(key, bounce, DIM_ROULETTE) >= q)
                path_continues = false;
            else
                beta /= q;
        }
        if (!(max3(beta) > 0.0f))
            path_continues = false;
        if (path_continues) {
            ray_origin[slot] = (float4)(offset_ray_origin(surf.position, surf.geometric_normal, wi), 0.0f);
            ray_direction[slot] = (float4)(wi, bs.pdf_w);
            /* Refraction into a dielectric that absorbs starts a segment inside it; refraction out
             * of one (wo inside, !front) ends it. Reflections keep the medium. */
            if (PT_HAS_MATERIAL_FEATURE(ABSORPTION) && (bs.flags & BSDF_TRANSMISSION))
                medium = front && max3(xyz(leaf.absorption)) > 0.0f ? leaf_index + 1u : 0u;
            throughput[slot] = (float4)(beta, as_float(medium));
        }
    }
    add_radiance(radiance, k, gathered);
    path_depth[slot] = path_continues ? depth + 1u : 0u;
    return queued;
}

/* With shadow_queue != 0 (RENDER_SHADOW_QUEUE), the slots that queued a shadow ray are appended to
 * shadow_queue[] (one global atomic per work-group, on shadow_count[0]) so that intersect_shadow
 * runs over those only; otherwise intersect_shadow checks every active slot's flag. */
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
