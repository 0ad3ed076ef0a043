/* SPDX-License-Identifier: MIT */
/* exclusive_scan.h: in-place exclusive prefix sum of a device array of uints, driving the
 * scan_reduce_values and scan_exclusive_values kernels of cl/parallel/scan.cl level by level:
 *
 *     exclusive_scan_enqueue(scan, counts, m, NULL);   counts[i] = sum of counts[0..i)
 *
 * Up to 8192 values (with work-groups of 256 and room in local memory) it is one launch; above,
 * the values are reduced per tile of 8 x 256 into a level above, until one work-group scans the
 * top level whole, and the levels are then scanned top down (3 launches up to 2^24 values). An
 * ExclusiveScan owns the kernels and the buffers of its upper levels, sized for max_m values. It
 * is not safe to use one from two threads at once. */
#ifndef PT_EXCLUSIVE_SCAN_H
#define PT_EXCLUSIVE_SCAN_H

#include <stddef.h>
#include <stdint.h>

#include "device/device.h"

typedef struct ExclusiveScan ExclusiveScan;

/* NULL with err set when a level buffer cannot be allocated or max_m exceeds UINT32_MAX
 * (ERR_TOO_LARGE). */
ExclusiveScan *exclusive_scan_create(Device *dev, size_t max_m, Error *err);

/* The same with work-groups of at most group_size (lowered to a power of two the device and the
 * kernels accept; 0 = 256): the compactor scans its tile counts with its own work-group size. */
ExclusiveScan *exclusive_scan_create_sized(Device *dev, size_t max_m, size_t group_size,
                                           Error *err);

/* Enqueues the scan of values[0..m) in place, m <= max_m, without waiting unless profile_ms is not
 * NULL: then it waits for each launch and adds the launches' device time to *profile_ms. */
void exclusive_scan_enqueue(ExclusiveScan *s, cl_mem values, uint32_t m, double *profile_ms);

/* The same, and the sum of all m values into total[0] (a device buffer of at least one uint);
 * nothing is written for m = 0. */
void exclusive_scan_enqueue_total(ExclusiveScan *s, cl_mem values, uint32_t m, cl_mem total,
                                  double *profile_ms);

/* Kernel launches the scan of m values takes (0 for m = 0). */
int exclusive_scan_launches(const ExclusiveScan *s, uint32_t m);

void exclusive_scan_destroy(ExclusiveScan *s);

/* The largest power of two <= request that the device and each of the kernels accept as a
 * work-group size: what the work-group scans of cl/parallel/scan.cl need. */
size_t pow2_group_size(Device *dev, const cl_kernel *kernels, size_t num_kernels, size_t request);

#endif
