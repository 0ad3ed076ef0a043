/* SPDX-License-Identifier: MIT */
/* bench.h: `pt bench`: throughput of the wavefront on one scene and device. */
#ifndef PT_BENCH_H
#define PT_BENCH_H

#include "app/cli.h"

int command_bench(const Options *o);

#endif
