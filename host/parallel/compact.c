// SPDX-License-Identifier: MIT
/* compact.c: drives the kernels of cl/parallel/scan.cl (see the stage list there). A compaction of n flags is
 * count -> scatter while the tile counts fit one work-group (up to 2^24 flags with the default
 * work-group size of 256), else count -> reduce per level -> exclusive scans, top level first ->
 * scatter (5 launches up to 2^32 flags). */
#include "parallel/compact.h"

#include <stdio.h>
#include <stdlib.h>

#define FLAGS_PER_ITEM 32 /* SCAN_FLAGS_PER_ITEM in cl/parallel/scan.cl: one 32-bit mask word per item */
#define VALUES_PER_ITEM 8 /* tile sums scanned per work item (a kernel argument, tunable here) */
#define MAX_LEVELS 16     /* enough for n = 2^32 - 1 even with one work item per group */
#define MAX_LAUNCHES (2 * MAX_LEVELS + 2)
#define MAX_GROUP_SIZE 2048 /* the scatter stages offsets within a tile (32 per item) as ushorts */
#define GPU_GROUP_SIZE 256  /* H100: 256 and 512 about equal, 128 slower (needs 2 more launches) */
#define CPU_GROUP_SIZE 256  /* PoCL, 2 busy cores: 16 to 256 within noise, 1024 2-3x slower */

struct Compactor {
    Device *dev;
    size_t max_n;
    size_t group_size;
    cl_kernel count_flags, reduce_values, exclusive_values, scatter_indices;
    cl_mem mask;                   /* one alive bit per slot, whole tiles */
    cl_mem tile_sums[MAX_LEVELS];  /* [1]: per flag tile; [k + 1]: per tile of level k */
    cl_mem zero;                   /* {0}: the top level's tile offset */
    cl_mem count;                  /* compactor_run's count */
    uint32_t last_n;               /* the last compaction's n, tiles and mode (for free lists) */
    size_t last_tiles;
    cl_uint last_sum_counts;
    double *profile_ms;
    cl_event events[MAX_LAUNCHES];
    int num_events;
};

static size_t div_up(size_t a, size_t b) { return (a + b - 1) / b; }

/* sizes[0] = n; sizes[k] = number of values at scan level k, until one work-group scans the
 * level whole. Returns the top level's index (0 when n == 0). */
static int level_sizes(size_t group_size, size_t n, size_t sizes[MAX_LEVELS])
{
    sizes[0] = n;
    if (n == 0)
        return 0;
    size_t values_tile = VALUES_PER_ITEM * group_size;
    int top = 1;
    sizes[1] = div_up(n, FLAGS_PER_ITEM * group_size);
    while (sizes[top] > values_tile) {
        if (top + 1 >= MAX_LEVELS)
            die("compactor: more than %d scan levels", MAX_LEVELS);
        sizes[top + 1] = div_up(sizes[top], values_tile);
        top++;
    }
    return top;
}

static size_t kernel_group_limit(Device *dev, cl_kernel kernel)
{
    size_t limit = 0;
    CL_CHECK(clGetKernelWorkGroupInfo(kernel, dev->device, CL_KERNEL_WORK_GROUP_SIZE, sizeof limit,
                                      &limit, NULL));
    return limit;
}

/* Largest power of two <= the request that every kernel and the local memory allow, and at most
 * MAX_GROUP_SIZE. The scatter needs the most local memory: FLAGS_PER_ITEM ushorts and 2 uints per
 * work item. */
