/* SPDX-License-Identifier: MIT */
/* rng_test.cl: kernels for tests/test_rng.c. */

/* The start of the random sequence of pixel i % num_pixels, sample sample_base + i / num_pixels:
 * dimensions 0 and 1 (24 bits each, as rng_uniform returns them) and the top 16 bits of dimension
 * 2, packed into 64 bits. Two samples with the same key get the same value. */
kernel void rng_test_sequence_starts(uint num_pixels, uint sample_base, uint seed, uint count,
                                     global ulong *starts)
{
    uint i = get_global_id(0);
    if (i >= count)
        return;
    uint pixel = i % num_pixels, sample = sample_base + i / num_pixels;
    ulong d0 = (ulong)(rng_uniform(pixel, sample, 0u, seed) * 16777216.0f);
    ulong d1 = (ulong)(rng_uniform(pixel, sample, 1u, seed) * 16777216.0f);
    ulong d2 = (ulong)(rng_uniform(pixel, sample, 2u, seed) * 65536.0f);
    starts[i] = d0 << 40 | d1 << 16 | d2;
}

/* Dimensions d0 and d1 of sample i / num_pixels of pixel i % num_pixels, as 8-bit bins each
 * (bins[i] = bin(d0) * 256 + bin(d1)), for tests/test_rng.c's uniformity and independence checks. */
kernel void rng_test_dimension_pair(uint num_pixels, uint seed, uint d0, uint d1, uint count,
                                    global ushort *bins)
{
    uint i = get_global_id(0);
    if (i >= count)
        return;
    uint pixel = i % num_pixels, sample = i / num_pixels;
    uint b0 = min((uint)(rng_uniform(pixel, sample, d0, seed) * 256.0f), 255u);
    uint b1 = min((uint)(rng_uniform(pixel, sample, d1, seed) * 256.0f), 255u);
    bins[i] = (ushort)(b0 * 256u + b1);
}

/* The pair (dimensions 4 tuple, 4 tuple + 1: Sobol dimensions 0 and 1) of tuple `tuple` of the
 * Sobol sampler for samples first .. first + count - 1 of pixel `pixel`, through the pair call
 * (use_pair 1), the tuple call (2) or one dimension at a time (0). */
kernel void rng_test_sobol_tuple(uint pixel, uint seed, uint tuple, uint first, uint count,
                                 uint use_pair, global uint2 *points)
{
    uint i = get_global_id(0);
    if (i >= count)
        return;
    RngKey key = rng_sampler_key(pixel, first + i, seed, RNG_SOBOL);
    uint d = 4u * tuple;
    points[i] = use_pair == 1u ? rng_bits2(key, d)
                : use_pair == 2u ? rng_bits4(key, d).xy
                                 : (uint2)(rng_bits(key, d), rng_bits(key, d + 1u));
}
