/* SPDX-License-Identifier: MIT */
/* render_loop.h: the path-traced render of `pt render`: window after window until every sample
 * is done or a stop signal arrives (app/stop_signals.h), keeping what is done. */
#ifndef PT_RENDER_LOOP_H
#define PT_RENDER_LOOP_H

#include <stdbool.h>

#include "app/render_output.h"
#include "render/session.h"
#include "render/wavefront.h"

typedef enum {
    PROGRESS_NONE,     /* --quiet, or stderr is not a terminal */
    PROGRESS_TERMINAL, /* one line, rewritten in place */
    PROGRESS_LINES,    /* --progress: a line after the first window, then at most one a second,
                        * and one at the end: "pt: progress: D/N spp (P%), S s" */
} ProgressStyle;

/* Renders into images->rgb (the mean of the samples so far per pixel) and the film's layers
 * (render_images_read_film); stats->spp_done says how many. */
bool render_loop_run(Session *session, const RenderSettings *settings, ProgressStyle progress,
                     RenderImages *images, RenderStats *stats, Error *err);

#endif
