// SPDX-License-Identifier: MIT
/* bench_scan: throughput of the stream compaction (host/parallel/compact.c) against the device's own copy
 * bandwidth, for n = 2^16 .. 2^24 flags at densities 0.5 and 0.9.
 *
 *   build/tools/bench_scan [--device SPEC] [--group-size G] [--min-log2 16] [--max-log2 24]
 *                          [--reps R] [--out FILE.csv]
 *
 * Times are device times from profiling events (the sum of the compaction's kernels; the copy's
 * one command), the mean over R runs after two warm-up runs. Effective bytes are what a
 * compaction must move at least: 4n flags read, 4 count indices written, and the per-tile sums
 * written and read once; copy bytes count the read and the write. Every configuration is checked
 * against a serial reference once. The CSV goes to bench/results/<device>/scan.csv by default. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "parallel/compact.h"
#include "device/device.h"

typedef struct {
    const char *device;
    const char *out;
    size_t group_size;
    int min_log2, max_log2, reps;
} Options;

static void usage(void)
{
    fprintf(stderr, "usage: bench_scan [--device gpu|cpu|P:D] [--group-size G] [--min-log2 K] "
                    "[--max-log2 K] [--reps R] [--out FILE.csv]\n");
    exit(2);
}

static Options parse_options(int argc, char **argv)
{
    Options o = {.device = NULL, .out = NULL, .group_size = 0, .min_log2 = 16, .max_log2 = 24,
                 .reps = 0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (i + 1 >= argc)
            usage();
        if (!strcmp(a, "--device"))
            o.device = argv[++i];
        else if (!strcmp(a, "--out"))
            o.out = argv[++i];
        else if (!strcmp(a, "--group-size"))
            o.group_size = (size_t)atol(argv[++i]);
        else if (!strcmp(a, "--min-log2"))
            o.min_log2 = atoi(argv[++i]);
        else if (!strcmp(a, "--max-log2"))
            o.max_log2 = atoi(argv[++i]);
        else if (!strcmp(a, "--reps"))
            o.reps = atoi(argv[++i]);
        else
            usage();
    }
    if (o.min_log2 < 0 || o.max_log2 > 31 || o.min_log2 > o.max_log2 || o.reps < 0)
        usage();
    return o;
}

static void random_flags(uint32_t *flags, uint32_t n, double density, uint64_t seed)
{
    uint64_t state = seed | 1;
    uint32_t threshold = (uint32_t)(density * 4294967295.0);
    for (uint32_t i = 0; i < n; i++) {
        state ^= state >> 12, state ^= state << 25, state ^= state >> 27;
        uint32_t r = (uint32_t)((state * 0x2545f4914f6cdd1dull) >> 32);
        flags[i] = r < threshold ? 1u + (r & 7u) : 0u;
    }
}

/* Compacts once and compares with the serial result; returns the count. */
static uint32_t check_once(Device *dev, Compactor *c, cl_mem flags, cl_mem indices,
                           const uint32_t *host_flags, uint32_t *readback, uint32_t n)
{
    uint32_t count = compactor_run(c, flags, indices, n);
    device_read(dev, indices, 0, (size_t)count * sizeof(uint32_t), readback);
    uint32_t expected = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (host_flags[i] == 0)
            continue;
        if (expected >= count || readback[expected] != i)
            die("bench_scan: wrong compaction at n %u, output %u", n, expected);
        expected++;
    }
    if (expected != count)
        die("bench_scan: count %u, expected %u at n %u", count, expected, n);
    return count;
}

int main(int argc, char **argv)
{
    Options o = parse_options(argc, argv);
    Device dev;
    Error err = {0};
    if (!device_open(&dev, o.device, &err) ||
        !device_build(&dev, PROGRAM_FEATURES_ALL, NULL, NULL, &err))
        die("%s", err.message);
    size_t max_n = (size_t)1 << o.max_log2;
    Compactor *c = compactor_create_sized(&dev, max_n, o.group_size, &err);
    cl_mem flags = device_buffer(&dev, "flags", CL_MEM_READ_WRITE, max_n * 4, NULL, &err);
    cl_mem indices = device_buffer(&dev, "indices", CL_MEM_READ_WRITE, max_n * 4, NULL, &err);
    uint32_t *host_flags = malloc(max_n * 4), *readback = malloc(max_n * 4);
    if (!c || !flags || !indices || !host_flags || !readback)
        die("%s", err.message[0] ? err.message : "out of memory");
    size_t group = compactor_group_size(c);

    char path[1024];
    FILE *csv = bench_open_results_csv(dev.name, o.out, "scan.csv", path, sizeof path);
    fprintf(csv, "device,n,density,count,group_size,launches,reps,scan_ms,scan_gbps,copy_ms,"
                 "copy_gbps,ratio\n");
    printf("device %s (%s), work-group size %zu\n", dev.name, dev.platform_name, group);
    printf("%10s %7s %10s %4s %9s %9s %9s %9s %6s\n", "n", "density", "count", "lnch", "scan ms",
           "scan GB/s", "copy ms", "copy GB/s", "ratio");

    const double densities[] = {0.5, 0.9};
    for (int log2n = o.min_log2; log2n <= o.max_log2; log2n++) {
        uint32_t n = (uint32_t)1 << log2n;
        /* Enough repetitions for about 64M flags in all, at least 5. */
        int reps = o.reps ? o.reps : (int)(((size_t)1 << 26) / n);
        if (reps < 5)
            reps = 5;
        double copy = bench_copy_ms(&dev, flags, indices, (size_t)n * 4, reps);
        double copy_gbps = 2.0 * 4.0 * n / (copy * 1e6);
        for (int d = 0; d < 2; d++) {
            random_flags(host_flags, n, densities[d], 12345 + (uint64_t)log2n);
            device_write(&dev, flags, 0, (size_t)n * 4, host_flags);
            uint32_t count = check_once(&dev, c, flags, indices, host_flags, readback, n);
            double total_ms = 0.0;
            compactor_run(c, flags, indices, n); /* warm-up (the check was the first) */
            compactor_set_profile(c, &total_ms);
            for (int r = 0; r < reps; r++)
                compactor_run(c, flags, indices, n);
            compactor_set_profile(c, NULL);
            double ms = total_ms / reps;
            size_t tiles = (n + 32 * group - 1) / (32 * group);
            double bytes = 4.0 * n + 4.0 * count + 8.0 * (double)tiles;
            double gbps = bytes / (ms * 1e6);
            int launches = compactor_launches(c, n);
            printf("%10u %7.2f %10u %4d %9.4f %9.2f %9.4f %9.2f %6.3f\n", n, densities[d], count,
                   launches, ms, gbps, copy, copy_gbps, gbps / copy_gbps);
            fprintf(csv, "\"%s\",%u,%.2f,%u,%zu,%d,%d,%.5f,%.3f,%.5f,%.3f,%.4f\n", dev.name, n,
                    densities[d], count, group, launches, reps, ms, gbps, copy, copy_gbps,
                    gbps / copy_gbps);
        }
    }
    fclose(csv);
    printf("wrote %s\n", path);
    compactor_destroy(c);
    CL_CHECK(clReleaseMemObject(flags));
    CL_CHECK(clReleaseMemObject(indices));
    free(host_flags), free(readback);
    device_close(&dev);
    return 0;
}
