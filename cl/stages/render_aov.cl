/* SPDX-License-Identifier: MIT */
/* render_aov: the albedo, normal and depth AOVs of one pixel per work item, over samples
 * p->sample_index .. + spp - 1 of the beauty's own camera rays (camera_sample, camera_time and the
 * cut-out stream of intersect_closest: the camera ray's first hit is the beauty's). Not part of
 * the wavefront: a pass of its own after the render, reading only the scene, so it cannot change
 * the beauty's bits.
 *
 * Albedo and normal are those of the first non-delta hit, as denoisers (OIDN) expect (an emitter's
 * albedo is its emission's colour, aov_albedo): a smooth
 * mirror reflects the ray, smooth glass refracts it (reflects on total internal reflection), for
 * at most p->max_depth segments; the last hit's values stand when the walk runs out. The followed
 * surfaces' tint does not multiply the albedo (the wall seen in a mirror has the wall's colour).
 * A mix resolves to a leaf with the beauty's number for that vertex (DIM_MIX), so the mean over
 * the samples is the mix's expected albedo. The normal is the shading normal as shade_surface
 * uses it (normal and bump maps applied), turned toward the incoming ray, world space, averaged
 * and not renormalised. Depth is the camera ray's distance to its first hit, averaged over the
 * samples that hit. Misses add nothing (albedo and normal 0).
 * Writes albedo[pixel] (rgb; w: mean depth of the hits, 0 when none) and normal[pixel] (xyz; w:
 * the fraction of the samples that hit). */

/* The direction a delta surface sends the ray on (local frame, wo.z > 0): the mirror direction,
 * or for smooth glass the refracted one (the reflected one on total internal reflection). */
inline float3 aov_delta_direction(const Bsdf *b, float3 wo, bool front)
{
    float3 mirror = (float3)(-wo.x, -wo.y, wo.z);
    if (b->type != MATERIAL_DIELECTRIC)
        return mirror;
    float eta = dielectric_eta(b, front), cos_t;
    if (fresnel_dielectric(wo.z, eta, &cos_t) >= 1.0f)
        return mirror;
    return normalize((float3)(-wo.x / eta, -wo.y / eta, -cos_t));
}

/* The albedo a hit shows the denoiser: the BSDF's, except on an emitter seen from its front,
 * which shows its emission's colour scaled to a largest channel of 1. A lamp often has the albedo
 * of what it sits on (the Cornell box's light and ceiling are both 0.78 grey): with that guide
 * OIDN blurs the lamp's edge into the ceiling (relMSE 1.7x that of the colour-only filter at
 * 16 spp); with this one the guide has the edge the image has. */
inline float3 aov_albedo(const Bsdf *b, Material m, bool front)
{
    if (m.emission.w <= 0.0f || !front)
        return bsdf_albedo(b);
    float3 emission = xyz(m.emission);
    return emission / fmax(fmax(emission.x, emission.y), fmax(emission.z, 1e-30f));
}

/* The beauty's closest hit for the AOV walk's segment `bounce` (its cut-out stream too), past
 * `interface` surfaces (media's invisible boundaries: shared/medium.h), whose t counts along. */
inline Hit aov_trace(const SceneView *scene, float3 origin, float3 dir, float time, RngKey key,
                     uint bounce)
{
    float travelled = 0.0f;
    for (uint crossing = 0u;; crossing++) {
        Hit h = PT_FEATURE(CUTOUT)
                    ? trace_closest_through(scene, 0u, origin, dir, 0.0f, INFINITY, time, false,
                                            rng_bounce_bits(key, bounce, DIM_OPACITY))
                    : scene_closest(scene, 0u, origin, dir, 0.0f, INFINITY, time);
        if (!PT_FEATURE(MEDIA) || h.prim == HIT_NONE || crossing == 64u ||
            scene->materials[scene->material_ids[h.prim]].type != MATERIAL_INTERFACE) {
            h.t += travelled;
            return h;
        }
        SurfaceHit s = surface_at(scene, h, time);
        origin = offset_ray_origin(s.position, s.geometric_normal, dir);
        travelled += h.t;
    }
}

