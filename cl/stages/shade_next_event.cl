/* SPDX-License-Identifier: MIT */
/* shade_next_event.cl: next-event estimation at a path vertex (shade_path, shade_surface.cl): one
 * light sample weighed against BSDF sampling, and the shadow ray that intersect_shadow resolves. */

/* A next-event shadow ray as shade_path queues it (queue_shadow_ray): intersect_shadow adds
 * contribution to the sample's radiance unless something lies along direction before tmax. */
typedef struct {
    float3 origin, direction, contribution;
    float tmax;
    uint medium; /* the slot of the medium it starts in (intersect_shadow tracks it with media) */
    uint bounce; /* the bounce that queued it (its cut-out and media streams); set on queuing */
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

/* Queues a shadow ray (bounce: for its cut-out and media streams): stored in slot's shadow lanes
 * for intersect_shadow, or with held (the kernel shade_surface, which traces it at once) handed back
 * in *held instead; true when queued. */
PT_INLINE bool queue_shadow_ray(PATH_STATE_PARAMS uint slot, ShadowRay ray, uint bounce,
                                ShadowRay *held)
{
    if (!ray.queued)
        return false;
    if (held) {
        ray.bounce = bounce;
        *held = ray;
        return true;
    }
    shadow_origin[slot] = shadow_origin_pack(ray.origin, ray.tmax);
    shadow_direction[slot] = shadow_direction_pack(ray.direction, bounce, ray.medium);
    shadow_contribution[slot] = shadow_contribution_pack(ray.contribution, true);
    return true;
}
