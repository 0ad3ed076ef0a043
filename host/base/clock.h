/* SPDX-License-Identifier: MIT */
/* clock.h: a monotonic wall clock for timings and progress (never for correctness). */
#ifndef PT_CLOCK_H
#define PT_CLOCK_H

#include <time.h>

/* Seconds since an arbitrary fixed point; only differences mean anything. */
static inline double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#endif
