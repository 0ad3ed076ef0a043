/* SPDX-License-Identifier: MIT */
/* compact.h: stream compaction of alive flags into a dense, ascending index list, on the device
 * (kernels in cl/parallel/scan.cl). The integrator runs it once per bounce over the path slots:
 *
 *     uint32_t live = compactor_run(compactor, alive_flags, active_indices, num_slots);
 *
 * flags: n uints, nonzero = alive. indices: receives the i with flags[i] != 0, in increasing order.
 * A Compactor owns its kernels and scratch buffers (a bit mask, the tile sums and an ExclusiveScan
 * for them, sized for max_n), so it serves any n <= max_n, as often as wanted, on the device's queue.
 * It is not safe to use one Compactor from two threads at once. */
#ifndef PT_COMPACT_H
#define PT_COMPACT_H

#include <stddef.h>
#include <stdint.h>

#include "device/device.h"

typedef struct Compactor Compactor;

/* Builds the compactor for up to max_n flags with the work-group size chosen for the device
 * (compactor_group_size tells which). NULL with err set when a buffer cannot be allocated or
 * max_n exceeds UINT32_MAX (ERR_TOO_LARGE). */
Compactor *compactor_create(Device *dev, size_t max_n, Error *err);

/* The same with an explicit work-group size: a power of two, at most what the device and the
 * kernels allow (the request is lowered to that); 0 = the device's default. For tests and tuning. */
Compactor *compactor_create_sized(Device *dev, size_t max_n, size_t group_size, Error *err);

/* Enqueues the compaction of flags[0..n) into indices[] and writes the count into count_buf[0] (a
 * device buffer of at least one uint) without waiting. n <= max_n; n = 0 writes a count of 0. */
void compactor_enqueue(Compactor *c, cl_mem flags, cl_mem indices, cl_mem count_buf, uint32_t n);

/* Enqueues the complement of the last compaction: the i < n with flags[i] == 0, in increasing
 * order, into indices[] (n - count of them). One launch: it reuses that compaction's bit mask and
 * tile sums, so the flags must not have changed since. Nothing when the last n was 0. */
void compactor_enqueue_free(Compactor *c, cl_mem indices);

/* compactor_enqueue into the compactor's own count buffer, then a blocking read of the count. */
uint32_t compactor_run(Compactor *c, cl_mem flags, cl_mem indices, uint32_t n);

/* When ms_accumulator is not NULL, each later compaction adds the device time of its kernels (from
 * profiling events) to *ms_accumulator and compactor_enqueue waits for them to finish. NULL turns
 * this off again. */
void compactor_set_profile(Compactor *c, double *ms_accumulator);

/* The work-group size in use; a flag tile is 32 times that many slots. */
size_t compactor_group_size(const Compactor *c);

/* Kernel launches the compaction of n flags takes: 2 up to 256 group_size^2 flags (2^24 for 256),
 * then 2 plus those of the exclusive scan of the n / (32 group_size) tile counts. */
int compactor_launches(const Compactor *c, uint32_t n);

void compactor_destroy(Compactor *c);

#endif
