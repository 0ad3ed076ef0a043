// SPDX-License-Identifier: MIT
/* The path pool and window a render chooses (render/pool_size.h): the default pool's memory share,
 * the user's pool's half, the max allocation, and the clamps to the render's samples. */
#include <criterion/criterion.h>

#include "render/pool_size.h"

#define GIB (1ull << 30)

static uint64_t bytes(uint64_t pool, uint64_t window)
{
    return pool * pool_bytes_per_slot + window * pool_bytes_per_sample;
}

/* A GPU with `gib` GiB and a quarter of it as the max allocation (NVIDIA's). */
static PoolDevice gpu(uint64_t gib) { return (PoolDevice){gib * GIB, gib * GIB / 4, true}; }

static PoolRequest defaults(void)
{
    return (PoolRequest){.window_pools = WINDOW_PER_POOL, .total_samples = UINT32_MAX};
}

/* On GPUs of 4 to 192 GiB the default pool is the largest power of two up to POOL_SIZE_GPU that,
 * with its window of WINDOW_PER_POOL pools, fits the default's share of the memory. */
Test(pool_size, the_default_gpu_pool_is_the_largest_that_fits_its_share)
{
    uint64_t sizes[] = {4, 8, 16, 24, 48, 80, 141, 192};
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++) {
        PoolDevice d = gpu(sizes[i]);
        PoolChoice c = pool_choose(d, defaults());
        uint64_t share = d.global_mem / DEFAULT_POOL_MEMORY_SHARE;
        cr_expect_leq(bytes(c.pool, c.window), share, "%llu GiB: pool %u, window %u",
                      (unsigned long long)sizes[i], c.pool, c.window);
        cr_expect_eq(c.pool & (c.pool - 1), 0u, "%u: a power of two", c.pool);
        cr_expect_leq(c.pool, POOL_SIZE_GPU);
        cr_expect_eq(c.window, WINDOW_PER_POOL * (uint64_t)c.pool);
        if (c.pool < POOL_SIZE_GPU)
            cr_expect_gt(bytes(2ull * c.pool, WINDOW_PER_POOL * 2ull * c.pool), share,
                         "%llu GiB: a pool of %u would have fit", (unsigned long long)sizes[i],
                         2 * c.pool);
    }
    /* The H100's 80 GiB hold the whole default; 8 GiB do not. */
    cr_expect_eq(pool_choose(gpu(80), defaults()).pool, POOL_SIZE_GPU);
    cr_expect_lt(pool_choose(gpu(8), defaults()).pool, POOL_SIZE_GPU);
}

/* A pool the user names may take half of the memory, and is kept where it fits. */
Test(pool_size, a_given_pool_may_take_half_the_memory)
{
    PoolRequest r = defaults();
    r.pool = 1u << 24;
    PoolChoice c = pool_choose(gpu(16), r);
    cr_expect_eq(c.pool, 1u << 24);
    cr_expect_leq(bytes(c.pool, c.window), 8 * GIB);
    cr_expect_gt(bytes(c.pool, c.window), 16 * GIB / DEFAULT_POOL_MEMORY_SHARE,
                 "the given pool was held to the default's share");
    r.pool = 1u << 26;
    c = pool_choose(gpu(16), r);
    cr_expect_lt(c.pool, 1u << 26);
    cr_expect_leq(bytes(c.pool, c.window), 8 * GIB);
}

/* CPUs keep POOL_SIZE_CPU slots and WINDOW_PER_POOL pools. */
Test(pool_size, cpus_keep_the_small_pool)
{
    PoolChoice c = pool_choose((PoolDevice){16 * GIB, 4 * GIB, false}, defaults());
    cr_expect_eq(c.pool, POOL_SIZE_CPU);
    cr_expect_eq(c.window, WINDOW_PER_POOL * POOL_SIZE_CPU);
}

/* Neither exceeds the render's samples; without compaction the window is the pool; the window's
 * radiance buffer fits the max allocation; a window the user gives shrinks only with the pool. */
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

    PoolDevice small_alloc = {80 * GIB, 256ull << 20, true};
    c = pool_choose(small_alloc, defaults());
    cr_expect_leq((uint64_t)c.window * 16u, small_alloc.max_alloc);

    r = defaults();
    r.window_pools = 16; /* PT_WINDOW_POOLS: gives way to WINDOW_PER_POOL before the pool shrinks */
    cr_expect_eq(pool_choose(gpu(16), r).pool, pool_choose(gpu(16), defaults()).pool);
    c = pool_choose(gpu(80), r); /* 8 pools fit its share, 16 not */
    cr_expect_eq(c.pool, POOL_SIZE_GPU);
    cr_expect_eq(c.window, 8ull * POOL_SIZE_GPU);
    cr_expect_eq(pool_choose(gpu(192), r).window, 16ull * POOL_SIZE_GPU);

    r = defaults();
    r.pool = 1u << 20;
    r.window = 1u << 24;
    c = pool_choose(gpu(80), r);
    cr_expect_eq(c.pool, 1u << 20);
    cr_expect_eq(c.window, 1u << 24);
}
