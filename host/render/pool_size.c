// SPDX-License-Identifier: MIT
#include "render/pool_size.h"

#include "base/shared_types.h"
#include "parallel/material_sort.h"

#define FIELD_BYTES(type, name) +sizeof(type)
const uint64_t pool_bytes_per_slot = 3 * sizeof(uint32_t) /* active, free_slots, shadow_queue */
    PATH_STATE_FIELDS(FIELD_BYTES);
const uint64_t pool_bytes_per_sample = 0 SAMPLE_STATE_FIELDS(FIELD_BYTES);
#undef FIELD_BYTES
const uint64_t pool_sort_bytes_per_slot = 2 * sizeof(uint32_t); /* sorted_active, sort keys */

/* The material sorter's counts: one per key per tile. */
static uint64_t sort_counts(uint64_t pool, uint32_t sort_keys)
{
    return (uint64_t)sort_keys * ((pool + MATERIAL_SORT_TILE - 1) / MATERIAL_SORT_TILE);
}

uint64_t pool_sort_bytes(uint64_t pool, uint32_t sort_keys)
{
    if (!sort_keys)
        return 0;
    return pool * pool_sort_bytes_per_slot + sort_counts(pool, sort_keys) * sizeof(uint32_t);
}

uint64_t pool_device_bytes(uint64_t pool, uint64_t window, uint32_t sort_keys)
{
    return pool * pool_bytes_per_slot + window * pool_bytes_per_sample +
           pool_sort_bytes(pool, sort_keys);
}

static bool fits(PoolDevice dev, uint64_t pool, uint64_t window, uint32_t sort_keys, uint64_t budget)
{
    return window * sizeof(float4) <= dev.max_alloc && sort_counts(pool, sort_keys) <= UINT32_MAX &&
           pool_device_bytes(pool, window, sort_keys) <= budget;
}

uint64_t pool_default_share(uint64_t global_mem)
{
    return global_mem / (global_mem >= LARGE_CARD_BYTES ? LARGE_CARD_POOL_MEMORY_SHARE
                                                        : DEFAULT_POOL_MEMORY_SHARE);
}

/* The window a pool starts from: the user's, else window_pools pools; at most 2^32 - 1 samples
 * (the count a window's launches take), at least the pool, and the pool without compaction (no
 * free slots to refill). */
static uint64_t first_window(PoolRequest req, uint64_t pool, uint32_t window_pools)
{
    uint64_t window = req.window ? req.window : (uint64_t)window_pools * pool;
    if (window > UINT32_MAX)
        window = UINT32_MAX;
    return req.no_compaction || window < pool ? pool : window;
}

/* The largest power of two in (POOL_SIZE_GPU, POOL_SIZE_GPU_LARGE] that fits the default's share
 * with the user's window or WINDOW_PER_POOL pools (a longer default window gives way to that), or
 * 0. */
static uint64_t large_gpu_pool(PoolDevice dev, PoolRequest req, uint64_t share)
{
    for (uint64_t pool = POOL_SIZE_GPU_LARGE; pool > POOL_SIZE_GPU; pool /= 2)
        if (fits(dev, pool, first_window(req, pool, WINDOW_PER_POOL), req.sort_keys, share))
            return pool;
    return 0;
}

PoolChoice pool_choose(PoolDevice dev, PoolRequest req)
{
    uint64_t pool = req.pool, budget = dev.global_mem / 2;
    uint32_t window_pools = req.window_pools ? req.window_pools : WINDOW_PER_POOL;
    if (!pool && dev.gpu) {
        uint64_t share = pool_default_share(dev.global_mem);
        pool = large_gpu_pool(dev, req, share);
        if (pool) {
            budget = share;
        } else {
            pool = POOL_SIZE_GPU;
            if (!req.window_pools)
                window_pools = WINDOW_PER_POOL_SMALL_GPU;
        }
    } else if (!pool) {
        pool = POOL_SIZE_CPU;
    }
    uint64_t window = first_window(req, pool, window_pools);
    while (pool > 1024 && !fits(dev, pool, window, req.sort_keys, budget)) {
        if (!req.window && window > WINDOW_PER_POOL * pool)
            window /= 2;
        else
            pool /= 2, window /= 2;
    }
    if (window > req.total_samples)
        window = req.total_samples;
    if (pool > window)
        pool = window;
    return (PoolChoice){(uint32_t)pool, (uint32_t)window};
}
