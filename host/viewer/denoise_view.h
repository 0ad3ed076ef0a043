/* SPDX-License-Identifier: MIT */
/* denoise_view.h: the viewer's denoised view (Ctrl+D). OIDN runs on a thread of its own, so the
 * progressive loop never waits for it: the frame loop hands it a copy of the film and the guides
 * when it is idle and the film has gained enough samples, and shows its latest result for the
 * current film (the noisy film until there is one). */
#ifndef PT_VIEWER_DENOISE_VIEW_H
#define PT_VIEWER_DENOISE_VIEW_H

#include <pthread.h>
#include <stdbool.h>

#include "render/denoise.h"

typedef struct {
    Denoiser *denoiser; /* NULL until the view is first turned on */
    pthread_t thread;
    pthread_mutex_t lock;
    pthread_cond_t wake;
    bool started, busy, quit; /* busy: the thread owns input and output (under lock) */
    int width, height;
    float *input, *albedo, *normal, *output; /* width * height * 3 each */
    unsigned input_generation, guide_generation, output_generation; /* film generations */
    int input_spp, output_spp; /* output_spp 0: no result */
    char error[1024];           /* the thread's last failure, "" if none */
} DenoiseView;

/* Loads OIDN and starts the thread; false with err when OIDN is missing (the viewer says so once
 * and stays noisy). Idempotent. */
bool denoise_view_start(DenoiseView *d, DenoiseDevice device, bool render_on_nvidia, Error *err);

/* Whether the thread is denoising now (input and output belong to it). */
bool denoise_view_busy(DenoiseView *d);

/* Sizes the buffers to the film (only while not busy); false when out of memory. */
bool denoise_view_resize(DenoiseView *d, int width, int height);

/* Hands input (filled by the caller, with the guides) to the thread, marked with the film's
 * generation and sample count. */
void denoise_view_submit(DenoiseView *d, unsigned generation, int spp);

/* Stops the thread and frees everything. */
void denoise_view_stop(DenoiseView *d);

#endif
