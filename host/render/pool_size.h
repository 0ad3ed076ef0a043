/* SPDX-License-Identifier: MIT */
/* pool_size.h: how many path slots a render keeps in flight (the pool) and how many samples a
 * window of them covers, from the device's memory and what the user asked for. */
#ifndef PT_POOL_SIZE_H
#define PT_POOL_SIZE_H

#include <stdbool.h>
#include <stdint.h>

/* Default pool. On a GPU as large as its memory share allows: every stage launch pays a fixed cost,
 * its ramp and its last, unevenly loaded wave, which a step over more paths spreads thinner
 * (bench/README.md "The path pool"). On a CPU, whose megakernel needs only a few paths per core,
 * modest. A default pool and its window take at most 1 / DEFAULT_POOL_MEMORY_SHARE of the device's
 * memory, so that the scene keeps the rest; a pool the user chose may take half. */
#define POOL_SIZE_GPU (1u << 25)
#define POOL_SIZE_CPU (1u << 16)
#define DEFAULT_POOL_MEMORY_SHARE 8

/* Default window: WINDOW_PER_POOL pools, long enough that the pool stays full for most of it (the
 * tail, where the last paths of the window run with no refills, is about a pool's worth of work,
 * and finish_paths (megakernel.h) takes its last paths in one launch). A window is also the unit of
 * progress and of the film's updates. With the large GPU pool, windows of 8 or 16 pools measured
 * 1-3% slower than 4 on long renders (bench/README.md "The path pool"). PT_WINDOW_POOLS overrides
 * it; a longer window shrinks back to WINDOW_PER_POOL pools before the pool shrinks. */
#define WINDOW_PER_POOL 4

/* Device bytes per path slot and per window sample (the film, the scene and the compactor's few
 * bits per slot aside). */
extern const uint64_t pool_bytes_per_slot, pool_bytes_per_sample;

typedef struct {
    uint64_t global_mem, max_alloc; /* CL_DEVICE_GLOBAL_MEM_SIZE, CL_DEVICE_MAX_MEM_ALLOC_SIZE */
    bool gpu;
} PoolDevice;

typedef struct {
    uint64_t pool;          /* the user's pool (RenderSettings.pool_size, PT_POOL_SIZE); 0: the default */
    uint64_t window;        /* the user's window (RenderSettings.window_size); 0: window_pools pools */
    uint32_t window_pools;  /* PT_WINDOW_POOLS, else WINDOW_PER_POOL */
    bool no_compaction;     /* no free slots to refill: the window is the pool */
    uint64_t total_samples; /* the render's samples: neither exceeds them */
} PoolRequest;

typedef struct {
    uint32_t pool, window;
} PoolChoice;

/* The pool and window: both shrink, a long default window first, until they fit the memory share
 * and every buffer fits the device's max allocation. */
PoolChoice pool_choose(PoolDevice dev, PoolRequest req);

#endif
