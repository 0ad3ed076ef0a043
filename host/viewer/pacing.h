/* SPDX-License-Identifier: MIT */
/* viewer_pacing.h: how much 'pt view' traces per frame, whatever the device's speed. */
#ifndef PT_VIEWER_PACING_H
#define PT_VIEWER_PACING_H

#include <stdint.h>

#define FRAME_BUDGET_S 0.040   /* a frame: sampling, then showing the film */
#define WINDOWS_PER_FRAME 3    /* a window cannot be interrupted: keep it a fraction of a frame */
#define VIEWER_MIN_WINDOW 1024u
#define VIEWER_MAX_WINDOW (1u << 24)

/* Samples per window for a measured rate (paths per second): the largest power of two, within
 * [VIEWER_MIN_WINDOW, VIEWER_MAX_WINDOW], that takes at most FRAME_BUDGET_S / WINDOWS_PER_FRAME
 * at that rate. The window, not the pool, is what wavefront_advance cannot split, so this bounds
 * how long input can wait. */
uint32_t viewer_window_for_rate(double paths_per_second);

#endif
