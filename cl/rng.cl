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

inline uint hash4(uint a, uint b, uint c, uint d)
{
    return hash_pcg(a ^ hash_pcg(b ^ hash_pcg(c ^ hash_pcg(d))));
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

inline float rng_uniform(uint pixel, uint sample, uint dimension, uint seed)
{
    return uint_to_unit(hash4(pixel, sample, dimension, seed));
}

inline float rng_bounce(uint pixel, uint sample, uint bounce, uint which, uint seed)
{
    return rng_uniform(pixel, sample, DIM_BOUNCE_BASE + bounce * DIMS_PER_BOUNCE + which, seed);
}
