/* SPDX-License-Identifier: MIT */
/* render_aov: first-hit arbitrary output variables (albedo with map_Kd, shading normal, depth),
 * averaged over `spp` jittered samples per pixel. Reads the scene buffers; writes film[pixel]
 * (rgb, w = 1). Misses give 0. Not part of the wavefront: a single pass for denoisers and
 * compositors. */

kernel void render_aov(constant RenderParams *p, SCENE_PARAMS uint spp, global float4 *film)
{
    SceneView scene = SCENE_VIEW;
    uint pixel = get_global_id(0);
    if (pixel >= p->width * p->height)
        return;
    float3 sum = (float3)(0.0f);
    for (uint s = 0; s < spp; s++) {
        float3 origin, dir;
        camera_sample(p, pixel, p->sample_index + s, &origin, &dir);
        /* The AOVs are of the shutter's opening instant. */
        Hit hit = scene_closest(&scene, p->num_bvh_prims, origin, dir, 0.0f, INFINITY, 0.0f);
        if (hit.prim == HIT_NONE)
            continue;
        SurfaceHit surf = surface_at(&scene, hit, 0.0f);
        if (p->aov == AOV_NORMAL) {
            sum += surf.shading_normal;
        } else if (p->aov == AOV_DEPTH) {
            sum += (float3)(hit.t);
        } else {
            /* A mix shows its first leaf's colour: the AOV is deterministic. */
            Material m = materials[material_resolve_mix(&scene, surf.material, surf.uv,
                                                        surf.object_position, 1.0f)];
            Bsdf bsdf = bsdf_at(&scene, m, surf.uv, surf.object_position);
            sum += bsdf_albedo(&bsdf);
        }
    }
    film[pixel] = (float4)(sum / (float)max(spp, 1u), 1.0f);
}
