/* SPDX-License-Identifier: MIT */
/* shade_surface: one path vertex. Adds emission (MIS-weighted against light sampling), queues a
 * next-event shadow ray for non-delta materials, samples the BSDF for the next segment and applies
 * Russian roulette. depth = path_depth[slot] = segments traced so far (1 after the camera ray); paths
 * of different depths share a launch once slots are refilled.
 * Reads: hit, hit_instance (PT_FEATURE(INSTANCES)), path_time (PT_FEATURE(MOTION): where moving
 * instances and their emitters are), ray_*, throughput, path_depth, sample_id, scene. Writes:
 * radiance[sample_id], throughput, ray_* (next segment), path_depth (depth + 1, or 0 when the
 * path ends), and with shade_surface_split shadow_* (waits when queued). Positions, normals and
 * directions are world space; textures are looked up at the hit's object-space point (surface.cl).
 * The kernel shade_surface also traces the vertex's shadow ray (below); shade_surface_split leaves
 * it to intersect_shadow. Next: compaction. */

/* ---- shade_path's steps (the names of Cycles' integrator_shade_surface): the light it gathers is
 * shade_emission.cl's, its light connection shade_next_event.cl's, the vertex set-up it shares
 * with render_aov (shading_point, resolve_leaf, surface_bsdf) cl/material/shading_point.cl's; the
 * continuation, the media vertex and the pass through an interface are here ---- */

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
                                   RngKey key, uint bounce, uint depth, ShadowRay *held)
{
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
            queued = queue_shadow_ray(PATH_STATE_ARGS slot, ray, bounce, held);
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

/* Shades the path in slot; true when it queued a shadow ray: into the slot's shadow lanes, or
 * with held (a constant at every call site) into *held (queue_shadow_ray). */
PT_INLINE bool shade_path(constant RenderParams *p, const SceneView *scene,
                          PATH_STATE_PARAMS uint slot, ShadowRay *held)
{
    uint depth = path_depth[slot];
    if (depth == 0u)
        return false;
    uint k = sample_id[slot];
    float4 hit4 = hit[slot], direction = ray_direction[slot];
    float4 throughput4 = path_throughput(p, throughput, slot, depth);
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
        float3 origin = xyz(path_ray_origin(p, ray_origin, slot, depth)), emitted = (float3)(0.0f);
        float t_event;
        MediumRng rng = medium_rng(rng_bounce_bits(key, bounce, DIM_MEDIUM), 0x6d2b79f5u);
        float tmax = hit_prim(hit4) == HIT_NONE ? INFINITY : hit_t(hit4);
        uint event = medium_track(scene, medium_at_slot(scene, medium), origin, xyz(direction),
                                  tmax, &rng, &beta, &emitted, &t_event);
        add_radiance(radiance, k, clamp_indirect(p, emitted, depth >= 3u));
        if (event == MEDIUM_EVENT_SCATTER)
            return shade_medium_vertex(p, scene, &env, PATH_STATE_ARGS slot,
                                       origin + t_event * xyz(direction), xyz(direction), beta,
                                       eta_scale, state, time, key, bounce, depth, held);
        if (event == MEDIUM_EVENT_ABSORB) {
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
    if (path_continues) {
        RngKey key = path_rng_key(p, active_pixels, k);
        uint leaf_index = resolve_leaf(scene, m, &sp.surf, key, bounce);
        Material leaf = material_is_mix(m.type) ? scene->materials[leaf_index] : m;
        /* The media a mix's leaf bounds (a dielectric's absorption) are the leaf's. */
        Material tm = (leaf.flags & MATERIAL_FLAG_MEDIUM_INTERFACE) ? leaf : m;
        SurfaceBsdf sb = surface_bsdf(scene, &sp, h.prim, m, leaf);
        ShadowRay shadow =
            connect_light(p, scene, &env, &sp, &sb, tm, beta, medium, time, key, bounce, depth);
        queued = queue_shadow_ray(PATH_STATE_ARGS slot, shadow, bounce, held);
        path_continues = continue_path(p, PATH_STATE_ARGS slot, &sp, &sb, tm, beta, eta_scale,
                                       medium, crossings, key, bounce, depth);
    }
    add_radiance(radiance, k, gathered);
    path_depth[slot] = path_continues ? depth + 1u : 0u;
    return queued;
}

/* shade_surface: shades each active slot's vertex (shade_path) and traces the shadow ray it
 * queued at once, from registers (shadow_ray_occluded, intersect_shadow.cl): the shadow lanes are
 * neither written nor read, and no second launch, shadow queue or second read of the active list
 * runs per step. The additions to radiance[sample_id] come in the split stages' order (the
 * vertex's own light, then the shadow ray's), so the film's bits are theirs. What it costs: lanes
 * whose vertex queued no ray (specular, or the light behind) idle while the others trace, and the
 * traversal's registers join shading's. counters[COUNTER_SHADOW_RAYS] counts the shadow rays
 * (count_group_rays). Each way of shading is a program part of its own (CONNECT, SPLIT), so that
 * a first build compiles the shading code once: NVIDIA's compiler inlines all of it into every
 * kernel that shades. */
#if PT_PART(CONNECT)
kernel void shade_surface(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                          const global uint *active, uint n_active, global uint *counters)
{
    local uint group_rays[2];
    clear_group_rays(group_rays);
    SceneView scene = SCENE_VIEW;
    uint i = get_global_id(0);
    bool traced = false;
    if (i < n_active) {
        uint slot = active[i];
        ShadowRay ray;
        if (shade_path(p, &scene, PATH_STATE_ARGS slot, &ray)) {
            float time = PT_FEATURE(MOTION) ? path_time[slot] : 0.0f;
            uint k = sample_id[slot];
            float3 c = ray.contribution;
            if (!shadow_ray_occluded(p, &scene, active_pixels, k, ray.origin, ray.direction,
                                     ray.tmax, time, ray.medium, ray.bounce, false, &c))
                radiance[k] += (float4)(c, 0.0f);
            traced = true;
        }
    }
    /* Every work item gets here: no early return above. */
    count_group_rays(group_rays, 0u, traced ? 1u : 0u, counters);
}
#endif

/* shade_surface_split: shading that stores each queued shadow ray in its slot's lanes for
 * intersect_shadow (RenderSettings.split_shadow: the wavefront before issue 41's tenth session,
 * kept to measure against). With shadow_queue != 0 (RENDER_SHADOW_QUEUE), the slots that queued a
 * shadow ray are appended to shadow_queue[] (one global atomic per work-group, on shadow_count[0])
 * so that intersect_shadow runs over those only; otherwise intersect_shadow checks every active
 * slot's flag. */
#if PT_PART(SPLIT)
kernel void shade_surface_split(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                          const global uint *active, uint n_active, global uint *shadow_queue,
                          global uint *shadow_count)
{
    local uint group_count, group_base;
    SceneView scene = SCENE_VIEW;
    uint i = get_global_id(0);
    uint slot = i < n_active ? active[i] : 0u;
    bool queued = i < n_active && shade_path(p, &scene, PATH_STATE_ARGS slot, 0);
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