static size_t pick_group_size(Device *dev, Compactor *c, size_t request)
{
    if (request == 0)
        request = (dev->type & CL_DEVICE_TYPE_GPU) ? GPU_GROUP_SIZE : CPU_GROUP_SIZE;
    cl_ulong local_bytes = 0;
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_LOCAL_MEM_SIZE, sizeof local_bytes,
                             &local_bytes, NULL));
    size_t limit = dev->max_work_group < MAX_GROUP_SIZE ? dev->max_work_group : MAX_GROUP_SIZE;
    cl_kernel kernels[] = {c->count_flags, c->reduce_values, c->exclusive_values,
                           c->scatter_indices};
    for (size_t i = 0; i < sizeof kernels / sizeof kernels[0]; i++) {
        size_t k = kernel_group_limit(dev, kernels[i]);
        if (k < limit)
            limit = k;
    }
    const size_t bytes_per_item = FLAGS_PER_ITEM * sizeof(cl_ushort) + 2 * sizeof(cl_uint);
    size_t size = 1;
    while (size * 2 <= request && size * 2 <= limit &&
           (cl_ulong)(size * 2 * bytes_per_item) <= local_bytes)
        size *= 2;
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
    c->reduce_values = device_kernel(dev, "scan_reduce_values");
    c->exclusive_values = device_kernel(dev, "scan_exclusive_values");
    c->scatter_indices = device_kernel(dev, "scan_scatter_indices");
    c->group_size = pick_group_size(dev, c, group_size);

    size_t sizes[MAX_LEVELS];
    int top = level_sizes(c->group_size, max_n, sizes);
    size_t tiles = top > 0 ? sizes[1] : 0;
    cl_uint zero = 0;
    c->mask = device_buffer(dev, "scan_mask", CL_MEM_READ_WRITE,
                            tiles * c->group_size * sizeof(cl_uint), NULL, err);
    bool ok = c->mask != NULL;
    for (int k = 1; k <= top && ok; k++) {
        char name[32];
        snprintf(name, sizeof name, "scan_tile_sums_%d", k);
        c->tile_sums[k] = device_buffer(dev, name, CL_MEM_READ_WRITE, sizes[k] * sizeof(cl_uint),
                                        NULL, err);
        ok = c->tile_sums[k] != NULL;
    }
    if (ok)
        c->zero = device_buffer(dev, "scan_zero", CL_MEM_READ_ONLY, sizeof zero, &zero, err);
    if (c->zero)
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

/* Launches groups work-groups of the compactor's size; keeps the event when profiling. */
static void launch(Compactor *c, cl_kernel kernel, size_t groups)
{
    size_t local = c->group_size;
    size_t global = groups * local;
    cl_event *event = NULL;
    if (c->profile_ms) {
        if (c->num_events >= MAX_LAUNCHES)
            die("compactor: more than %d launches", MAX_LAUNCHES);
        event = &c->events[c->num_events++];
    }
    CL_CHECK(clEnqueueNDRangeKernel(c->dev->queue, kernel, 1, NULL, &global, &local, 0, NULL,
                                    event));
}

/* Waits for the profiled launches and adds their device time. */
static void collect_profile(Compactor *c)
{
    if (c->num_events == 0)
        return;
    for (int i = 0; i < c->num_events; i++)
        *c->profile_ms += device_event_ms(c->events[i]);
    c->num_events = 0;
}

/* Exclusive scan of level k in place, adding the offsets of level k + 1 (already scanned), or
 * {0} at the top. Every level's last tile writes the same grand total into count_buf. */
static void scan_level(Compactor *c, const size_t *sizes, int k, int top, cl_mem count_buf)
{
    size_t local = c->group_size;
    cl_uint m = (cl_uint)sizes[k], per_item = VALUES_PER_ITEM;
    cl_mem offsets = k == top ? c->zero : c->tile_sums[k + 1];
    cl_kernel kernel = c->exclusive_values;
    KERNEL_ARGS(kernel, 0, KARG(c->tile_sums[k]), KARG(m), KARG(per_item), KARG(offsets),
                KARG(count_buf), KARG_LOCAL(VALUES_PER_ITEM * local * sizeof(cl_uint)),
                KARG_LOCAL(2 * local * sizeof(cl_uint)));
    launch(c, kernel, k == top ? 1 : sizes[k + 1]);
}

