// SPDX-License-Identifier: MIT
/* compact.c: drives the kernels of cl/parallel/scan.cl (see the stage list there). A compaction of n flags is
 * count -> scatter while the scatter can add up the tile counts itself (up to 2^24 flags with the
 * default work-group size of 256), else count -> exclusive scan of the tile counts
 * (parallel/exclusive_scan.h, with the compactor's work-group size) -> scatter: 3 launches up to
 * 2^26 flags, 5 up to 2^32. */
#include "parallel/compact.h"

#include <stdlib.h>

#include "parallel/exclusive_scan.h"

#define FLAGS_PER_ITEM 32 /* SCAN_FLAGS_PER_ITEM in cl/parallel/scan.cl: one 32-bit mask word per item */
#define SUMMED_PER_ITEM 8 /* the scatter adds up to this many tile counts per work item itself */
#define MAX_GROUP_SIZE 2048 /* the scatter stages offsets within a tile (32 per item) as ushorts */
#define GPU_GROUP_SIZE 256  /* H100: 256 and 512 about equal, 128 slower (needs 2 more launches) */
#define CPU_GROUP_SIZE 256  /* PoCL, 2 busy cores: 16 to 256 within noise, 1024 2-3x slower */

struct Compactor {
    Device *dev;
    size_t max_n;
    size_t group_size;
    cl_kernel count_flags, scatter_indices;
    cl_mem mask;             /* one alive bit per slot, whole tiles */
    cl_mem tile_sums;        /* per flag tile: its count, or its offset once scanned */
    ExclusiveScan *scan;     /* the tile counts into offsets, when the scatter cannot sum them */
    cl_mem count;            /* compactor_run's count */
    uint32_t last_n;         /* the last compaction's n, tiles and mode (for free lists) */
    size_t last_tiles;
    cl_uint last_sum_counts;
    double *profile_ms;
};

static size_t div_up(size_t a, size_t b) { return (a + b - 1) / b; }

static size_t flag_tiles(const Compactor *c, size_t n) { return div_up(n, FLAGS_PER_ITEM * c->group_size); }

/* Whether the scatter adds up the tile counts before its tile itself, which saves the scan. */
static bool scatter_sums_counts(const Compactor *c, size_t tiles)
{
    return tiles <= SUMMED_PER_ITEM * c->group_size;
}

/* Largest power of two <= the request that both kernels and the local memory allow, and at most
 * MAX_GROUP_SIZE. The scatter needs the most local memory: FLAGS_PER_ITEM ushorts and 2 uints per
 * work item. */
static size_t pick_group_size(Device *dev, Compactor *c, size_t request)
{
    if (request == 0)
        request = (dev->type & CL_DEVICE_TYPE_GPU) ? GPU_GROUP_SIZE : CPU_GROUP_SIZE;
    cl_kernel kernels[] = {c->count_flags, c->scatter_indices};
    size_t size = pow2_group_size(dev, kernels, 2, request < MAX_GROUP_SIZE ? request : MAX_GROUP_SIZE);
    const size_t bytes_per_item = FLAGS_PER_ITEM * sizeof(cl_ushort) + 2 * sizeof(cl_uint);
    while (size > 1 && (cl_ulong)(size * bytes_per_item) > device_local_mem_bytes(dev))
        size /= 2;
    return size;
}

Compactor *compactor_create_sized(Device *dev, size_t max_n, size_t group_size, Error *err)
{
    if (max_n > UINT32_MAX) {
        error_set(err, ERR_TOO_LARGE, NULL, 0,
                  "compactor: %zu slots requested, at most %u can be compacted", max_n,
                  (unsigned)UINT32_MAX);
        return NULL;
    }
    Compactor *c = calloc(1, sizeof *c);
    if (!c)
        die("out of memory");
    c->dev = dev;
    c->max_n = max_n;
    c->count_flags = device_kernel(dev, "scan_count_flags");
    c->scatter_indices = device_kernel(dev, "scan_scatter_indices");
    c->group_size = pick_group_size(dev, c, group_size);

    size_t tiles = flag_tiles(c, max_n);
    cl_uint zero = 0;
    c->mask = device_buffer(dev, "scan_mask", CL_MEM_READ_WRITE,
                            tiles * c->group_size * sizeof(cl_uint), NULL, err);
    if (c->mask)
        c->tile_sums = device_buffer(dev, "scan_tile_sums", CL_MEM_READ_WRITE,
                                     tiles * sizeof(cl_uint), NULL, err);
    if (c->tile_sums)
        c->scan = exclusive_scan_create_sized(dev, tiles, c->group_size, err);
    if (c->scan)
        c->count = device_buffer(dev, "scan_count", CL_MEM_READ_WRITE, sizeof zero, &zero, err);
    if (!c->count) {
        compactor_destroy(c);
        return NULL;
    }
    return c;
}

