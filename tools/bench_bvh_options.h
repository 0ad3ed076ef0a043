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

/* The order of the primary rays (and so of their bounces) in the batch: 4x4-pixel tiles, each
 * pixel's samples together (as tinybvh's speed test); scanlines; or shuffled, so that no two
 * neighbouring rays share a pixel (what packet tracers lose without coherence). */
typedef enum { ORDER_TILES, ORDER_ROWS, ORDER_RANDOM } RayOrder;

typedef struct {
    const char *device, *assets, *out;
    const char *write_rays; /* --write-rays DIR: each mesh's triangles and rays, for
                               tools/bench_bvh_mitsuba.py to trace the same rays */
    int spp, reps;
    uint32_t max_triangles;
    RayOrder order;   /* --order: 4x4-pixel tiles (default), scanlines, or shuffled */
    bool count_steps; /* --count-steps: node visits and triangle tests per ray instead of timings */
} Options;

static void usage(void)
{
    fprintf(stderr, "usage: bench_bvh [--device gpu|cpu|P:D] [--spp N] [--reps R] [--assets DIR] "
                    "[--max-triangles N] [--out DIR] [--order tiles|rows|random]\n"
                    "                 [--count-steps] [--write-rays DIR]\n");
    exit(2);
}

static Options parse_options(int argc, char **argv)
{
    Options o = {NULL, "../shared/assets", "bench/results", NULL, 16, 3, 2000000, ORDER_TILES, false};
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
        else if (!strcmp(key, "--write-rays"))
            o.write_rays = value;
        else if (!strcmp(key, "--spp"))
            o.spp = atoi(value);
        else if (!strcmp(key, "--reps"))
            o.reps = atoi(value);
        else if (!strcmp(key, "--max-triangles"))
            o.max_triangles = (uint32_t)strtoul(value, NULL, 10);
        else if (!strcmp(key, "--order") && !strcmp(value, "tiles"))
            o.order = ORDER_TILES;
        else if (!strcmp(key, "--order") && !strcmp(value, "rows"))
            o.order = ORDER_ROWS;
        else if (!strcmp(key, "--order") && !strcmp(value, "random"))
            o.order = ORDER_RANDOM;
        else
            usage();
    }
    if (o.spp < 1 || o.reps < 1)
        usage();
    return o;
}

#endif
