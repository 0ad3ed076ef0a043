/* SPDX-License-Identifier: MIT */
/* parallel_for.h: a loop over [0, count) split into contiguous chunks run on the host's cores
 * (POSIX threads), for the host's large linear passes (an environment map's tables). The chunks
 * are fixed by count and the thread count only, and each index is handled by exactly one call, so
 * a body that writes only its own indices gives the same result on any machine. */
#ifndef PT_PARALLEL_FOR_H
#define PT_PARALLEL_FOR_H

#include <stddef.h>

/* Calls body(ctx, begin, end) on disjoint ranges covering [0, count), on up to 16 threads (one if
 * count < min_per_thread * 2). Returns when all are done. A thread that cannot be started has its
 * range run by the caller. */
void parallel_for(size_t count, size_t min_per_thread, void (*body)(void *ctx, size_t begin, size_t end),
                  void *ctx);

#endif
