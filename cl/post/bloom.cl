/* SPDX-License-Identifier: MIT */
/* bloom.cl: the glow of --bloom on the linear film (host: host/render/bloom.c), a separable
 * Gaussian of the image's bright part added back in place of that part:
 *
 *   bloom_bright_part        bright = bright(rgb)
 *   bloom_blur_rows          blurred = rows(bright)
 *   bloom_blur_columns_mix   rgb += s * (columns(blurred) - bright(rgb))   (in place)
 *
 * bright(c) = c * max(L - T, 0) / L, L the Rec.709 luminance and T the threshold: the share of the
 * pixel's light above T, hue kept, zero at and below T, continuous at T (and zero for a
 * non-finite pixel). The image is extended
 * by mirror symmetry (period 2n: ... 1 0 | 0 1 .. n-1 | n-1 n-2 ...), which makes each 1-D blur a
 * symmetric matrix whose rows, hence also columns, sum to the weights' sum 1: the blur moves light
 * without adding or losing any, also at the borders, and the sum over the image is unchanged
 * (up to float rounding). weights[0..radius] is one half of the normalised kernel (weights[|k|]
 * for tap k). Pixels are RGB float triples, row 0 at the top; one work item per pixel, 1-D. The
 * blurs index directly where the kernel's reach stays inside the image and mirror only near the
 * borders: the modulo in every tap tripled PoCL's time. */

inline float3 bloom_bright(float3 c, float threshold)
{
    float luminance = 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
    /* a non-finite pixel would spread NaN over the kernel's reach: it adds no glow */
    return luminance > threshold && isfinite(luminance) ? c * ((luminance - threshold) / luminance)
                                                        : (float3)(0.0f);
}

/* The index i of a row or column of n pixels, mirrored into [0, n). */
inline int bloom_mirror(int i, int n)
{
    int period = 2 * n, m = i % period;
    if (m < 0)
        m += period;
    return m < n ? m : period - 1 - m;
}

kernel void bloom_bright_part(global const float *rgb, global float *bright, int pixels,
                              float threshold)
{
    int i = (int)get_global_id(0);
    if (i < pixels)
        vstore3(bloom_bright(vload3(i, rgb), threshold), i, bright);
}

/* sum over |k| <= radius of weights[|k|] * values[at + k * stride], the taps at position + k of a
 * line of n pixels mirrored. */
inline float3 bloom_blur_line(global const float *values, global const float *weights, int radius,
                              int at, int position, int stride, int n)
{
    float3 sum = weights[0] * vload3(at, values);
    if (position >= radius && position + radius < n) {
        for (int k = 1; k <= radius; k++)
            sum += weights[k] * (vload3(at - k * stride, values) + vload3(at + k * stride, values));
    } else {
        int start = at - position * stride;
        for (int k = 1; k <= radius; k++)
            sum += weights[k] * (vload3(start + bloom_mirror(position - k, n) * stride, values) +
                                 vload3(start + bloom_mirror(position + k, n) * stride, values));
    }
    return sum;
}

kernel void bloom_blur_rows(global const float *bright, global float *blurred,
                            global const float *weights, int radius, int width, int height)
{
    int i = (int)get_global_id(0);
    if (i < width * height)
        vstore3(bloom_blur_line(bright, weights, radius, i, i % width, 1, width), i, blurred);
}

kernel void bloom_blur_columns_mix(global float *rgb, global const float *blurred,
                                   global const float *weights, int radius, int width, int height,
                                   float threshold, float strength)
{
    int i = (int)get_global_id(0);
    if (i >= width * height)
        return;
    float3 sum = bloom_blur_line(blurred, weights, radius, i, i / width, width, height);
    float3 c = vload3(i, rgb);
    vstore3(c + strength * (sum - bloom_bright(c, threshold)), i, rgb);
}
