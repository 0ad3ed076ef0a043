/* SPDX-License-Identifier: MIT */
/* eval_texture_at_points: texture_eval (cl/material/texture.cl) of texture `index` at each (uv,
 * position), so the host can compare procedural noise with its own reference. */
kernel void eval_texture_at_points(const global uint *texels, const global TextureInfo *textures,
                                   const global float *srgb_decode,
                                   uint index, const global float4 *points, global float4 *out,
                                   uint n)
{
    SceneView scene = {0};
    scene.texels = texels;
    scene.textures = textures;
    scene.srgb_decode = srgb_decode;
    uint i = get_global_id(0);
    if (i < n)
        out[i] = texture_eval(&scene, index, (float2)(points[i].w, 0.0f), xyz(points[i]));
}
