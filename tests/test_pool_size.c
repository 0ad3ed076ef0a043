// SPDX-License-Identifier: MIT
/* The path pool and window a render chooses (render/pool_size.h): the large GPU pool within its
 * memory share (a larger one on large cards), the old pool below it, the user's pool's half, the
 * material sorter's counts, the max allocation and the clamps. */
#include <criterion/criterion.h>

#include "parallel/material_sort.h"
#include "render/pool_size.h"

#define GIB (1ull << 30)

/* A GPU with `gib` GiB and a quarter of it as the max allocation (NVIDIA's). */
static PoolDevice gpu(uint64_t gib) { return (PoolDevice){gib * GIB, gib * GIB / 4, true}; }

static PoolRequest defaults(void) { return (PoolRequest){.total_samples = UINT32_MAX}; }

/* On GPUs of 4 to 192 GiB, with and without material sorting: where the default's share holds a
 * pool above POOL_SIZE_GPU with WINDOW_PER_POOL pools, the pool is the largest power of two up to
 * POOL_SIZE_GPU_LARGE that fits it; where it does not, the old default, POOL_SIZE_GPU with
 * WINDOW_PER_POOL_SMALL_GPU pools. */
Test(pool_size, the_default_gpu_pool_is_the_largest_that_fits_its_share)
{
    uint64_t sizes[] = {2, 4, 6, 8, 16, 24, 48, 80, 141, 192};
    uint32_t keys[] = {0, 9};
    for (size_t k = 0; k < 2; k++)
        for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
            PoolDevice d = gpu(sizes[i]);
            PoolRequest r = defaults();
            r.sort_keys = keys[k];
            PoolChoice c = pool_choose(d, r);
            uint64_t share = pool_default_share(d.global_mem);
            cr_expect_eq(c.pool & (c.pool - 1), 0u, "%u: a power of two", c.pool);
            if (c.pool > POOL_SIZE_GPU) {
                cr_expect_leq(pool_device_bytes(c.pool, c.window, keys[k]), share,
                              "%llu GiB: pool %u, window %u", (unsigned long long)sizes[i],
                              c.pool, c.window);
                cr_expect_leq(c.pool, POOL_SIZE_GPU_LARGE);
                if (sizes[i] < 64) /* the pools of before the larger share */
                    cr_expect_leq(c.pool, 1u << 25, "%llu GiB", (unsigned long long)sizes[i]);
                cr_expect_eq(c.window, WINDOW_PER_POOL * (uint64_t)c.pool);
            } else {
                cr_expect_eq(c.pool, POOL_SIZE_GPU, "%llu GiB", (unsigned long long)sizes[i]);
                cr_expect_eq(c.window, WINDOW_PER_POOL_SMALL_GPU * (uint64_t)POOL_SIZE_GPU);
            }
            if (c.pool < POOL_SIZE_GPU_LARGE)
                cr_expect_gt(pool_device_bytes(2ull * c.pool, WINDOW_PER_POOL * 2ull * c.pool,
                                               keys[k]),
                             share, "%llu GiB: a pool of %u would have fit",
                             (unsigned long long)sizes[i], 2 * c.pool);
        }
    /* The H100's 80 GiB hold the whole large pool; 16 GiB hold 2^23 slots; 4 GiB the old pool. */
    cr_expect_eq(pool_choose(gpu(80), defaults()).pool, POOL_SIZE_GPU_LARGE);
    cr_expect_eq(pool_choose(gpu(16), defaults()).pool, 1u << 23);
    cr_expect_eq(pool_choose(gpu(4), defaults()).pool, POOL_SIZE_GPU);
}

/* Cards of LARGE_CARD_BYTES or more give the pool a third of their memory, smaller ones an
 * eighth: 64 GiB hold 2^26 slots, 63 GiB 2^25, 141 GiB (an H200) 2^27. */
Test(pool_size, large_cards_give_the_pool_a_larger_share)
{
    cr_expect_eq(pool_default_share(64 * GIB), 64 * GIB / LARGE_CARD_POOL_MEMORY_SHARE);
    cr_expect_eq(pool_default_share(63 * GIB), 63 * GIB / DEFAULT_POOL_MEMORY_SHARE);
    cr_expect_eq(pool_choose(gpu(64), defaults()).pool, 1u << 26);
    cr_expect_eq(pool_choose(gpu(63), defaults()).pool, 1u << 25);
    cr_expect_eq(pool_choose(gpu(141), defaults()).pool, POOL_SIZE_GPU_LARGE);
}

/* An H100 (81559 MiB) holds the large pool and its window of 4 pools in its third, but not with
 * material sorting's lists too (2^26 then); the frame (1280x960 at 256 spp) gets the
 * large pool and one window of its samples. */
Test(pool_size, an_h100_holds_the_large_pool_unsorted)
{
    PoolDevice h100 = {81559ull << 20, (81559ull << 20) / 4, true};
    PoolRequest r = defaults();
    cr_expect_eq(pool_choose(h100, r).pool, POOL_SIZE_GPU_LARGE);
    r.sort_keys = 9;
    cr_expect_eq(pool_choose(h100, r).pool, POOL_SIZE_GPU_LARGE / 2);
    r = defaults();
    r.total_samples = 1280ull * 960 * 256;
    PoolChoice c = pool_choose(h100, r);
    cr_expect_eq(c.pool, POOL_SIZE_GPU_LARGE);
    cr_expect_eq(c.window, r.total_samples);
}

