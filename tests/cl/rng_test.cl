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
