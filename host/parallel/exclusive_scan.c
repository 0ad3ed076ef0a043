// SPDX-License-Identifier: MIT
/* exclusive_scan.c: the level scheme of exclusive_scan.h over the kernels of cl/parallel/scan.cl. Level 0
 * is the caller's array; level k + 1 holds the sums of level k's tiles of VALUES_PER_ITEM x group
 * values, until a level fits one work-group, which scans it with as many values per work item as
 * it needs (at most TOP_MAX_PER_ITEM). */
#include "parallel/exclusive_scan.h"

#include <stdio.h>
#include <stdlib.h>

#define VALUES_PER_ITEM 8   /* per work item on the levels below the top (the compactor's tile sums too) */
#define TOP_MAX_PER_ITEM 32 /* the top level's tile: 32 x 256 values = 32 KiB of local memory */
#define MAX_LEVELS 16       /* enough for 2^32 values even with one work item per group */
#define GROUP_SIZE 256

struct ExclusiveScan {
    Device *dev;
    size_t max_m;
    size_t group_size;
    size_t top_max_per_item;
    cl_kernel reduce_values, exclusive_values;
    cl_mem levels[MAX_LEVELS]; /* [0]: the caller's array, set per call; [k]: level k's values */
    cl_mem zero;               /* {0}: the top level's offset */
    cl_mem total;              /* the grand total, when the caller wants none */
};

static size_t div_up(size_t a, size_t b) { return (a + b - 1) / b; }

size_t pow2_group_size(Device *dev, const cl_kernel *kernels, size_t num_kernels, size_t request)
{
    size_t limit = dev->max_work_group < request ? dev->max_work_group : request;
    for (size_t i = 0; i < num_kernels; i++) {
        size_t kernel_limit = device_kernel_work_group_size(dev, kernels[i]);
        if (kernel_limit < limit)
            limit = kernel_limit;
    }
    size_t size = 1;
    while (size * 2 <= limit)
        size *= 2;
    return size;
}

/* sizes[k]: values at level k, sizes[0] = m. Returns the top level's index. */
static int level_sizes(const ExclusiveScan *s, size_t m, size_t sizes[MAX_LEVELS])
{
    int top = 0;
    sizes[0] = m;
    while (sizes[top] > s->top_max_per_item * s->group_size) {
        if (top + 1 >= MAX_LEVELS)
            die("exclusive_scan: more than %d levels", MAX_LEVELS);
        sizes[top + 1] = div_up(sizes[top], VALUES_PER_ITEM * s->group_size);
        top++;
    }
    return top;
}

ExclusiveScan *exclusive_scan_create_sized(Device *dev, size_t max_m, size_t group_size, Error *err)
{
    if (max_m > UINT32_MAX) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "exclusive scan: %zu values, at most %u", max_m,
                  (unsigned)UINT32_MAX);
        return NULL;
    }
    ExclusiveScan *s = calloc(1, sizeof *s);
    if (!s)
        die("out of memory");
    s->dev = dev;
    s->max_m = max_m;
    s->reduce_values = device_kernel(dev, "scan_reduce_values");
    s->exclusive_values = device_kernel(dev, "scan_exclusive_values");
    cl_kernel kernels[] = {s->reduce_values, s->exclusive_values};
    s->group_size = pow2_group_size(dev, kernels, 2, group_size ? group_size : GROUP_SIZE);

    /* The top level's tile and the scan scratch (2 uints per item) must fit local memory. */
    cl_ulong local_bytes = device_local_mem_bytes(dev);
    size_t per_item = local_bytes / (sizeof(cl_uint) * s->group_size);
    per_item = per_item > 2 ? per_item - 2 : 1;
    s->top_max_per_item = per_item < TOP_MAX_PER_ITEM ? per_item : TOP_MAX_PER_ITEM;
    if (s->top_max_per_item < VALUES_PER_ITEM)
        s->top_max_per_item = VALUES_PER_ITEM; /* what the lower levels need anyway */

    size_t sizes[MAX_LEVELS];
    int top = level_sizes(s, max_m, sizes);
    bool ok = true;
    for (int k = 1; k <= top && ok; k++) {
        char name[32];
        snprintf(name, sizeof name, "scan_level_%d", k);
        s->levels[k] = device_buffer(dev, name, CL_MEM_READ_WRITE, sizes[k] * sizeof(cl_uint),
                                     NULL, err);
        ok = s->levels[k] != NULL;
    }
    cl_uint zero = 0;
    if (ok)
        s->zero = device_buffer(dev, "scan_zero", CL_MEM_READ_ONLY, sizeof zero, &zero, err);
    if (s->zero)
        s->total = device_buffer(dev, "scan_total", CL_MEM_READ_WRITE, sizeof zero, NULL, err);
    if (!s->total) {
        exclusive_scan_destroy(s);
        return NULL;
    }
    return s;
}

