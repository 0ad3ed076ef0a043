/* SPDX-License-Identifier: MIT */
/* render_aov: first-hit arbitrary output variables (albedo with map_Kd, shading normal, depth),
 * averaged over `spp` jittered samples per pixel. Reads the scene buffers; writes film[pixel]
 * (rgb, w = 1). Misses give 0. Not part of the wavefront: a single pass for denoisers and
 * compositors. */

kernel void render_aov(constant RenderParams *p, const global TraversalNode *nodes,
                       const global TraversalPrim *bvh_tris, const global float4 *positions,
                       const global float4 *normals, const global float2 *uvs,
                       const global Triangle *triangles, const global uint *material_ids,
                       const global Material *materials, const global uint *texels,
                       const global TextureInfo *textures, uint spp, global float4 *film)
{
    uint pixel = get_global_id(0);
    if (pixel >= p->width * p->height)
        return;
    uint x = pixel % p->width, y = pixel / p->width;
    float3 sum = (float3)(0.0f);
    for (uint s = 0; s < spp; s++) {
        uint sample = p->sample_index + s;
        float2 jitter = (float2)(rng_uniform(pixel, sample, DIM_CAMERA_JITTER_X, p->seed),
                                 rng_uniform(pixel, sample, DIM_CAMERA_JITTER_Y, p->seed));
        float2 lens = (float2)(rng_uniform(pixel, sample, DIM_LENS_U, p->seed),
                               rng_uniform(pixel, sample, DIM_LENS_V, p->seed));
        float3 origin, dir;
        camera_ray(p, x, y, jitter, lens, &origin, &dir);
        Hit hit = trace_closest(nodes, bvh_tris, p->num_bvh_prims, origin, dir, 0.0f, INFINITY);
        if (hit.prim == HIT_NONE)
            continue;
        SurfaceHit surf = surface_at(hit, positions, normals, uvs, triangles, material_ids);
        if (p->aov == AOV_NORMAL) {
            sum += surf.shading_normal;
        } else if (p->aov == AOV_DEPTH) {
            sum += (float3)(hit.t);
        } else {
            Material m = materials[surf.material];
            float3 albedo = m.type == MATERIAL_MIRROR        ? xyz(m.ks)
                            : m.type == MATERIAL_DIELECTRIC ? xyz(m.tf)
                                                            : xyz(m.kd);
            if (m.map_kd != NO_TEXTURE)
                albedo *= xyz(texture_sample(texels, textures, m.map_kd, surf.uv));
            sum += albedo;
        }
    }
    film[pixel] = (float4)(sum / (float)max(spp, 1u), 1.0f);
}
