/* SPDX-License-Identifier: MIT */
/* env_test.cl: kernels for tests/test_environment_sampling.c. */

#define ENV_TEST_PARAMS                                                                            \
    const global float4 *texels, const global uint *cdf, uint width, uint height,                  \
        float rotation
#define ENV_TEST_MAP {texels, cdf, width, height, rotation}

/* Work item i draws samples_per_item env_sample directions (the path RNG of pixel i, samples 0..,
 * light dimensions of the first bounce) and counts them per texel that env_lookup puts them in.
 * mismatches[0] counts samples whose pdf or radiance differ from env_lookup's for their
 * direction (the NEE pdf and the escaped-ray pdf must be the same function). */
kernel void env_test_sample(ENV_TEST_PARAMS, uint samples_per_item, uint seed,
                            global uint *counts, global uint *mismatches)
{
    EnvMap env = ENV_TEST_MAP;
    uint item = get_global_id(0);
    for (uint s = 0; s < samples_per_item; s++) {
        RngKey key = rng_path_key(item, s, seed);
        uint2 bits = rng_bounce_bits2(key, 0u, DIM_LIGHT_U);
        EnvSample es = env_sample(&env, bits.x, bits.y);
        atomic_inc(&counts[env_texel_of(&env, es.direction)]);
        float pdf;
        float3 L = env_lookup(&env, es.direction, &pdf);
        if (!(fabs(pdf - es.pdf_w) <= 1e-3f * es.pdf_w) || any(L != es.radiance) ||
            !(fabs(length(es.direction) - 1.0f) < 1e-5f))
            atomic_inc(&mismatches[0]);
    }
}

/* out[i] = env_lookup of directions[i]: rgb the radiance an escaped ray sees, w its solid-angle
 * pdf. */
kernel void env_test_lookup(ENV_TEST_PARAMS, const global float4 *directions, uint n,
                            global float4 *out)
{
    EnvMap env = ENV_TEST_MAP;
    uint i = get_global_id(0);
    if (i >= n)
        return;
    float p;
    float3 L = env_lookup(&env, xyz(directions[i]), &p);
    out[i] = (float4)(L, p);
}

/* Sample s = 0 .. n - 1 of one pixel under the Sobol sampler (the first n of its sequence), the
 * light dimensions of bounce `bounce`: texels[s] gets the texel each lands in. */
kernel void env_test_sobol_texels(ENV_TEST_PARAMS, uint pixel, uint bounce, uint seed, uint n,
                                  global uint *texel_of)
{
    EnvMap env = ENV_TEST_MAP;
    uint s = get_global_id(0);
    if (s >= n)
        return;
    uint2 bits = rng_bounce_bits2(rng_sampler_key(pixel, s, seed, RNG_SOBOL), bounce, DIM_LIGHT_U);
    EnvSample es = env_sample(&env, bits.x, bits.y);
    texel_of[s] = env_texel_of(&env, es.direction);
}
