/* SPDX-License-Identifier: MIT */
/* rng.cl: counter-based random numbers. Every number is a hash of (pixel, sample, dimension, seed),
 * so a render is a pure function of its settings whatever the device, pass split or path order. */

/* PCG-style 32-bit permutation (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"). A
 * bijection of uint: distinct inputs give distinct outputs. */
inline uint hash_pcg(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/* Per-(pixel, sample, seed) key. x: the pixel hashed with the seed, for both samplers. Independent
 * sampler (z = 0): y is the sample hashed with a differently derived seed, so for one seed the pair
 * (x, y) is injective: no two samples of a render share a random sequence however many there are.
 * (A 32-bit fold of the three gives about 2^23 pairs of samples with identical sequences at 512 x
 * 512 x 1024 spp.) Sobol sampler (z = 1, sobol.cl): y is the sample index bit-reversed, as the
 * shuffle takes it. Hashed once per kernel, then once per dimension (rng_bits). */
typedef uint3 RngKey;

#define RNG_INDEPENDENT 0u
#define RNG_SOBOL 1u

inline RngKey rng_sampler_key(uint pixel, uint sample, uint seed, uint sampler)
{
    uint seed_hash = hash_pcg(seed);
    uint pixel_hash = hash_pcg(pixel ^ seed_hash);
    if (sampler == RNG_SOBOL)
        return (RngKey)(pixel_hash, reverse_bits(sample), RNG_SOBOL);
    return (RngKey)(pixel_hash, hash_pcg(sample ^ hash_pcg(seed_hash ^ 0x9e3779b9u)), RNG_INDEPENDENT);
}

/* The independent sampler's key (tests, and numbers that must not be stratified). */
inline RngKey rng_path_key(uint pixel, uint sample, uint seed)
{
    return rng_sampler_key(pixel, sample, seed, RNG_INDEPENDENT);
}

/* 32 random bits of one dimension: one hash of both key words, the second rotated by the
 * dimension, plus the dimension times the golden ratio (so dimensions 32 apart differ too). Two
 * keys of the same pixel (or the same sample) never give the same word in any dimension, as their
 * difference is a nonzero rotation (or word); two keys differing in both words agree only in the
 * dimensions d where rotate(dy, d) == dx: a few words of a stream, never a stream. One hash per
 * dimension, not two: shade_surface draws 8 a bounce. */
inline uint rng_independent_bits(RngKey key, uint dimension)
{
    return hash_pcg(key.x ^ rotate(key.y, dimension & 31u) ^ (dimension * 0x9e3779b9u));
}

/* Sobol: dimensions 4t .. 4t + 3 are tuple t, the four Sobol dimensions under a scramble and a
 * shuffle hashed from (pixel, seed, t) (sobol.cl); numbering puts what is drawn together in one
 * tuple, pairs first (jitter x, y with lens u, v; light u, v with its pick; BSDF u, v with the
 * lobe). */
inline uint rng_sobol_tuple_seed(RngKey key, uint tuple) { return hash_pcg(key.x ^ (tuple * 0x9e3779b9u)); }

inline uint rng_sobol_bits(RngKey key, uint dimension)
{
    uint tuple_seed = rng_sobol_tuple_seed(key, dimension >> 2);
    return sobol_owen_bits(sobol_shuffled_index(key.y, tuple_seed), dimension & 3u, tuple_seed);
}

inline uint rng_bits(RngKey key, uint dimension)
{
    return key.z == RNG_SOBOL ? rng_sobol_bits(key, dimension) : rng_independent_bits(key, dimension);
}

/* Dimensions `first` and `first` + 1 (first even: a pair of one tuple) at once: the tuple's hash
 * and shuffle are shared. */
inline uint2 rng_bits2(RngKey key, uint first)
{
    if (key.z != RNG_SOBOL)
        return (uint2)(rng_independent_bits(key, first), rng_independent_bits(key, first + 1u));
    uint tuple_seed = rng_sobol_tuple_seed(key, first >> 2);
    uint index = sobol_shuffled_index(key.y, tuple_seed);
    uint c = first & 3u;
    return (uint2)(sobol_owen_bits(index, c, tuple_seed), sobol_owen_bits(index, c + 1u, tuple_seed));
}

/* Dimensions `first` .. `first` + 3 (first a multiple of 4: a whole tuple). */
inline uint4 rng_bits4(RngKey key, uint first)
{
    if (key.z != RNG_SOBOL)
        return (uint4)(rng_independent_bits(key, first), rng_independent_bits(key, first + 1u),
                       rng_independent_bits(key, first + 2u), rng_independent_bits(key, first + 3u));
    uint tuple_seed = rng_sobol_tuple_seed(key, first >> 2);
    uint index = sobol_shuffled_index(key.y, tuple_seed);
    uint2 high = sobol_dims23_reversed(index);
    return (uint4)(sobol_owen_finish(index, 0u, tuple_seed),
                   sobol_owen_finish(sobol_dim1_reversed(index), 1u, tuple_seed),
                   sobol_owen_finish(high.x, 2u, tuple_seed), sobol_owen_finish(high.y, 3u, tuple_seed));
}

/* A uniform float in [0, 1): the top 24 bits, so 1.0f is never returned. */
inline float uint_to_unit(uint x) { return (float)(x >> 8) * (1.0f / 16777216.0f); }

/* Dimension numbering. Dimensions are hashed, never stored, so unused numbers cost nothing; they are
 * reserved so that later features do not renumber (and so re-noise) what exists:
 *   camera, 0..7: jitter x, y, lens u, v; 4 is for the shutter time (motion blur), 5..7 spare;
 *   (the Sobol sampler stratifies 4t .. 4t + 3 jointly, best the pair 4t, 4t + 1: keep what is
 *   drawn together so);
 *   bounce b, DIM_BOUNCE_BASE + b * DIMS_PER_BOUNCE + which: light u, v, light pick, alias coin,
 *   BSDF u, v, lobe, roulette, BSDF w, mix leaf, opacity of the closest hit, opacity along
 *   the shadow ray, two free (12, 13: the environment's texel pick and alias coin until its
 *   CDFs took the light sample's numbers), black-hole disk pass-through coins
 *   (14, DIM_DISK_COIN in integrate_geodesic.cl), the medium tracking of the segment that reached
 *   the vertex and of its shadow ray (15, cl/medium/medium_track.cl). */
#define DIM_CAMERA_JITTER_X 0u
#define DIM_CAMERA_JITTER_Y 1u
#define DIM_LENS_U 2u
#define DIM_LENS_V 3u
#define DIM_CAMERA_TIME 4u /* the path's shutter fraction (camera_time) */
#define DIM_BOUNCE_BASE 8u
#define DIMS_PER_BOUNCE 16u
#define DIM_LIGHT_U 0u
#define DIM_LIGHT_V 1u
#define DIM_LIGHT_PICK 2u
#define DIM_LIGHT_COIN 3u
#define DIM_BSDF_U 4u
#define DIM_BSDF_V 5u
#define DIM_BSDF_LOBE 6u
#define DIM_ROULETTE 7u
#define DIM_BSDF_W 8u     /* a third BSDF number (e.g. a lobe choice that needs u, v free) */
#define DIM_MIX 9u        /* which leaf of a mix material */
#define DIM_OPACITY 10u   /* alpha cut-out pass-through of the closest hit */
#define DIM_SHADOW_OPACITY 11u /* the same along the bounce's shadow ray */
/* 12 and 13 are free (they drew the environment map's alias-table entry and coin). */
#define DIM_MEDIUM 15u    /* the first free-flight distance; seeds the tracking's stream */

inline float rng_from_key(RngKey key, uint dimension) { return uint_to_unit(rng_bits(key, dimension)); }

/* The key of sample `sample` of pixel `pixel` under the render's sampler (RENDER_SOBOL). */
inline RngKey render_rng_key(constant RenderParams *p, uint pixel, uint sample)
{
    return rng_sampler_key(pixel, sample, p->seed, (p->flags & RENDER_SOBOL) ? RNG_SOBOL : RNG_INDEPENDENT);
}

inline float rng_uniform(uint pixel, uint sample, uint dimension, uint seed)
{
    return rng_from_key(rng_path_key(pixel, sample, seed), dimension);
}

/* Dimensions `first` and `first` + 1 (first even: a tuple) as two floats. */
inline float2 rng_pair(RngKey key, uint first)
{
    uint2 bits = rng_bits2(key, first);
    return (float2)(uint_to_unit(bits.x), uint_to_unit(bits.y));
}

/* Dimension `which` (DIM_LIGHT_PICK...) of bounce `bounce` (0 = the camera ray's hit). */
inline uint rng_bounce_bits(RngKey key, uint bounce, uint which)
{
    return rng_bits(key, DIM_BOUNCE_BASE + bounce * DIMS_PER_BOUNCE + which);
}
inline float rng_bounce(RngKey key, uint bounce, uint which)
{
    return uint_to_unit(rng_bounce_bits(key, bounce, which));
}

/* Dimensions `which` and `which` + 1 (which even: DIM_LIGHT_PICK, DIM_LIGHT_U, DIM_BSDF_U) of
 * bounce `bounce`, as bits or as floats. */
inline uint2 rng_bounce_bits2(RngKey key, uint bounce, uint which)
{
    return rng_bits2(key, DIM_BOUNCE_BASE + bounce * DIMS_PER_BOUNCE + which);
}
/* Dimensions `which` .. `which` + 3 (which a multiple of 4: DIM_LIGHT_U) of bounce `bounce`. */
inline uint4 rng_bounce_bits4(RngKey key, uint bounce, uint which)
{
    return rng_bits4(key, DIM_BOUNCE_BASE + bounce * DIMS_PER_BOUNCE + which);
}
inline float2 rng_bounce_pair(RngKey key, uint bounce, uint which)
{
    return rng_pair(key, DIM_BOUNCE_BASE + bounce * DIMS_PER_BOUNCE + which);
}
