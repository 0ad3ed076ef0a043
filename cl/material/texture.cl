/* SPDX-License-Identifier: MIT */
/* texture.cl: texture lookups on the packed texel buffer (host/scene/texture.h). Bilinear filtering,
 * repeat wrapping; 8-bit texels are sRGB-decoded before filtering. OBJ's v = 0 is the image's
 * bottom row, and row 0 of the stored image is its top. */

inline float srgb_to_linear(float c)
{
    return c <= 0.04045f ? c * (1.0f / 12.92f) : pow((c + 0.055f) * (1.0f / 1.055f), 2.4f);
}

inline float4 texel_fetch(const global uint *texels, TextureInfo info, int x, int y)
{
    uint index = (uint)y * info.width + (uint)x;
    if (info.format == TEXTURE_RGBA32F) {
        const global uint *p = texels + info.offset + 4u * index;
        return (float4)(as_float(p[0]), as_float(p[1]), as_float(p[2]), as_float(p[3]));
    }
    uint packed = texels[info.offset + index];
    float4 c = (float4)((float)(packed & 0xffu), (float)((packed >> 8) & 0xffu),
                        (float)((packed >> 16) & 0xffu), (float)(packed >> 24)) * (1.0f / 255.0f);
    return (float4)(srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z), c.w);
}

inline int wrap_coord(int i, int n)
{
    int r = i % n;
    return r < 0 ? r + n : r;
}

float4 texture_sample(const SceneView *scene, uint index, float2 uv)
{
    const global uint *texels = scene->texels;
    TextureInfo info = scene->textures[index];
    /* Texel centres sit at half-integer coordinates; flip v so v = 0 is the bottom row. The
     * fmin/fmax keep a NaN or infinite uv (and rounding of the fraction up to 1) from reaching the
     * float-to-int conversions below, whose out-of-range result is undefined. */
    float w = (float)info.width, h = (float)info.height;
    float x = fmin(fmax((uv.x - floor(uv.x)) * w - 0.5f, -0.5f), w - 0.5f);
    float y = fmin(fmax((1.0f - (uv.y - floor(uv.y))) * h - 0.5f, -0.5f), h - 0.5f);
    float fx = floor(x), fy = floor(y);
    float ax = x - fx, ay = y - fy;
    int x0 = wrap_coord((int)fx, (int)info.width), x1 = wrap_coord((int)fx + 1, (int)info.width);
    int y0 = wrap_coord((int)fy, (int)info.height), y1 = wrap_coord((int)fy + 1, (int)info.height);
    float4 top = mix(texel_fetch(texels, info, x0, y0), texel_fetch(texels, info, x1, y0), ax);
    float4 bottom = mix(texel_fetch(texels, info, x0, y1), texel_fetch(texels, info, x1, y1), ax);
    return mix(top, bottom, ay);
}
