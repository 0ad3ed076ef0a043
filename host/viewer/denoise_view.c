// SPDX-License-Identifier: MIT
#include "viewer/denoise_view.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GLFW/glfw3.h>

/* The thread: waits for a submitted film, denoises it at OIDN's interactive ("balanced")
 * quality, publishes the result and wakes the frame loop (glfwPostEmptyEvent may be called from
 * any thread). */
static void *denoise_thread(void *arg)
{
    DenoiseView *d = arg;
    pthread_mutex_lock(&d->lock);
    for (;;) {
        while (!d->busy && !d->quit)
            pthread_cond_wait(&d->wake, &d->lock);
        if (d->quit)
            break;
        pthread_mutex_unlock(&d->lock);
        DenoiseInput in = {.color = d->input, .albedo = d->albedo, .normal = d->normal,
                           .width = d->width, .height = d->height, .interactive = true};
        Error err = {0};
        bool ok = denoiser_run(d->denoiser, &in, d->output, &err);
        pthread_mutex_lock(&d->lock);
        if (ok) {
            d->output_generation = d->input_generation;
            d->output_spp = d->input_spp;
        } else {
            snprintf(d->error, sizeof d->error, "%s", err.message);
            d->output_spp = 0;
        }
        d->busy = false;
        glfwPostEmptyEvent(); /* an idle frame loop sleeps in glfwWaitEvents: show the result */
    }
    pthread_mutex_unlock(&d->lock);
    return NULL;
}

bool denoise_view_start(DenoiseView *d, DenoiseDevice device, bool render_on_nvidia, Error *err)
{
    if (d->started)
        return true;
    d->denoiser = denoiser_open(device, render_on_nvidia, err);
    if (!d->denoiser)
        return false;
    pthread_mutex_init(&d->lock, NULL);
    pthread_cond_init(&d->wake, NULL);
    if (pthread_create(&d->thread, NULL, denoise_thread, d) != 0) {
        error_set(err, ERR_SYSTEM, NULL, 0, "cannot start the denoising thread");
        denoiser_close(d->denoiser);
        d->denoiser = NULL;
        return false;
    }
    d->started = true;
    return true;
}

bool denoise_view_busy(DenoiseView *d)
{
    pthread_mutex_lock(&d->lock);
    bool busy = d->busy;
    pthread_mutex_unlock(&d->lock);
    return busy;
}

bool denoise_view_resize(DenoiseView *d, int width, int height)
{
    if (d->input && width == d->width && height == d->height)
        return true;
    size_t bytes = (size_t)width * (size_t)height * 3 * sizeof(float);
    float **buffers[] = {&d->input, &d->albedo, &d->normal, &d->output};
    bool ok = true;
    for (int b = 0; b < 4; b++) {
        free(*buffers[b]);
        *buffers[b] = malloc(bytes);
        ok = ok && *buffers[b];
    }
    d->width = width, d->height = height;
    d->output_spp = 0;
    d->guide_generation = d->output_generation = (unsigned)-1; /* no guides nor result yet */
    return ok;
}

void denoise_view_submit(DenoiseView *d, unsigned generation, int spp)
{
    pthread_mutex_lock(&d->lock);
    d->input_generation = generation;
    d->input_spp = spp;
    d->busy = true;
    pthread_cond_signal(&d->wake);
    pthread_mutex_unlock(&d->lock);
}

void denoise_view_stop(DenoiseView *d)
{
    if (d->started) {
        pthread_mutex_lock(&d->lock);
        d->quit = true;
        pthread_cond_signal(&d->wake);
        pthread_mutex_unlock(&d->lock);
        pthread_join(d->thread, NULL); /* a filter under way ends first */
        pthread_mutex_destroy(&d->lock);
        pthread_cond_destroy(&d->wake);
        denoiser_close(d->denoiser);
    }
    free(d->input), free(d->albedo), free(d->normal), free(d->output);
    memset(d, 0, sizeof *d);
}
