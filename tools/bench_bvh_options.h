/* SPDX-License-Identifier: MIT */
/* bench_bvh_options.h: tools/bench_bvh's command line (usage in bench_bvh.c). Header-only (static
 * functions), like bench_common.h, so that tools/bench_bvh.c stays one translation unit. */
#ifndef PT_BENCH_BVH_OPTIONS_H
#define PT_BENCH_BVH_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    const char *device, *assets, *out;
    int spp, reps;
    uint32_t max_triangles;
    bool rows;        /* --order rows: pixels in scanline order instead of 4x4 tiles */
    bool count_steps; /* --count-steps: node visits and triangle tests per ray instead of timings */
} Options;

static void usage(void)
{
    fprintf(stderr, "usage: bench_bvh [--device gpu|cpu|P:D] [--spp N] [--reps R] [--assets DIR] "
                    "[--max-triangles N] [--out DIR] [--order tiles|rows]\n"
                    "                 [--count-steps]\n");
    exit(2);
}

static Options parse_options(int argc, char **argv)
{
    Options o = {NULL, "../shared/assets", "bench/results", 16, 3, 2000000, false, false};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--count-steps")) {
            o.count_steps = true;
            continue;
        }
        if (i + 1 >= argc)
            usage();
        const char *key = argv[i], *value = argv[++i];
        if (!strcmp(key, "--device"))
            o.device = value;
        else if (!strcmp(key, "--assets"))
            o.assets = value;
        else if (!strcmp(key, "--out"))
            o.out = value;
        else if (!strcmp(key, "--spp"))
            o.spp = atoi(value);
        else if (!strcmp(key, "--reps"))
            o.reps = atoi(value);
        else if (!strcmp(key, "--max-triangles"))
            o.max_triangles = (uint32_t)strtoul(value, NULL, 10);
        else if (!strcmp(key, "--order") && (!strcmp(value, "tiles") || !strcmp(value, "rows")))
            o.rows = !strcmp(value, "rows");
        else
            usage();
    }
    if (o.spp < 1 || o.reps < 1)
        usage();
    return o;
}

#endif
