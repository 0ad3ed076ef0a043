/* SPDX-License-Identifier: MIT */
/* pool_size.h: how many path slots a render keeps in flight (the pool) and how many samples a
 * window of them covers, from the device's memory and what the user asked for. */
#ifndef PT_POOL_SIZE_H
#define PT_POOL_SIZE_H

#include <stdbool.h>
#include <stdint.h>

/* Default pools. A GPU gets the largest power of two up to POOL_SIZE_GPU_LARGE that, with its
 * window and the material sorter's counts, takes at most 1 / DEFAULT_POOL_MEMORY_SHARE of its
 * memory, or 1 / LARGE_CARD_POOL_MEMORY_SHARE on a card of LARGE_CARD_BYTES or more (which keeps
 * over 40 GiB for the scene; a smaller card's eighth holds at most 2^25 slots, as before the
 * larger share), so that the scene keeps the rest: every stage launch pays a fixed cost, its ramp
 * and its last, unevenly loaded wave, which a step over more paths spreads thinner
 * (bench/README.md "The path pool", "Issue 41's table before and after"). Where the share holds
 * no more than POOL_SIZE_GPU, the GPU keeps that pool with windows of WINDOW_PER_POOL_SMALL_GPU
 * pools, the configuration measured best at that size. A CPU, whose megakernel needs only a few
 * paths per core, gets POOL_SIZE_CPU. Other than the large pool, a pool (the default or the
 * user's) may take half the memory. */
#define POOL_SIZE_GPU_LARGE (1u << 27)
#define POOL_SIZE_GPU (1u << 21)
#define POOL_SIZE_CPU (1u << 16)
#define DEFAULT_POOL_MEMORY_SHARE 8
#define LARGE_CARD_POOL_MEMORY_SHARE 3
#define LARGE_CARD_BYTES (64ull << 30)

/* Default window: WINDOW_PER_POOL pools, long enough that the pool stays full for most of it (the
 * tail, where the last paths of the window run with no refills, is about a pool's worth of work,
 * and finish_paths (megakernel.h) takes its last paths in one launch). A window is also the unit of
 * progress and of the film's updates. With the large GPU pool, windows of 8 or 16 pools measured
 * 1-3% slower than 4 on long renders; with 2^21 slots 16 measured up to 5% faster than 4
 * (bench/README.md "The path pool", "The wavefront's tail"). PT_WINDOW_POOLS overrides both; a
 * longer default window shrinks back to WINDOW_PER_POOL pools before the pool shrinks. */
#define WINDOW_PER_POOL 4
#define WINDOW_PER_POOL_SMALL_GPU 16

/* Device bytes per path slot and per window sample: the path state, the active, free and shadow
 * lists; with material sorting also the sorted list and the sort keys per slot, and the sorter's
 * counts (pool_sort_bytes). The compactor's few bits per slot aside. */
extern const uint64_t pool_bytes_per_slot, pool_bytes_per_sample, pool_sort_bytes_per_slot;

typedef struct {
    uint64_t global_mem, max_alloc; /* CL_DEVICE_GLOBAL_MEM_SIZE, CL_DEVICE_MAX_MEM_ALLOC_SIZE */
    bool gpu;
} PoolDevice;

typedef struct {
    uint64_t pool;          /* the user's pool (RenderSettings.pool_size, PT_POOL_SIZE); 0: the default */
    uint64_t window;        /* the user's window (RenderSettings.window_size); 0: window_pools pools */
    uint32_t window_pools;  /* PT_WINDOW_POOLS; 0: the default (WINDOW_PER_POOL...) */
    bool no_compaction;     /* no free slots to refill: the window is the pool */
    uint64_t total_samples; /* the render's samples: neither exceeds them */
    uint32_t sort_keys;     /* material sorting: num_materials + 1 keys; 0 without */
} PoolRequest;

typedef struct {
    uint32_t pool, window;
} PoolChoice;

/* The pool and window: both shrink, a long default window first, until they fit their memory
 * budget, the window's radiance fits the device's max allocation and the sorter's counts stay
 * under 2^32. */
PoolChoice pool_choose(PoolDevice dev, PoolRequest req);

/* Device bytes of a pool of `pool` slots with a window of `window` samples, sorted by sort_keys
 * keys (0: not sorted); of the sorting alone. */
uint64_t pool_device_bytes(uint64_t pool, uint64_t window, uint32_t sort_keys);
uint64_t pool_sort_bytes(uint64_t pool, uint32_t sort_keys);

/* The memory the default GPU pool may take on a device with global_mem bytes. */
uint64_t pool_default_share(uint64_t global_mem);

#endif
