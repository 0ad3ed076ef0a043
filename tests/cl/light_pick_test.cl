/* SPDX-License-Identifier: MIT */
/* light_pick_test.cl: kernels for tests/test_light_pick.c. */

#define LIGHT_PICK_TEST_GROUPS 64u

/* Work item i draws samples_per_item light choices, as shade_surface does at the first bounce of
 * pixel i's samples 0.., and counts them per group of emitters (group_of[triangle]). */
kernel void light_pick_test_count(const global LightEntry *lights, uint num_lights,
                                  const global uchar *group_of, uint samples_per_item, uint seed,
                                  global uint *counts)
{
    uint item = get_global_id(0);
    uint local_counts[LIGHT_PICK_TEST_GROUPS];
    for (uint g = 0; g < LIGHT_PICK_TEST_GROUPS; g++)
        local_counts[g] = 0u;
    for (uint s = 0; s < samples_per_item; s++) {
        RngKey key = rng_path_key(item, s, seed);
        LightEntry entry = light_pick(lights, num_lights, rng_bounce_bits(key, 0u, DIM_LIGHT_PICK),
                                      rng_bounce(key, 0u, DIM_LIGHT_COIN));
        local_counts[group_of[entry.triangle]]++;
    }
    for (uint g = 0; g < LIGHT_PICK_TEST_GROUPS; g++)
        if (local_counts[g] != 0u)
            atomic_add(&counts[g], local_counts[g]);
}
