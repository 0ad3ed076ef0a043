/* SPDX-License-Identifier: MIT */
/* adaptive.h: adaptive sampling and the variance estimate, the parts of a Wavefront that read the
 * film's second moments (render/film.h, shared/render.h MOMENT_WORDS).
 *
 * Adaptive sampling (RenderSettings.noise_threshold T > 0): every pixel gets min_spp samples; then
 * at sample-count boundaries film_variance computes each pixel's relative error from the exact
 * sums and adaptive_select stops the pixels whose 8 neighbours are all below T
 * (cl/stages/adaptive_select.cl says why not the pixel's own). The first boundary is min_spp; the
 * next comes step x pixels / active pixels samples later (step = ADAPTIVE_STEP(min_spp)), i.e.
 * after about as many paths as step uniform samples, so that windows stay long as pixels stop.
 * The pixels still active are compacted, in increasing order, into active_pixels, and the next
 * windows cycle over that list only (window_pixel); all of them hold the same count, so a pixel's
 * samples keep the indices (and RNG streams) a uniform render gives them. The decisions read only
 * exact integer sums at fixed counts, so the image is a pure function of (scene, settings, seed):
 * the same bits for any window or pool. Pixels stop for good at settings.spp. */
#ifndef PT_ADAPTIVE_H
#define PT_ADAPTIVE_H

#include <stdbool.h>
#include <stdint.h>

#include "parallel/compact.h"
#include "render/wavefront.h"

/* The default min_spp: max(16, spp / 16), at most spp. 16 samples estimate a variance to about
 * +-35% (sqrt(2 / 15)), and fewer let a pixel whose rare paths (a small light's caustic) have not
 * shown up yet look converged to its neighbours; spp / 16 keeps the uniform part at a sixteenth of
 * the budget, so that long renders look longer before deciding. */
#define ADAPTIVE_MIN_SPP_FLOOR 16
#define ADAPTIVE_MIN_SPP_DIVISOR 16
/* Samples between decisions while every pixel is active: half of min_spp (at least 1). A decision
 * costs two passes over the film and a compaction; a pixel converged just after the first check
 * overshoots by at most half the samples it had there. */
#define ADAPTIVE_STEP(min_spp) ((min_spp) / 2u > 0u ? (min_spp) / 2u : 1u)

typedef struct {
    bool on;             /* adaptive sampling */
    float threshold;     /* T */
    uint32_t min_spp, step, spp;
    uint32_t next_boundary; /* the sample count of the next decision */
    bool done;              /* every pixel has stopped */
    cl_mem variance;        /* float4 per pixel (film_variance.cl), with moments */
    cl_mem pixel_flags;     /* uint per pixel: 1 still sampled; adaptive only */
    cl_kernel film_variance, select;
    Compactor *compactor;   /* over pixel_flags into active_pixels */
} Adaptive;

uint32_t adaptive_default_min_spp(uint32_t spp);

/* Resolves the settings against the scene's render.noise_threshold and render.min_spp (the
 * settings win) into w->adaptive and checks them: an error names the key (or option) and value.
 * Turns s->moments on for adaptive sampling. Before the film exists. */
bool adaptive_configure(Wavefront *w, const Scene *scene, RenderSettings *s, Error *err);
/* The buffers and kernels: the moments' (s->moments) and adaptive sampling's. */
bool adaptive_init(Wavefront *w, Error *err);
void adaptive_reset(Wavefront *w); /* every pixel sampled again, from the first decision on */
/* The sample count the next windows stop at: max_spp, or the next decision before it. */
uint32_t adaptive_window_end(const Wavefront *w, uint32_t max_spp);
/* After a window: at a decision's sample count (w->next_sample, no pixel slice pending), decides
 * which pixels go on and points the windows at them. */
void adaptive_after_window(Wavefront *w);
/* film_variance over the whole film into adaptive.variance (with moments). */
void adaptive_compute_variance(Wavefront *w);
void adaptive_release(Wavefront *w);

#endif