#if PT_PART(AOV)
kernel void render_aov(constant RenderParams *p, SCENE_PARAMS uint spp, global float4 *albedo,
                       global float4 *normal)
{
    SceneView scene = SCENE_VIEW;
    uint pixel = get_global_id(0);
    if (pixel >= p->width * p->height)
        return;
    float3 albedo_sum = (float3)(0.0f), normal_sum = (float3)(0.0f);
    float depth_sum = 0.0f;
    uint hits = 0u;
    uint max_segments = max(p->max_depth, 1u);
    for (uint s = 0; s < spp; s++) {
        uint sample = p->sample_index + s;
        float3 origin, dir;
        camera_sample(p, pixel, sample, &origin, &dir);
        float time = PT_FEATURE(MOTION) ? camera_time(p, pixel, sample) : 0.0f;
        RngKey key = render_rng_key(p, pixel, sample);
        for (uint bounce = 0u; bounce < max_segments; bounce++) {
            Hit hit = aov_trace(&scene, origin, dir, time, key, bounce);
            if (hit.prim == HIT_NONE)
                break;
            if (bounce == 0u) {
                depth_sum += hit.t;
                hits++;
            }
            ShadingPoint sp = shading_point(&scene, hit, time, dir);
            Material m = scene.materials[sp.surf.material];
            uint leaf_index = resolve_leaf(&scene, m, &sp.surf, key, bounce);
            Material leaf = material_is_mix(m.type) ? scene.materials[leaf_index] : m;
            SurfaceBsdf sb = surface_bsdf(&scene, &sp, hit.prim, m, leaf);
            if (!bsdf_is_delta(&sb.bsdf) || bounce + 1u == max_segments) {
                albedo_sum += aov_albedo(&sb.bsdf, m, sp.front);
                normal_sum += sb.frame.n;
                break;
            }
            dir = frame_to_world(sb.frame, aov_delta_direction(&sb.bsdf, sb.wo_local, sp.front));
            origin = offset_ray_origin(sp.surf.position, sp.surf.geometric_normal, dir);
        }
    }
    float n = (float)max(spp, 1u);
    albedo[pixel] = (float4)(albedo_sum / n, hits ? depth_sum / (float)hits : 0.0f);
    normal[pixel] = (float4)(normal_sum / n, (float)hits / n);
}
#endif

/* render_coverage: render_aov's first hits alone, for the beauty's alpha (coverage) and the depth
 * AOV: the same camera samples and the same writes to albedo.w and normal.w, the rest 0, without
 * the shading that makes render_aov as slow to compile as shade_surface (every render writes the
 * alpha; only --aov albedo,normal needs render_aov). In both parts a render starts with, so that
 * the alpha costs no second build. */
#if PT_PART(CORE) || PT_PART(MEGAKERNEL)
kernel void render_coverage(constant RenderParams *p, SCENE_PARAMS uint spp, global float4 *albedo,
                            global float4 *normal)
{
    SceneView scene = SCENE_VIEW;
    uint pixel = get_global_id(0);
    if (pixel >= p->width * p->height)
        return;
    float depth_sum = 0.0f;
    uint hits = 0u;
    for (uint s = 0; s < spp; s++) {
        uint sample = p->sample_index + s;
        float3 origin, dir;
        camera_sample(p, pixel, sample, &origin, &dir);
        float time = PT_FEATURE(MOTION) ? camera_time(p, pixel, sample) : 0.0f;
        Hit hit = aov_trace(&scene, origin, dir, time, render_rng_key(p, pixel, sample), 0u);
        if (hit.prim != HIT_NONE) {
            depth_sum += hit.t;
            hits++;
        }
    }
    float n = (float)max(spp, 1u);
    albedo[pixel] = (float4)(0.0f, 0.0f, 0.0f, hits ? depth_sum / (float)hits : 0.0f);
    normal[pixel] = (float4)(0.0f, 0.0f, 0.0f, (float)hits / n);
}
#endif
