/* SPDX-License-Identifier: MIT */
/* xorshift.h: xorshift64* (Vigna 2016), the reproducible random numbers of the tests and benchmark
 * tools: a seed in a failure message replays the case. Header-only; tools reach it through -Itests.
 * tests/test_scan.c holds an older copy and can include this instead. */
#ifndef PT_XORSHIFT_H
#define PT_XORSHIFT_H

#include <stdint.h>

/* The next 32 random bits; *state must not be 0 (seed with seed | 1). */
static inline uint32_t xorshift_next(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    return (uint32_t)((*state * 0x2545f4914f6cdd1dull) >> 32);
}

#endif
