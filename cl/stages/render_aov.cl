/* SPDX-License-Identifier: MIT */
/* render_aov: the albedo, normal and depth AOVs of one pixel per work item, over samples
 * p->sample_index .. + spp - 1 of the beauty's own camera rays (camera_sample, camera_time and the
 * cut-out stream of intersect_closest: the camera ray's first hit is the beauty's). Not part of
 * the wavefront: a pass of its own after the render, reading only the scene, so it cannot change
 * the beauty's bits.
 *
 * Albedo and normal are those of the first non-delta hit, as denoisers (OIDN) expect: a smooth
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
        RngKey key = rng_path_key(pixel, sample, p->seed);
        for (uint bounce = 0u; bounce < max_segments; bounce++) {
            Hit hit = PT_FEATURE(CUTOUT)
                          ? trace_closest_through(&scene, 0u, origin, dir, 0.0f, INFINITY, time,
                                                  false, rng_bounce_bits(key, bounce, DIM_OPACITY))
                          : scene_closest(&scene, 0u, origin, dir, 0.0f, INFINITY, time);
            if (hit.prim == HIT_NONE)
                break;
            if (bounce == 0u) {
                depth_sum += hit.t;
                hits++;
            }
            SurfaceHit surf = surface_at(&scene, hit, time);
            Material m = scene.materials[surf.material];
            bool is_mix = PT_FEATURE(MIX) && m.type == MATERIAL_MIX;
            Material leaf = is_mix ? scene.materials[material_resolve_mix(
                                         &scene, surf.material, surf.uv, surf.object_position,
                                         rng_bounce(key, bounce, DIM_MIX))]
                                   : m;
            Bsdf bsdf = bsdf_at(&scene, leaf, surf.uv, surf.object_position);
            float3 wo = -dir;
            bool front = dot(wo, surf.geometric_normal) > 0.0f;
            float3 ng = front ? surf.geometric_normal : -surf.geometric_normal;
            float3 ns = front ? surf.shading_normal : -surf.shading_normal;
            if (dot(ns, wo) <= 0.0f)
                ns = ng;
            Frame frame = surface_needs_tangents(m, leaf)
                              ? surface_detail_frame(&scene, hit.prim, surf, m, wo, front, ng)
                              : frame_from_normal(ns);
            if (!bsdf_is_delta(&bsdf) || bounce + 1u == max_segments) {
                albedo_sum += bsdf_albedo(&bsdf);
                normal_sum += frame.n;
                break;
            }
            dir = frame_to_world(frame, aov_delta_direction(&bsdf, frame_to_local(frame, wo), front));
            origin = offset_ray_origin(surf.position, surf.geometric_normal, dir);
        }
    }
    float n = (float)max(spp, 1u);
    albedo[pixel] = (float4)(albedo_sum / n, hits ? depth_sum / (float)hits : 0.0f);
    normal[pixel] = (float4)(normal_sum / n, (float)hits / n);
}
