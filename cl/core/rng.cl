/* SPDX-License-Identifier: MIT */
/* rng.cl: counter-based random numbers. Every number is a hash of (pixel, sample, dimension, seed),
 * so a render is a pure function of its settings whatever the device, pass split or path order. */

/* PCG-style 32-bit permutation (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering"). */
inline uint hash_pcg(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

/* Per-(pixel, sample, seed) key: hashed once per kernel, then once more per dimension (below), so
 * a path vertex that draws 7 numbers costs 3 + 7 hashes instead of 4 x 7. */
inline uint rng_path_key(uint pixel, uint sample, uint seed)
{
    return hash_pcg(pixel ^ hash_pcg(sample ^ hash_pcg(seed)));
}

/* A uniform float in [0, 1): the top 24 bits, so 1.0f is never returned. */
inline float uint_to_unit(uint x) { return (float)(x >> 8) * (1.0f / 16777216.0f); }

/* Dimension numbering: each bounce uses DIMS_PER_BOUNCE consecutive dimensions. */
#define DIM_CAMERA_JITTER_X 0u
#define DIM_CAMERA_JITTER_Y 1u
#define DIM_LENS_U 2u
#define DIM_LENS_V 3u
#define DIM_BOUNCE_BASE 4u
#define DIMS_PER_BOUNCE 8u
#define DIM_LIGHT_PICK 0u
#define DIM_LIGHT_U 1u
#define DIM_LIGHT_V 2u
#define DIM_BSDF_U 3u
#define DIM_BSDF_V 4u
#define DIM_BSDF_LOBE 5u
#define DIM_ROULETTE 6u

inline float rng_from_key(uint key, uint dimension) { return uint_to_unit(hash_pcg(dimension ^ key)); }

inline float rng_uniform(uint pixel, uint sample, uint dimension, uint seed)
{
    return rng_from_key(rng_path_key(pixel, sample, seed), dimension);
}

/* Dimension `which` (DIM_LIGHT_PICK...) of bounce `bounce` (0 = the camera ray's hit). */
inline float rng_bounce(uint key, uint bounce, uint which)
{
    return rng_from_key(key, DIM_BOUNCE_BASE + bounce * DIMS_PER_BOUNCE + which);
}