/* Flags -> mask and per-tile counts (level 1). */
static void count_flags(Compactor *c, cl_mem flags, uint32_t n, size_t tiles)
{
    size_t local = c->group_size;
    cl_uint n_arg = n;
    KERNEL_ARGS(c->count_flags, 0, KARG(flags), KARG(n_arg), KARG(c->mask), KARG(c->tile_sums[1]),
                KARG_LOCAL(FLAGS_PER_ITEM / 4 * local), KARG_LOCAL(local * sizeof(cl_uint)));
    launch(c, c->count_flags, tiles);
}

/* Sums level k per tile into level k + 1. */
static void reduce_level(Compactor *c, const size_t *sizes, int k)
{
    cl_uint m = (cl_uint)sizes[k], per_item = VALUES_PER_ITEM;
    KERNEL_ARGS(c->reduce_values, 0, KARG(c->tile_sums[k]), KARG(m), KARG(per_item),
                KARG(c->tile_sums[k + 1]), KARG_LOCAL(c->group_size * sizeof(cl_uint)));
    launch(c, c->reduce_values, sizes[k + 1]);
}

/* Mask + level 1 (tile counts when sum_counts, else tile offsets) -> indices. */
static void scatter_indices(Compactor *c, cl_mem indices, cl_mem count_buf, size_t tiles,
                            cl_uint sum_counts, uint32_t n, cl_uint complement)
{
    size_t local = c->group_size;
    cl_uint n_arg = n;
    KERNEL_ARGS(c->scatter_indices, 0, KARG(c->mask), KARG(c->tile_sums[1]), KARG(sum_counts),
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
        CL_CHECK(clEnqueueFillBuffer(c->dev->queue, count_buf, &zero, sizeof zero, 0, sizeof zero,
                                     0, NULL, NULL));
        return;
    }
    size_t sizes[MAX_LEVELS];
    int top = level_sizes(c->group_size, n, sizes);
    count_flags(c, flags, n, sizes[1]);
    /* When the tile counts fit one work-group, the scatter adds them up itself, which saves a
     * launch; otherwise reduce them level by level, then scan them top level down, so that level 1
     * holds each flag tile's first output position. */
    cl_uint sum_counts = top == 1;
    if (!sum_counts) {
        for (int k = 1; k < top; k++)
            reduce_level(c, sizes, k);
        for (int k = top; k >= 1; k--)
            scan_level(c, sizes, k, top, count_buf);
    }
    scatter_indices(c, indices, count_buf, sizes[1], sum_counts, n, 0);
    c->last_tiles = sizes[1];
    c->last_sum_counts = sum_counts;
    if (c->profile_ms)
        collect_profile(c);
}

void compactor_enqueue_free(Compactor *c, cl_mem indices)
{
    if (c->last_n == 0)
        return;
    scatter_indices(c, indices, c->count, c->last_tiles, c->last_sum_counts, c->last_n, 1);
    if (c->profile_ms)
        collect_profile(c);
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
    size_t sizes[MAX_LEVELS];
    int top = level_sizes(c->group_size, n, sizes);
    return top == 0 ? 0 : top == 1 ? 2 : 2 * top + 1;
}

void compactor_destroy(Compactor *c)
{
    if (!c)
        return;
    cl_kernel kernels[] = {c->count_flags, c->reduce_values, c->exclusive_values,
                           c->scatter_indices};
    for (size_t i = 0; i < sizeof kernels / sizeof kernels[0]; i++)
        if (kernels[i])
            CL_CHECK(clReleaseKernel(kernels[i]));
    cl_mem buffers[] = {c->mask, c->zero, c->count};
    for (size_t i = 0; i < sizeof buffers / sizeof buffers[0]; i++)
        if (buffers[i])
            CL_CHECK(clReleaseMemObject(buffers[i]));
    for (int k = 0; k < MAX_LEVELS; k++)
        if (c->tile_sums[k])
            CL_CHECK(clReleaseMemObject(c->tile_sums[k]));
    free(c);
}
