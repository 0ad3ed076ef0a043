/* SPDX-License-Identifier: MIT */
/* film_variance: per pixel, from the film's sums and its second moments (accumulate_film_moments),
 * the variance of the pixel's mean per channel and adaptive sampling's relative error. One work
 * item per pixel. The sum of squared deviations is computed exactly in 128-bit integers, so a
 * pixel whose samples are all equal has variance 0, and the result does not depend on the order in
 * which samples arrived (nor does anything else: the inputs are exact sums).
 * Reads: film (FILM_WORDS per pixel), moments (MOMENT_WORDS per pixel). Writes: variance[pixel] =
 * (variance of the mean of r, g, b; w: relative error), INFINITY for w below 2 samples.
 * The 128-bit helpers u128_mul and u128_add come from accumulate_film.cl (before this file). */

/* The relative error: sqrt(Var of the mean's luminance) / max(mean luminance, ADAPTIVE_EPSILON).
 * The variance is the luminance-weighted sum of the channels' (no cross-moments are kept): for
 * grey noise it bounds the luminance's from above, and it counts coloured noise too.
 * ADAPTIVE_EPSILON: a pixel darker than a thousandth of display white is judged by its absolute
 * error against T x 1e-3, which for any T <= 0.1 is a third of the first 8-bit sRGB step above
 * black (1 / 255 / 12.92 = 3.0e-4) or less: invisible noise in black areas does not keep them
 * sampling, visible noise does. */
#define ADAPTIVE_EPSILON 1e-3f
#define LUMINANCE_WEIGHTS ((float3)(0.2126f, 0.7152f, 0.0722f)) /* Rec. 709 */

inline ulong2 u128_sub(ulong2 a, ulong2 b)
{
    return (ulong2)(a.x - b.x, a.y - b.y - (a.x < b.x ? 1ul : 0ul));
}

inline float u128_to_float(ulong2 a) { return (float)a.y * 0x1p64f + (float)a.x; }

/* The variance of the mean of n fixed-point samples with sum s and sum of squares s2, in radiance
 * units. With m = floor(s / n) and r = s - n m: sum (x - m)^2 = s2 - 2 m s + n m^2 exactly (it is
 * >= 0 and no intermediate exceeds 2^128), and sum (x - mean)^2 = that - r^2 / n. */
inline float variance_of_mean(ulong s, ulong2 s2, ulong n)
{
    ulong m = s / n, r = s - m * n;
    ulong2 two_ms = u128_mul(m, s);
    two_ms = u128_add(two_ms, two_ms);
    ulong2 deviations = u128_sub(u128_add(s2, u128_mul(m * n, m)), two_ms);
    float centred = u128_to_float(deviations) - (float)r * ((float)r / (float)n);
    float sample_variance = fmax(centred, 0.0f) / (float)(n - 1ul);
    return sample_variance / (float)n * 0x1p-48f; /* 2^-48: the squares' step */
}

kernel void film_variance(uint num_pixels, const global ulong4 *film, const global ulong2 *moments,
                          global float4 *variance)
{
    uint pixel = get_global_id(0);
    if (pixel >= num_pixels)
        return;
    ulong4 sums = film[pixel];
    ulong n = sums.w;
    if (n < 2ul) {
        variance[pixel] = (float4)(0.0f, 0.0f, 0.0f, INFINITY);
        return;
    }
    float3 var = (float3)(variance_of_mean(sums.x, moments[3 * pixel], n),
                          variance_of_mean(sums.y, moments[3 * pixel + 1], n),
                          variance_of_mean(sums.z, moments[3 * pixel + 2], n));
    float3 mean = convert_float3(sums.xyz) / (float)n * (1.0f / (float)(1u << FILM_FRACTION_BITS));
    float error = sqrt(dot(LUMINANCE_WEIGHTS, var)) / fmax(dot(LUMINANCE_WEIGHTS, mean), ADAPTIVE_EPSILON);
    variance[pixel] = (float4)(var, error);
}
