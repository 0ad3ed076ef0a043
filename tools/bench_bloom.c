// SPDX-License-Identifier: MIT
/* bench_bloom: the time of --bloom (host/render/bloom.c) on a 4K film, 3840 x 2160, at the default
 * radius (1% of the diagonal, 44 pixels) or --radius R.
 *
 *   build/tools/bench_bloom [--device SPEC] [--radius R] [--reps N]
 *
 * Prints the mean over N calls (default 5, after one warm-up) of the two kernels' device time
 * (profiling events) and of the whole call: upload, kernels, read-back, as render_cmd pays it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "device/device.h"
#include "render/bloom.h"

enum { WIDTH = 3840, HEIGHT = 2160 };

static void usage(void)
{
    fprintf(stderr, "usage: bench_bloom [--device gpu|cpu|P:D] [--radius R] [--reps N]\n");
    exit(2);
}

int main(int argc, char **argv)
{
    const char *device = NULL;
    float radius = 0.0f;
    int reps = 5;
    for (int i = 1; i < argc; i++) {
        if (i + 1 >= argc)
            usage();
        if (!strcmp(argv[i], "--device"))
            device = argv[++i];
        else if (!strcmp(argv[i], "--radius"))
            radius = strtof(argv[++i], NULL);
        else if (!strcmp(argv[i], "--reps"))
            reps = atoi(argv[++i]);
        else
            usage();
    }
    if (reps < 1)
        usage();
    Device dev;
    Error err = {0};
    if (!device_open(&dev, device, &err) ||
        !device_build(&dev, PROGRAM_FEATURES_ALL, NULL, NULL, &err))
        die("%s", err.message);
    size_t values = (size_t)WIDTH * HEIGHT * 3;
    float *film = malloc(values * sizeof(float)), *work = malloc(values * sizeof(float));
    if (!film || !work)
        die("out of memory");
    unsigned state = 1u; /* mostly dark, a few percent above the threshold */
    for (size_t i = 0; i < values; i++) {
        state = state * 1664525u + 1013904223u;
        float u = (float)(state >> 8) / 16777216.0f;
        film[i] = 8.0f * u * u * u * u;
    }
    double kernel_ms = 0.0, call_ms = 0.0;
    for (int r = -1; r < reps; r++) { /* r = -1: warm-up, not counted */
        memcpy(work, film, values * sizeof(float));
        double kernels = 0.0, start = seconds_now();
        if (!bloom_apply_profiled(&dev, work, WIDTH, HEIGHT, 0.5f, radius, &kernels, &err))
            die("%s", err.message);
        double elapsed = 1e3 * (seconds_now() - start);
        if (r >= 0)
            kernel_ms += kernels, call_ms += elapsed;
    }
    printf("bloom %dx%d, radius %.1f px, on %s (%s): kernels %.2f ms, whole call %.2f ms "
           "(mean of %d)\n",
           WIDTH, HEIGHT, radius > 0.0f ? radius : bloom_default_radius(WIDTH, HEIGHT), dev.name,
           dev.platform_name, kernel_ms / reps, call_ms / reps, reps);
    free(film), free(work);
    device_close(&dev);
    return 0;
}
