/* SPDX-License-Identifier: MIT */
/* viewer_stats.h: what 'pt view' measured, for the one-line summary it prints at exit: the time of
 * every frame (mean, median, 95th percentile, maximum) and the camera paths (samples) traced, per
 * second of frames and per second of sampling. The first frame is reported on its own: it holds
 * the kernels' first launch. */
#ifndef PT_VIEWER_STATS_H
#define PT_VIEWER_STATS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

typedef struct {
    int frames;
    double first_frame_ms;
    double *frame_ms;            /* the frames after the first */
    size_t frame_ms_capacity;
    double frames_seconds;       /* all frames, the first included */
    uint64_t paths;              /* camera paths traced (one per pixel sample) */
    double sampling_seconds, sampling_ms_max;
} ViewerStats;

void viewer_stats_add_frame(ViewerStats *s, double ms);
void viewer_stats_add_sampling(ViewerStats *s, uint64_t paths, double seconds);

/* "pt: view: N frames, N spp; first frame X ms, then frame time mean X ms, median X ms, p95 X ms,
 * max X ms; longest sampling step X ms; X Msamples/s (X while sampling) on DEVICE" (tests and
 * tools parse it: append, don't reorder). */
void viewer_stats_print(const ViewerStats *s, int spp, const char *device, FILE *out);

void viewer_stats_destroy(ViewerStats *s);

#endif
