/* SPDX-License-Identifier: MIT */
/* render_loop.h: the path-traced render of `pt render`: window after window until every sample
 * is done, a stop signal arrives (app/stop_signals.h) or the time limit passes, keeping what is
 * done. */
#ifndef PT_RENDER_LOOP_H
#define PT_RENDER_LOOP_H

#include <stdbool.h>
#include <stdint.h>

#include "app/render_output.h"
#include "render/render_stop.h"
#include "render/session.h"
#include "render/wavefront.h"

typedef enum {
    PROGRESS_NONE,     /* --quiet */
    PROGRESS_TERMINAL, /* stderr is a terminal: one line, rewritten in place */
    PROGRESS_LINES,    /* --progress: a line after the first window, then at most one a second,
                        * and one at the end: "pt: progress: D/N spp (P%), S s" */
    PROGRESS_LOG,      /* stderr is not a terminal (a CI log, a pipe): the same lines, at most
                        * one every LOG_UPDATE_SECONDS (render_loop.c) */
} ProgressStyle;

/* The progress style for the command line: --quiet none, --progress lines every second, else
 * the terminal line when stderr is one and log lines when it is not. */
ProgressStyle render_loop_progress_style(bool quiet, bool progress_lines, bool stderr_is_terminal);

/* Seconds between two progress lines of a style, and one line: spp_done of spp, done of total
 * camera paths, elapsed seconds (render_units.c shows its progress the same way). */
double render_loop_update_interval(ProgressStyle style);
void render_loop_print_progress(ProgressStyle style, int spp_done, int spp, uint64_t done,
                                uint64_t total, double elapsed);

typedef struct {
    ProgressStyle progress;
    double time_limit; /* --time-limit: seconds of rendering (loading and the kernel build not
                        * counted) after which the loop stops at the next whole sample; 0 = none */
} RenderLoopDesc;

/* Renders into images->rgb (the mean of the samples so far per pixel) and the film's layers
 * (render_images_read_film); stats->spp_done says how many and *stop why the loop ended. */
bool render_loop_run(Session *session, const RenderSettings *settings, const RenderLoopDesc *desc,
                     RenderImages *images, RenderStats *stats, RenderStop *stop, Error *err);

#endif
