/* SPDX-License-Identifier: MIT */
/* render_stop.h: why a render ended, shared by the one-device loop (app/render_loop.h) and the
 * unit render (dist/render_units.h), so that dist/ need not reach up into app/ for it. */
#ifndef PT_RENDER_STOP_H
#define PT_RENDER_STOP_H

/* Anything but RENDER_COMPLETE leaves a partial image (fewer spp than asked) that the EXR header
 * marks partial. */
typedef enum {
    RENDER_COMPLETE,              /* every sample asked for */
    RENDER_STOPPED_BY_SIGNAL,     /* SIGINT, SIGTERM or SIGHUP (app/stop_signals.h says which) */
    RENDER_STOPPED_BY_TIME_LIMIT, /* the time limit passed; the image holds whole samples */
} RenderStop;

#endif
