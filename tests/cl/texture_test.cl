/* SPDX-License-Identifier: MIT */
/* sample_texture_at_uvs: texture_sample (cl/material/texture.cl) of texture `index` at each uv, so the host
 * can compare with its own bilinear, sRGB-decoded reference. */
kernel void sample_texture_at_uvs(const global uint *texels, const global TextureInfo *textures,
                                  const global float *srgb_decode,
                                  uint index, const global float2 *uvs, global float4 *out, uint n)
{
    SceneView scene = {0};
    scene.texels = texels;
    scene.textures = textures;
    scene.srgb_decode = srgb_decode;
    uint i = get_global_id(0);
    if (i < n)
        out[i] = texture_sample(&scene, index, uvs[i]);
}