Compactor *compactor_create(Device *dev, size_t max_n, Error *err)
{
    return compactor_create_sized(dev, max_n, 0, err);
}

/* Launches groups work-groups of the compactor's size; adds the device time when profiling. */
static void launch(Compactor *c, cl_kernel kernel, size_t groups)
{
    double ms = 0.0;
    device_run(c->dev, kernel, groups * c->group_size, c->group_size, c->profile_ms ? &ms : NULL);
    if (c->profile_ms)
        *c->profile_ms += ms;
}

/* Flags -> mask and per-tile counts. */
static void count_flags(Compactor *c, cl_mem flags, uint32_t n, size_t tiles)
{
    size_t local = c->group_size;
    cl_uint n_arg = n;
    KERNEL_ARGS(c->count_flags, 0, KARG(flags), KARG(n_arg), KARG(c->mask), KARG(c->tile_sums),
                KARG_LOCAL(FLAGS_PER_ITEM / 4 * local), KARG_LOCAL(local * sizeof(cl_uint)));
    launch(c, c->count_flags, tiles);
}

/* Mask + tile counts (when sum_counts) or tile offsets -> indices. */
static void scatter_indices(Compactor *c, cl_mem indices, cl_mem count_buf, size_t tiles,
                            cl_uint sum_counts, uint32_t n, cl_uint complement)
{
    size_t local = c->group_size;
    cl_uint n_arg = n;
    KERNEL_ARGS(c->scatter_indices, 0, KARG(c->mask), KARG(c->tile_sums), KARG(sum_counts),
                KARG(count_buf), KARG(indices), KARG(n_arg), KARG(complement),
                KARG_LOCAL(FLAGS_PER_ITEM * local * sizeof(cl_ushort)),
                KARG_LOCAL(2 * local * sizeof(cl_uint)));
    launch(c, c->scatter_indices, tiles);
}

void compactor_enqueue(Compactor *c, cl_mem flags, cl_mem indices, cl_mem count_buf, uint32_t n)
{
    if (n > c->max_n)
        die("compactor: %u flags, above the %zu it was created for", n, c->max_n);
    c->last_n = n;
    if (n == 0) {
        cl_uint zero = 0;
        device_fill(c->dev, count_buf, &zero, sizeof zero, 0, sizeof zero, NULL);
        return;
    }
    size_t tiles = flag_tiles(c, n);
    count_flags(c, flags, n, tiles);
    /* When the tile counts fit one work-group, the scatter adds them up itself, which saves the
     * scan's launches; otherwise the scan turns them into each flag tile's first output position
     * (and writes the count). */
    cl_uint sum_counts = scatter_sums_counts(c, tiles);
    if (!sum_counts)
        exclusive_scan_enqueue_total(c->scan, c->tile_sums, (uint32_t)tiles, count_buf, c->profile_ms);
    scatter_indices(c, indices, count_buf, tiles, sum_counts, n, 0);
    c->last_tiles = tiles;
    c->last_sum_counts = sum_counts;
}

void compactor_enqueue_free(Compactor *c, cl_mem indices)
{
    if (c->last_n == 0)
        return;
    scatter_indices(c, indices, c->count, c->last_tiles, c->last_sum_counts, c->last_n, 1);
}

uint32_t compactor_run(Compactor *c, cl_mem flags, cl_mem indices, uint32_t n)
{
    compactor_enqueue(c, flags, indices, c->count, n);
    cl_uint count = 0;
    device_read(c->dev, c->count, 0, sizeof count, &count);
    return count;
}

void compactor_set_profile(Compactor *c, double *ms_accumulator) { c->profile_ms = ms_accumulator; }

size_t compactor_group_size(const Compactor *c) { return c->group_size; }

int compactor_launches(const Compactor *c, uint32_t n)
{
    size_t tiles = flag_tiles(c, n);
    if (tiles == 0 || scatter_sums_counts(c, tiles))
        return tiles == 0 ? 0 : 2;
    return 2 + exclusive_scan_launches(c->scan, (uint32_t)tiles);
}

void compactor_destroy(Compactor *c)
{
    if (!c)
        return;
    cl_kernel kernels[] = {c->count_flags, c->scatter_indices};
    for (size_t i = 0; i < sizeof kernels / sizeof kernels[0]; i++)
        if (kernels[i])
            device_release_kernel(kernels[i]);
    cl_mem buffers[] = {c->mask, c->tile_sums, c->count};
    for (size_t i = 0; i < sizeof buffers / sizeof buffers[0]; i++)
        if (buffers[i])
            device_release_buffer(buffers[i]);
    exclusive_scan_destroy(c->scan);
    free(c);
}
