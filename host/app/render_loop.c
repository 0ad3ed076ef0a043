// SPDX-License-Identifier: MIT
#include "app/render_loop.h"

#include <stdio.h>

#include "app/stop_signals.h"
#include "base/clock.h"

/* Seconds between progress updates: often enough to see it move, rare enough to cost nothing. */
#define TERMINAL_UPDATE_SECONDS 0.25
#define LINE_UPDATE_SECONDS 1.0

static void print_progress(ProgressStyle style, int spp_done, int spp, uint64_t done,
                           uint64_t total, double elapsed)
{
    double fraction = total ? (double)done / (double)total : 1.0;
    if (style == PROGRESS_LINES) {
        fprintf(stderr, "pt: progress: %d/%d spp (%.1f%%), %.1f s\n", spp_done, spp,
                100.0 * fraction, elapsed);
    } else {
        double rate = (double)done / (elapsed > 0 ? elapsed : 1e-9);
        double eta = (double)(total - done) / (rate > 0 ? rate : 1);
        fprintf(stderr, "\rpt: %5.1f%%  %d/%d spp  %.2f Msamples/s  elapsed %.1f s  ETA %.1f s   ",
                100.0 * fraction, spp_done, spp, rate * 1e-6, elapsed, eta);
    }
    fflush(stderr);
}

bool render_loop_run(Session *session, const RenderSettings *settings, ProgressStyle progress,
                     RenderImages *images, RenderStats *stats, Error *err)
{
    Wavefront *w = wavefront_create(&session->dev, &session->scene, &session->buffers, settings, err);
    if (!w)
        return false;
    uint64_t total = (uint64_t)session->scene.desc.width * (uint64_t)session->scene.desc.height *
                     (uint64_t)settings->spp;
    uint64_t done = 0;
    double start = seconds_now(), last_print = -1.0;
    double interval = progress == PROGRESS_LINES ? LINE_UPDATE_SECONDS : TERMINAL_UPDATE_SECONDS;
    while (wavefront_spp_done(w) < settings->spp && !stop_signal_received()) {
        bool first = done == 0;
        done += wavefront_advance(w, 1, settings->spp);
        double now = seconds_now() - start;
        bool finished = wavefront_spp_done(w) == settings->spp;
        if (progress != PROGRESS_NONE && (first || finished || now - last_print >= interval)) {
            print_progress(progress, wavefront_spp_done(w), settings->spp, done, total, now);
            last_print = now;
        }
        if (first)
            stop_signals_test_point("render");
    }
    if (progress == PROGRESS_TERMINAL)
        fputc('\n', stderr);
    if (stop_signal_received())
        fprintf(stderr, "pt: %s received: stopping with %d spp done\n",
                stop_signal_name(stop_signal_received()), wavefront_spp_done(w));
    wavefront_read_film(w, images->rgb);
    render_images_read_film(images, w);
    *stats = *wavefront_stats(w);
    wavefront_destroy(w);
    return true;
}