ExclusiveScan *exclusive_scan_create(Device *dev, size_t max_m, Error *err)
{
    return exclusive_scan_create_sized(dev, max_m, 0, err);
}

/* Launches groups work-groups; adds the device time when profiling. */
static void launch(ExclusiveScan *s, cl_kernel kernel, size_t groups, double *profile_ms)
{
    double ms = 0.0;
    device_run(s->dev, kernel, groups * s->group_size, s->group_size, profile_ms ? &ms : NULL);
    if (profile_ms)
        *profile_ms += ms;
}

/* Exclusive scan of level k in tiles of per_item x group values, plus the offsets of level k + 1
 * (already scanned), or {0} at the top (one work-group). Every level's last tile writes the same
 * grand total into total[0]. */
static void scan_level(ExclusiveScan *s, const size_t *sizes, int k, int top, cl_mem total,
                       double *profile_ms)
{
    size_t group = s->group_size;
    cl_uint m = (cl_uint)sizes[k];
    cl_uint per_item = k == top ? (cl_uint)div_up(sizes[k], group) : VALUES_PER_ITEM;
    cl_mem offsets = k == top ? s->zero : s->levels[k + 1];
    cl_kernel kernel = s->exclusive_values;
    KERNEL_ARGS(kernel, 0, KARG(s->levels[k]), KARG(m), KARG(per_item), KARG(offsets),
                KARG(total), KARG_LOCAL(per_item * group * sizeof(cl_uint)),
                KARG_LOCAL(2 * group * sizeof(cl_uint)));
    launch(s, kernel, k == top ? 1 : sizes[k + 1], profile_ms);
}

/* Sums level k per tile into level k + 1. */
static void reduce_level(ExclusiveScan *s, const size_t *sizes, int k, double *profile_ms)
{
    cl_uint m = (cl_uint)sizes[k], per_item = VALUES_PER_ITEM;
    KERNEL_ARGS(s->reduce_values, 0, KARG(s->levels[k]), KARG(m), KARG(per_item),
                KARG(s->levels[k + 1]), KARG_LOCAL(s->group_size * sizeof(cl_uint)));
    launch(s, s->reduce_values, sizes[k + 1], profile_ms);
}

void exclusive_scan_enqueue_total(ExclusiveScan *s, cl_mem values, uint32_t m, cl_mem total,
                                  double *profile_ms)
{
    if (m > s->max_m)
        die("exclusive_scan: %u values, above the %zu it was created for", m, s->max_m);
    if (m == 0)
        return;
    size_t sizes[MAX_LEVELS];
    int top = level_sizes(s, m, sizes);
    s->levels[0] = values;
    for (int k = 0; k < top; k++)
        reduce_level(s, sizes, k, profile_ms);
    for (int k = top; k >= 0; k--)
        scan_level(s, sizes, k, top, total, profile_ms);
    s->levels[0] = NULL;
}

void exclusive_scan_enqueue(ExclusiveScan *s, cl_mem values, uint32_t m, double *profile_ms)
{
    exclusive_scan_enqueue_total(s, values, m, s->total, profile_ms);
}

int exclusive_scan_launches(const ExclusiveScan *s, uint32_t m)
{
    size_t sizes[MAX_LEVELS];
    return m == 0 ? 0 : 2 * level_sizes(s, m, sizes) + 1;
}

void exclusive_scan_destroy(ExclusiveScan *s)
{
    if (!s)
        return;
    cl_kernel kernels[] = {s->reduce_values, s->exclusive_values};
    for (size_t i = 0; i < sizeof kernels / sizeof kernels[0]; i++)
        if (kernels[i])
            device_release_kernel(kernels[i]);
    cl_mem buffers[] = {s->zero, s->total};
    for (size_t i = 0; i < sizeof buffers / sizeof buffers[0]; i++)
        if (buffers[i])
            device_release_buffer(buffers[i]);
    for (int k = 1; k < MAX_LEVELS; k++)
        if (s->levels[k])
            device_release_buffer(s->levels[k]);
    free(s);
}
