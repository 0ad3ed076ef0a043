/* SPDX-License-Identifier: MIT */
/* report_sizes: writes sizeof of every shared struct, indexed by SIZEOF_*, so the host can check
 * that both compilers lay them out alike. */
kernel void report_sizes(global uint *out)
{
    out[SIZEOF_TRIANGLE] = sizeof(Triangle);
    out[SIZEOF_BVH_NODE] = sizeof(BvhNode);
    out[SIZEOF_BVH_TRIANGLE] = sizeof(BvhTriangle);
    out[SIZEOF_MATERIAL] = sizeof(Material);
    out[SIZEOF_TEXTURE_INFO] = sizeof(TextureInfo);
    out[SIZEOF_CAMERA] = sizeof(Camera);
    out[SIZEOF_RENDER_PARAMS] = sizeof(RenderParams);
    out[SIZEOF_LIGHT_ENTRY] = sizeof(LightEntry);
    out[SIZEOF_BVH_NODE4] = sizeof(BvhNode4);
    out[SIZEOF_TRIANGLE_PACK4] = sizeof(TrianglePack4);
    out[SIZEOF_BVH_NODE8] = sizeof(BvhNode8);
    out[SIZEOF_TRIANGLE_PACK8] = sizeof(TrianglePack8);
    out[SIZEOF_BVH_NODE_QUANTIZED] = sizeof(BvhNodeQuantized);
}
