/* SPDX-License-Identifier: MIT */
/* sobol.cl: the first two dimensions of the Sobol sequence, Owen-scrambled by a hash, with the
 * sample index shuffled by another (Burley 2020, "Practical Hash-based Owen Scrambling", JCGT
 * 9(4); Cycles' Sobol-Burley). rng.cl pads them: every pair of dimensions (a "tuple") is this 2D
 * point set under its own scramble and shuffle, so a tuple's two numbers are stratified together
 * and tuples are independent of each other. Two dimensions need no table: dimension 0 is the
 * radical inverse and dimension 1's generator matrix is Pascal's triangle mod 2, both a few shifts.
 *
 * Why the shuffle keeps prefixes stratified: it is a nested scramble of the index that changes
 * bit q only as a function of the bits above q, so the indices 0 .. 2^k - 1 (high bits zero) go to
 * c 2^k .. c 2^k + 2^k - 1 for one c: an aligned block of the sequence, which for these two
 * dimensions is a (0, k, 2)-net, and Owen scrambling keeps nets nets. Any count n is a sum of
 * such blocks (its binary digits), so every prefix is a union of nets (tests/test_rng.c checks
 * the nets). */

/* x with its 32 bits in reverse order (OpenCL C 1.2 has no bit-reverse built-in). */
inline uint reverse_bits(uint x)
{
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

/* The index that sample `reversed_sample` (the sample index bit-reversed) of a tuple scrambled
 * by `seed` takes in the Sobol sequence (the shuffle, see the top). */
inline uint sobol_shuffled_index(uint reversed_sample, uint seed)
{
    return reverse_bits(owen_scramble_reversed(reversed_sample, seed ^ 0xbff95bfeu));
}

/* 32 bits of component `component` (0 or 1) of Sobol point `index`, Owen-scrambled by `seed`
 * (each component by its own). */
inline uint sobol_owen_bits(uint index, uint component, uint seed)
{
    uint reversed = component ? sobol_dim1_reversed(index) : index; /* dim 0: reverse(reverse(i)) */
    return reverse_bits(owen_scramble_reversed(reversed, seed ^ (component ? 0x94964d4eu : 0xe0aaaf76u)));
}
