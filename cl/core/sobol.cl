/* SPDX-License-Identifier: MIT */
/* sobol.cl: the first four dimensions of the Sobol sequence, Owen-scrambled by a hash, with the
 * sample index shuffled by another (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT
 * 9(4); Cycles' Sobol-Burley). rng.cl pads them: every four dimensions (a "tuple") are this 4D
 * point set under their own scramble and shuffle, so a tuple's numbers are stratified together
 * and tuples are independent of each other. Dimensions 0 and 1 need no table (0 is the radical
 * inverse, 1's generator matrix is Pascal's triangle mod 2: a few shifts each) and form a
 * (0, 2)-sequence: what is drawn in pairs (light u, v; BSDF u, v; jitter) takes them; 2 and 3
 * (Joe & Kuo's direction numbers, 2 x 32 words) go to the numbers drawn with a pair (the light
 * pick with the point on the light, the lobe with the BSDF direction).
 *
 * Why the shuffle keeps prefixes stratified: it is a nested scramble of the index that changes
 * bit q only as a function of the bits above q, so the indices 0 .. 2^k - 1 (high bits zero) go to
 * c 2^k .. c 2^k + 2^k - 1 for one c: an aligned block of the sequence, which for these two
 * dimensions is a (0, k, 2)-net, and Owen scrambling keeps nets nets. Any count n is a sum of
 * such blocks (its binary digits), so every prefix is a union of nets (tests/test_rng.c checks
 * the nets). */

/* x with its 32 bits in reverse order (OpenCL C 1.2 has no bit-reverse built-in). NVIDIA's
 * compiler does not make the swaps below its bit-reverse instruction, and a Sobol tuple reverses
 * five words: with the instruction spelled out, shading took 6-12% less time on an H100
 * (bench/README.md "Where the GPU's time goes"). */
inline uint reverse_bits(uint x)
{
#ifdef PT_VENDOR_NVIDIA
    uint reversed;
    asm("brev.b32 %0, %1;" : "=r"(reversed) : "r"(x));
    return reversed;
#endif
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return rotate(x, 16u);
}

/* A nested uniform scramble of a bit-reversed 32-bit fraction (Laine & Karras 2011, with the
 * constants of Burley 2020 / Vegdahl): every step changes a bit only as a function of the bits
 * below it, i.e. of the more significant digits of the fraction, which is Owen's scrambling. */
inline uint owen_scramble_reversed(uint x, uint seed)
{
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

/* Dimension 1 of the Sobol sequence (Joe & Kuo's second: polynomial x + 1, direction numbers
 * v_k = v_(k-1) ^ (v_(k-1) >> 1)), bit-reversed, of index i: bit j of the result is the parity of
 * the index bits k whose binary digits include j's (Lucas: C(k, j) odd), a superset sum. */
inline uint sobol_dim1_reversed(uint i)
{
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0f0f0f0fu;
    i ^= (i >> 8) & 0x00ff00ffu;
    i ^= i >> 16;
    return i;
}

/* Dimensions 2 and 3 (Joe & Kuo 2008, new-joe-kuo-6.21201, their dimensions 3 and 4), direction
 * number k bit-reversed: the reversed point is the XOR of those of the index's set bits. */
constant uint sobol_directions_reversed[2][32] = {
    {0x00000001u, 0x00000003u, 0x00000006u, 0x00000009u, 0x00000017u, 0x0000003au,
     0x00000071u, 0x000000a3u, 0x00000116u, 0x00000339u, 0x00000677u, 0x000009aau,
     0x00001601u, 0x00003903u, 0x00007706u, 0x0000aa09u, 0x00010117u, 0x0003033au,
     0x00060671u, 0x000909a3u, 0x00171616u, 0x003a3939u, 0x00717777u, 0x00a3aaaau,
     0x01170001u, 0x033a0003u, 0x06710006u, 0x09a30009u, 0x16160017u, 0x3939003au,
     0x77770071u, 0xaaaa00a3u},
    {0x00000001u, 0x00000003u, 0x00000004u, 0x0000000au, 0x0000001fu, 0x0000002eu,
     0x00000045u, 0x000000c9u, 0x0000011bu, 0x000002a4u, 0x0000079au, 0x00000b67u,
     0x0000101eu, 0x0000302du, 0x00004041u, 0x0000a0c3u, 0x0001f104u, 0x0002e28au,
     0x000457dfu, 0x000c9baeu, 0x0011a105u, 0x002a7289u, 0x0079e7dbu, 0x00b6dba4u,
     0x0100011au, 0x030002a7u, 0x0400079eu, 0x0a000b6du, 0x1f001001u, 0x2e003003u,
     0x45004004u, 0xc900a00au}
};

/* The index that sample `reversed_sample` (the sample index bit-reversed) of a tuple scrambled
 * by `seed` takes in the Sobol sequence (the shuffle, see the top). */
inline uint sobol_shuffled_index(uint reversed_sample, uint seed)
{
    return reverse_bits(owen_scramble_reversed(reversed_sample, seed ^ 0xbff95bfeu));
}

/* Dimensions 2 and 3 of Sobol point `index` mod 2^16, bit-reversed (x: 2, y: 3): branch-free, so
 * work items stay in step. The bits above 16 only XOR a constant into a block of up to 2^16
 * samples (a digital shift, which the Owen scramble absorbs: every aligned block keeps its net),
 * so leaving them out costs nothing below 65536 spp and halves the loop; beyond, these two
 * dimensions repeat their set of values every 2^16 samples, paired with other values of 0 and 1. */
inline uint2 sobol_dims23_reversed(uint index)
{
    uint2 r = (uint2)(0u);
    for (uint k = 0; k < 16u; k++) {
        uint take = 0u - ((index >> k) & 1u);
        r.x ^= sobol_directions_reversed[0][k] & take;
        r.y ^= sobol_directions_reversed[1][k] & take;
    }
    return r;
}

/* The Owen scramble of component `component` (0 .. 3) of a tuple whose bit-reversed value is
 * `reversed`, as 32 bits of a fraction: each component by its own seed. */
inline uint sobol_owen_finish(uint reversed, uint component, uint seed)
{
    uint salt = component == 0u ? 0xe0aaaf76u : component == 1u ? 0x94964d4eu
              : component == 2u ? 0x6d2f3c1bu : 0x2c8e4a77u;
    return reverse_bits(owen_scramble_reversed(reversed, seed ^ salt));
}

/* 32 bits of component `component` (0 .. 3) of Sobol point `index`, Owen-scrambled by `seed`. */
inline uint sobol_owen_bits(uint index, uint component, uint seed)
{
    uint reversed = component == 0u ? index /* dim 0: reverse(reverse(i)) */
                  : component == 1u ? sobol_dim1_reversed(index)
                  : component == 2u ? sobol_dims23_reversed(index).x
                                    : sobol_dims23_reversed(index).y;
    return sobol_owen_finish(reversed, component, seed);
}
