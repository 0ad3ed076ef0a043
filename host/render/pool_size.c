// SPDX-License-Identifier: MIT
#include "render/pool_size.h"

#include "base/shared_types.h"

#define FIELD_BYTES(type, name) +sizeof(type)
const uint64_t pool_bytes_per_slot =
    2 * sizeof(uint32_t) /* active, free_slots */ PATH_STATE_FIELDS(FIELD_BYTES);
const uint64_t pool_bytes_per_sample = 0 SAMPLE_STATE_FIELDS(FIELD_BYTES);
#undef FIELD_BYTES

PoolChoice pool_choose(PoolDevice dev, PoolRequest req)
{
    uint64_t pool = req.pool, budget = dev.global_mem / (pool ? 2 : DEFAULT_POOL_MEMORY_SHARE);
    if (!pool)
        pool = dev.gpu ? POOL_SIZE_GPU : POOL_SIZE_CPU;
    uint64_t window = req.window ? req.window : (uint64_t)req.window_pools * pool;
    if (window > UINT32_MAX)
        window = UINT32_MAX; /* the count a window's launches take */
    if (req.no_compaction || window < pool)
        window = pool; /* without compaction there are no free slots to refill */
    while (pool > 1024 && (window * sizeof(float4) > dev.max_alloc ||
                           pool * pool_bytes_per_slot + window * pool_bytes_per_sample > budget)) {
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
