// SPDX-License-Identifier: MIT
/* adaptive.c: adaptive sampling's settings, buffers and decisions, and the variance estimate
 * (render/adaptive.h). The frame loop (render/wavefront.c) asks where windows must stop and calls
 * in after each window. */
#include "render/adaptive.h"

#include <math.h>
#include <stdlib.h>

#include "render/wavefront_internal.h"

uint32_t adaptive_default_min_spp(uint32_t spp)
{
    uint32_t min_spp = spp / ADAPTIVE_MIN_SPP_DIVISOR;
    if (min_spp < ADAPTIVE_MIN_SPP_FLOOR)
        min_spp = ADAPTIVE_MIN_SPP_FLOOR;
    return min_spp < spp ? min_spp : spp;
}

bool adaptive_configure(Wavefront *w, const Scene *scene, RenderSettings *s, Error *err)
{
    Adaptive *a = &w->adaptive;
    const SceneDesc *d = &scene->desc;
    if (s->noise_threshold != 0.0f && !(s->noise_threshold > 0.0f && isfinite(s->noise_threshold))) {
        error_set_setting(err, "noise_threshold", "%g: must be a finite number > 0",
                          s->noise_threshold);
        return false;
    }
    if (s->min_spp < 0) {
        error_set_setting(err, "min_spp", "%d: must be at least 1", s->min_spp);
        return false;
    }
    if (s->min_spp > s->spp) {
        error_set_setting(err, "min_spp", "%d: more than the spp (%d)", s->min_spp, s->spp);
        return false;
    }
    if (!s->min_spp && d->min_spp > s->spp) {
        error_set(err, ERR_JSON_VALUE, d->path, 0, "%s: render.min_spp: %d is more than the spp (%d)",
                  d->path, d->min_spp, s->spp);
        return false;
    }
    a->threshold = s->noise_threshold > 0.0f ? s->noise_threshold : d->noise_threshold;
    a->on = a->threshold > 0.0f;
    a->spp = (uint32_t)s->spp;
    a->min_spp = s->min_spp ? (uint32_t)s->min_spp
                 : d->min_spp ? (uint32_t)d->min_spp
                              : adaptive_default_min_spp((uint32_t)s->spp);
    a->step = ADAPTIVE_STEP(a->min_spp);
    if (a->on && s->first_sample != 0) {
        error_set(err, ERR_SETTINGS, NULL, 0,
                  "adaptive sampling decides from the whole film: it cannot render a block of "
                  "samples (first_sample %u)", s->first_sample);
        return false;
    }
    if (a->on)
        s->moments = true;
    return true;
}

bool adaptive_init(Wavefront *w, Error *err)
{
    Adaptive *a = &w->adaptive;
    size_t np = w->num_pixels;
    /* Without adaptive sampling window_pixel never reads the list: one entry to bind. */
    w->active_pixels = device_buffer(w->dev, "active_pixels", CL_MEM_READ_WRITE,
                                     (a->on ? np : 1) * sizeof(cl_uint), NULL, err);
    if (!w->active_pixels)
        return false;
    if (!w->settings.moments)
        return true;
    if (!film_add_moments(&w->film, err))
        return false;
    a->variance = device_buffer(w->dev, "film_variance", CL_MEM_READ_WRITE, np * sizeof(cl_float4),
                                NULL, err);
    if (!a->variance)
        return false;
    a->film_variance = device_kernel(w->dev, "film_variance");
    cl_uint n = w->num_pixels;
    KERNEL_ARGS(a->film_variance, 0, KARG(n), KARG(w->film.sums), KARG(w->film.moments),
                KARG(a->variance));
    w->stats->config.device_bytes += np * (MOMENT_BYTES_PER_PIXEL + sizeof(cl_float4));
    if (!a->on)
        return true;
    a->pixel_flags = device_buffer(w->dev, "pixel_flags", CL_MEM_READ_WRITE, np * sizeof(cl_uint),
                                   NULL, err);
    if (!a->pixel_flags)
        return false;
    a->compactor = compactor_create(w->dev, np, err);
    if (!a->compactor)
        return false;
    a->select = device_kernel(w->dev, "adaptive_select");
    cl_uint width = w->params.width, height = w->params.height;
    KERNEL_ARGS(a->select, 0, KARG(width), KARG(height), KARG(a->threshold), KARG(a->variance),
                KARG(a->pixel_flags));
    w->stats->config.device_bytes += np * 2 * sizeof(cl_uint);
    return true;
}

void adaptive_reset(Wavefront *w)
{
    Adaptive *a = &w->adaptive;
    w->params.window_pixels = w->num_pixels;
    w->params.flags &= ~RENDER_ADAPTIVE;
    w->stats->active_pixels = w->num_pixels;
    a->done = false;
    a->next_boundary = a->min_spp;
    if (!a->on)
        return;
    cl_uint one = 1;
    device_fill(w->dev, a->pixel_flags, &one, sizeof one, 0, (size_t)w->num_pixels * sizeof one,
                NULL);
}

uint32_t adaptive_window_end(const Wavefront *w, uint32_t max_spp)
{
    const Adaptive *a = &w->adaptive;
    /* Past settings.spp (a viewer asking for more) there is no decision left to stop at. */
    bool ahead = a->on && a->next_boundary > w->next_sample;
    return ahead && a->next_boundary < max_spp ? a->next_boundary : max_spp;
}

void adaptive_compute_variance(Wavefront *w)
{
    device_run(w->dev, w->adaptive.film_variance, w->num_pixels, 0, NULL);
}

void adaptive_after_window(Wavefront *w)
{
    Adaptive *a = &w->adaptive;
    if (!a->on || a->done || w->next_pixel != 0 || w->next_sample != a->next_boundary ||
        w->next_sample >= a->spp)
        return;
    adaptive_compute_variance(w);
    device_run(w->dev, a->select, w->num_pixels, 0, NULL);
    uint32_t active = compactor_run(a->compactor, a->pixel_flags, w->active_pixels, w->num_pixels);
    w->stats->active_pixels = active;
    if (active == 0) {
        a->done = true;
        return;
    }
    /* The next decision after about step x all pixels' worth of samples: the fewer pixels go on,
     * the more samples each gets before it, so that windows stay long (a function of the film,
     * like everything here, never of the device). */
    uint64_t step = ((uint64_t)a->step * w->num_pixels + active - 1) / active;
    a->next_boundary = step < a->spp - a->next_boundary ? a->next_boundary + (uint32_t)step : a->spp;
    w->params.window_pixels = active;
    w->params.flags |= RENDER_ADAPTIVE;
}

void adaptive_release(Wavefront *w)
{
    Adaptive *a = &w->adaptive;
    if (a->film_variance)
        device_release_kernel(a->film_variance);
    if (a->select)
        device_release_kernel(a->select);
    if (a->compactor)
        compactor_destroy(a->compactor);
    cl_mem all[] = {a->variance, a->pixel_flags, w->active_pixels};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (all[i])
            device_release_buffer(all[i]);
}
