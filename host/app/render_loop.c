// SPDX-License-Identifier: MIT
#include "app/render_loop.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "app/stop_signals.h"
#include "base/clock.h"

/* Seconds between progress updates: often enough to see it move, rare enough to cost nothing; a
 * log (stderr not a terminal) gets fewer lines, so that a long CI render stays readable. */
#define TERMINAL_UPDATE_SECONDS 0.25
#define LINE_UPDATE_SECONDS 1.0
#define LOG_UPDATE_SECONDS 5.0

ProgressStyle render_loop_progress_style(bool quiet, bool progress_lines, bool stderr_is_terminal)
{
    if (progress_lines)
        return PROGRESS_LINES;
    if (quiet)
        return PROGRESS_NONE;
    return stderr_is_terminal ? PROGRESS_TERMINAL : PROGRESS_LOG;
}

double render_loop_update_interval(ProgressStyle style)
{
    return style == PROGRESS_TERMINAL ? TERMINAL_UPDATE_SECONDS
           : style == PROGRESS_LOG    ? LOG_UPDATE_SECONDS
                                      : LINE_UPDATE_SECONDS;
}

void render_loop_print_progress(ProgressStyle style, int spp_done, int spp, uint64_t done,
                           uint64_t total, double elapsed)
{
    /* Adaptive sampling finishes with fewer paths than pixels x spp: done is then 100%. */
    double fraction = total && spp_done < spp ? (double)done / (double)total : 1.0;
    if (style != PROGRESS_TERMINAL) {
        fprintf(stderr, "pt: progress: %d/%d spp (%.1f%%), %.1f s\n", spp_done, spp,
                100.0 * fraction, elapsed);
    } else {
        double rate = (double)done / (elapsed > 0 ? elapsed : 1e-9);
        double eta = fraction < 1.0 ? (double)(total - done) / (rate > 0 ? rate : 1) : 0.0;
        fprintf(stderr, "\rpt: %5.1f%%  %d/%d spp  %.2f Msamples/s  elapsed %.1f s  ETA %.1f s   ",
                100.0 * fraction, spp_done, spp, rate * 1e-6, elapsed, eta);
    }
    fflush(stderr);
}

/* How adaptive sampling spent the samples: the mean, least and most per pixel. */
static void print_adaptive_spp(Wavefront *w, size_t pixels, float threshold)
{
    float *spp = malloc(pixels * sizeof *spp);
    if (!spp || pixels == 0) {
        free(spp);
        return;
    }
    wavefront_read_spp(w, spp);
    double sum = 0.0;
    float lo = spp[0], hi = spp[0];
    for (size_t i = 0; i < pixels; i++) {
        sum += spp[i];
        lo = spp[i] < lo ? spp[i] : lo;
        hi = spp[i] > hi ? spp[i] : hi;
    }
    fprintf(stderr, "pt: adaptive sampling (noise threshold %g): %.1f spp per pixel on average, "
            "%.0f to %.0f\n", threshold, sum / (double)pixels, lo, hi);
    free(spp);
}

bool render_loop_run(Session *session, const RenderSettings *settings, const RenderLoopDesc *desc,
                     RenderImages *images, RenderStats *stats, RenderStop *stop, Error *err)
{
    Wavefront *w = wavefront_create(&session->dev, &session->scene, &session->buffers, settings, err);
    if (!w)
        return false;
    uint64_t pixels = (uint64_t)session->scene.desc.width * (uint64_t)session->scene.desc.height;
    uint64_t total = pixels * (uint64_t)settings->spp;
    uint64_t done = 0;
    double start = seconds_now(), last_print = -1.0;
    double interval = render_loop_update_interval(desc->progress);
    ProgressStyle progress = desc->progress;
    *stop = RENDER_COMPLETE;
    while (wavefront_spp_done(w) < settings->spp && !stop_signal_received()) {
        bool first = done == 0;
        done += wavefront_advance(w, 1, settings->spp);
        double now = seconds_now() - start;
        bool timed_out = desc->time_limit > 0.0 && now >= desc->time_limit &&
                         wavefront_spp_done(w) < settings->spp;
        /* A window may be a slice of one sample's pixels: past the limit, the sample under way is
         * finished first, so that every pixel holds the same whole number of samples. */
        if (timed_out && !wavefront_at_whole_sample(w))
            done += wavefront_advance(w, UINT64_MAX, wavefront_spp_done(w) + 1);
        bool finished = wavefront_spp_done(w) == settings->spp || timed_out;
        if (progress != PROGRESS_NONE && (first || finished || now - last_print >= interval)) {
            render_loop_print_progress(progress, wavefront_spp_done(w), settings->spp, done, total,
                           seconds_now() - start);
            last_print = now;
        }
        if (first)
            stop_signals_test_point("render");
        if (timed_out && wavefront_spp_done(w) < settings->spp) {
            *stop = RENDER_STOPPED_BY_TIME_LIMIT;
            break;
        }
    }
    if (progress == PROGRESS_TERMINAL)
        fputc('\n', stderr);
    if (stop_signal_received()) {
        if (wavefront_spp_done(w) < settings->spp)
            *stop = RENDER_STOPPED_BY_SIGNAL;
        fprintf(stderr, "pt: %s received: stopping with %d spp done\n",
                stop_signal_name(stop_signal_received()), wavefront_spp_done(w));
    } else if (*stop == RENDER_STOPPED_BY_TIME_LIMIT) {
        fprintf(stderr, "pt: time limit of %g s reached: stopping with %d of %d spp done\n",
                desc->time_limit, wavefront_spp_done(w), settings->spp);
    }
    float threshold = settings->noise_threshold > 0.0f ? settings->noise_threshold
                                                        : session->scene.desc.noise_threshold;
    if (threshold > 0.0f && progress != PROGRESS_NONE)
        print_adaptive_spp(w, (size_t)pixels, threshold);
    wavefront_read_film(w, images->rgb);
    render_images_read_film(images, w);
    *stats = *wavefront_stats(w);
    wavefront_destroy(w);
    return true;
}
