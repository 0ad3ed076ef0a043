// SPDX-License-Identifier: MIT
#include "viewer/stats.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"

void viewer_stats_add_frame(ViewerStats *s, double ms)
{
    s->frames_seconds += 1e-3 * ms;
    if (s->frames++ == 0) {
        s->first_frame_ms = ms;
        return;
    }
    size_t n = (size_t)s->frames - 1;
    if (n > s->frame_ms_capacity) {
        s->frame_ms_capacity = s->frame_ms_capacity ? 2 * s->frame_ms_capacity : 1024;
        s->frame_ms = realloc(s->frame_ms, s->frame_ms_capacity * sizeof *s->frame_ms);
        if (!s->frame_ms)
            die("out of memory for %zu frame times", s->frame_ms_capacity);
    }
    s->frame_ms[n - 1] = ms;
}

void viewer_stats_add_sampling(ViewerStats *s, uint64_t paths, double seconds)
{
    s->paths += paths;
    s->sampling_seconds += seconds;
    s->sampling_ms_max = fmax(s->sampling_ms_max, 1e3 * seconds);
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The q-quantile of sorted[0..n) by the nearest rank (a measured frame, never an interpolation). */
static double quantile(const double *sorted, size_t n, double q)
{
    size_t rank = (size_t)ceil(q * (double)n);
    return sorted[rank > 0 ? rank - 1 : 0];
}

void viewer_stats_print(const ViewerStats *s, int spp, const char *device, FILE *out)
{
    size_t n = s->frames > 1 ? (size_t)s->frames - 1 : 0;
    double mean = 0.0, median = 0.0, p95 = 0.0, max = 0.0;
    if (n > 0) {
        double *sorted = malloc(n * sizeof *sorted);
        if (!sorted)
            die("out of memory for %zu frame times", n);
        memcpy(sorted, s->frame_ms, n * sizeof *sorted);
        qsort(sorted, n, sizeof *sorted, compare_doubles);
        for (size_t i = 0; i < n; i++)
            mean += sorted[i] / (double)n;
        median = quantile(sorted, n, 0.5), p95 = quantile(sorted, n, 0.95), max = sorted[n - 1];
        free(sorted);
    }
    double per_frame_second = s->frames_seconds > 0.0 ? (double)s->paths / s->frames_seconds : 0.0;
    double per_sampling_second =
        s->sampling_seconds > 0.0 ? (double)s->paths / s->sampling_seconds : 0.0;
    fprintf(out,
            "pt: view: %d frames, %d spp; first frame %.0f ms, then frame time mean %.1f ms, "
            "median %.1f ms, p95 %.1f ms, max %.1f ms; longest sampling step %.1f ms; "
            "%.3f Msamples/s (%.3f while sampling) on %s\n",
            s->frames, spp, s->first_frame_ms, mean, median, p95, max, s->sampling_ms_max,
            1e-6 * per_frame_second, 1e-6 * per_sampling_second, device);
}

void viewer_stats_destroy(ViewerStats *s)
{
    free(s->frame_ms);
    memset(s, 0, sizeof *s);
}