/* The sorter's counts (one per key per tile) count against the share and stay under 2^32: a
 * million materials take the large pool down, where 9 leave it whole. */
Test(pool_size, material_sorting_counts_against_the_pool)
{
    PoolRequest r = defaults();
    r.sort_keys = 1u << 20;
    PoolChoice c = pool_choose(gpu(80), r);
    cr_expect_lt(c.pool, POOL_SIZE_GPU_LARGE);
    cr_expect_leq((uint64_t)r.sort_keys * (c.pool / MATERIAL_SORT_TILE), UINT32_MAX);
    cr_expect_leq(pool_device_bytes(c.pool, c.window, r.sort_keys), 80 * GIB / 2);
    cr_expect_gt(pool_sort_bytes(c.pool, r.sort_keys), pool_sort_bytes(c.pool, 9));
    cr_expect_eq(pool_sort_bytes(c.pool, 0), 0u);
    /* A given pool is held to the 2^32 counts too, where the sorter would refuse it. */
    r.pool = 1u << 28;
    c = pool_choose(gpu(192), r);
    cr_expect_leq((uint64_t)r.sort_keys * (c.pool / MATERIAL_SORT_TILE), UINT32_MAX);
}

/* A pool the user names may take half of the memory, and is kept where it fits. */
Test(pool_size, a_given_pool_may_take_half_the_memory)
{
    PoolRequest r = defaults();
    r.pool = 1u << 24;
    PoolChoice c = pool_choose(gpu(16), r);
    cr_expect_eq(c.pool, 1u << 24);
    cr_expect_leq(pool_device_bytes(c.pool, c.window, 0), 8 * GIB);
    cr_expect_gt(pool_device_bytes(c.pool, c.window, 0), pool_default_share(16 * GIB),
                 "the given pool was held to the default's share");
    r.pool = 1u << 26;
    c = pool_choose(gpu(16), r);
    cr_expect_lt(c.pool, 1u << 26);
    cr_expect_leq(pool_device_bytes(c.pool, c.window, 0), 8 * GIB);
}

/* CPUs keep POOL_SIZE_CPU slots and WINDOW_PER_POOL pools. */
Test(pool_size, cpus_keep_the_small_pool)
{
    PoolChoice c = pool_choose((PoolDevice){16 * GIB, 4 * GIB, false}, defaults());
    cr_expect_eq(c.pool, POOL_SIZE_CPU);
    cr_expect_eq(c.window, WINDOW_PER_POOL * POOL_SIZE_CPU);
}

/* Neither exceeds the render's samples; without compaction, or with a window shorter than the
 * pool, the window is the pool; the window's radiance fits the max allocation and its count 32
 * bits; a longer window (PT_WINDOW_POOLS) gives way to WINDOW_PER_POOL pools before the pool
 * shrinks, and a window the user gives shrinks only with the pool. */
Test(pool_size, clamps)
{
    PoolRequest r = defaults();
    r.total_samples = 1000;
    PoolChoice c = pool_choose(gpu(80), r);
    cr_expect_eq(c.pool, 1000u);
    cr_expect_eq(c.window, 1000u);

    r = defaults();
    r.no_compaction = true;
    c = pool_choose(gpu(80), r);
    cr_expect_eq(c.window, c.pool);
    r = defaults();
    r.window = 1; /* pt bench's no-refill mode */
    c = pool_choose(gpu(80), r);
    cr_expect_eq(c.pool, POOL_SIZE_GPU_LARGE);
    cr_expect_eq(c.window, c.pool);

    PoolDevice small_alloc = {80 * GIB, 256ull << 20, true};
    c = pool_choose(small_alloc, defaults());
    cr_expect_leq((uint64_t)c.window * 16u, small_alloc.max_alloc);

    r = defaults();
    r.pool = 1u << 28;
    r.window_pools = 4096;
    r.total_samples = 1ull << 45;
    c = pool_choose((PoolDevice){1ull << 50, 1ull << 50, true}, r);
    cr_expect_eq(c.window, UINT32_MAX);

    r = defaults();
    r.window_pools = 16;
    cr_expect_eq(pool_choose(gpu(16), r).pool, pool_choose(gpu(16), defaults()).pool);
    c = pool_choose(gpu(128), r); /* 8 pools of the large pool fit its share, 16 not */
    cr_expect_eq(c.pool, POOL_SIZE_GPU_LARGE);
    cr_expect_eq(c.window, 8ull * POOL_SIZE_GPU_LARGE);
    c = pool_choose(gpu(80), r); /* nor 8 on 80 GiB: the window gives way, not the pool */
    cr_expect_eq(c.pool, POOL_SIZE_GPU_LARGE);
    cr_expect_eq(c.window, (uint64_t)WINDOW_PER_POOL * POOL_SIZE_GPU_LARGE);
    cr_expect_eq(pool_choose(gpu(192), r).window, 16ull * POOL_SIZE_GPU_LARGE);

    r = defaults();
    r.pool = 1u << 20;
    r.window = 1u << 24;
    c = pool_choose(gpu(80), r);
    cr_expect_eq(c.pool, 1u << 20);
    cr_expect_eq(c.window, 1u << 24);
    r.pool = 1u << 26;
    r.window = 1u << 30; /* 16 GiB of radiance: over half of 16 GiB and over its max allocation */
    c = pool_choose(gpu(16), r);
    cr_expect_eq((uint64_t)c.window, 16ull * c.pool, "the given window shrank alone: %u, %u",
                 c.pool, c.window);
}
