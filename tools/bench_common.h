/* SPDX-License-Identifier: MIT */
/* bench_common.h: what the benchmark tools share: the device name made safe as a folder name
 * (results go to bench/results/<device>/NAME.csv), opening that CSV, and the copy bandwidth that
 * memory-bound stages are compared with. Header-only (static functions) so that each tools/NAME.c stays one
 * translation unit. */
#ifndef PT_BENCH_COMMON_H
#define PT_BENCH_COMMON_H

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "device/device.h"
#include "base/error.h"
#include "base/fs.h"

/* "NVIDIA H100 80GB HBM3" -> "NVIDIA-H100-80GB-HBM3". */
static inline void bench_folder_name(const char *device_name, char *out, size_t size)
{
    size_t k = 0;
    for (const char *p = device_name; *p && k + 1 < size; p++) {
        bool keep = (*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') ||
                    (*p >= '0' && *p <= '9') || *p == '.' || *p == '_';
        if (keep)
            out[k++] = *p;
        else if (k > 0 && out[k - 1] != '-')
            out[k++] = '-';
    }
    while (k > 0 && out[k - 1] == '-')
        k--;
    out[k] = '\0';
}

/* Opens path for writing after creating its folders (mkdir -p); dies when it cannot. */
static inline FILE *bench_open_csv(const char *path)
{
    if (!fs_make_parent_dirs(path))
        die("cannot create the folder of %s: %s", path, strerror(errno));
    FILE *csv = fopen(path, "w");
    if (!csv)
        die("cannot write %s: %s", path, strerror(errno));
    return csv;
}

/* The tool's CSV: `out` when given, else bench/results/<device>/<name> (its path into path[size]);
 * folders are created. */
static inline FILE *bench_open_results_csv(const char *device_name, const char *out, const char *name,
                                           char *path, size_t size)
{
    char folder[300];
    bench_folder_name(device_name, folder, sizeof folder);
    if (out)
        snprintf(path, size, "%s", out);
    else
        snprintf(path, size, "bench/results/%s/%s", folder, name);
    return bench_open_csv(path);
}

/* Mean device time of one copy of bytes from src to dst over reps copies, after one warm-up: the
 * scale a memory-bound stage is measured against. */
static inline double bench_copy_ms(Device *dev, cl_mem src, cl_mem dst, size_t bytes, int reps)
{
    double total = 0.0;
    for (int r = -1; r < reps; r++) {
        cl_event event;
        CL_CHECK(clEnqueueCopyBuffer(dev->queue, src, dst, 0, 0, bytes, 0, NULL, &event));
        double ms = device_event_ms(event);
        if (r >= 0)
            total += ms;
    }
    return total / reps;
}

#endif
