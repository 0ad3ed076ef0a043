// SPDX-License-Identifier: MIT
/* denoised_frames.c: the viewer's side of the denoised view (Ctrl+D): when to hand the film to
 * the denoising thread (viewer/denoise_view.h) and when to show its result. */
#include "viewer/actions.h"

#include <stdio.h>
#include <string.h>

#include "render/aov.h"

/* The guides' samples: anti-aliased enough for OIDN's balanced filter, and about half a beauty
 * sample's cost, paid once per film (camera pose), not per denoised frame. */
#define VIEWER_GUIDE_SPP 4

void viewer_toggle_denoise(Viewer *v)
{
    if (!v->denoise_on) {
        Error err = {0};
        bool on_nvidia_gpu = v->session.dev.is_nvidia && (v->session.dev.type & CL_DEVICE_TYPE_GPU);
        if (!denoise_view_start(&v->denoise, (DenoiseDevice)v->options->denoise_device,
                                on_nvidia_gpu, &err)) {
            fprintf(stderr, "pt: warning: denoised view: %s\n", err.message);
            return;
        }
    }
    v->denoise_on = !v->denoise_on;
    v->film_changed = true; /* the noisy film again, until (or instead of) a denoised one */
    v->shown_spp = 0;
    printf("denoised view %s\n", v->denoise_on ? "on" : "off");
}

/* The albedo and normal of the film's camera into the denoiser's guide buffers. */
static void render_guides(Viewer *v)
{
    AovSettings settings = {.spp = VIEWER_GUIDE_SPP, .max_depth = v->settings.max_depth,
                            .seed = v->settings.seed};
    AovImages images = {.albedo = v->denoise.albedo, .normal = v->denoise.normal};
    Error err = {0};
    if (!aov_render_layers(&v->session.dev, &v->session.scene, &v->session.buffers, &settings,
                           &images, &err))
        die("%s", err.message);
    v->denoise.guide_generation = v->film_generation;
}

/* A result for this film and newer than the one shown goes to the display. */
static void show_result(Viewer *v)
{
    DenoiseView *d = &v->denoise;
    if (d->error[0]) { /* OIDN failed (out of memory, say): back to the noisy view, once */
        fprintf(stderr, "pt: warning: denoised view: %s; the view stays noisy\n", d->error);
        d->error[0] = '\0';
        v->denoise_on = false, v->film_changed = true, v->shown_spp = 0;
        return;
    }
    if (d->output_spp == 0 || d->output_generation != v->film_generation ||
        (v->shown_spp == d->output_spp && v->shown_generation == v->film_generation))
        return;
    const SceneDesc *desc = &v->session.scene.desc;
    Error err = {0};
    if (!viewer_bloom(v, d->output, &err))
        die("%s", err.message);
    memcpy(viewer_display_upload_begin(&v->display), d->output,
           (size_t)desc->width * (size_t)desc->height * 3 * sizeof(float));
    viewer_display_upload_end(&v->display);
    v->shown_spp = d->output_spp, v->shown_generation = v->film_generation;
    v->film_changed = false;
    viewer_print_event(&v->input, "denoised %d spp", d->output_spp);
}

/* Each frame: collect a finished result, then hand over the film when the thread is idle and the
 * film is new, has doubled its samples since the last result, or has stopped gaining samples. */
void viewer_update_denoised(Viewer *v, bool film_still)
{
    DenoiseView *d = &v->denoise;
    if (!v->denoise_on || denoise_view_busy(d))
        return;
    show_result(v);
    if (!v->denoise_on)
        return;
    const SceneDesc *desc = &v->session.scene.desc;
    int spp = wavefront_spp_done(v->wavefront);
    bool same_film = d->output_generation == v->film_generation && d->width == desc->width &&
                     d->height == desc->height && d->output_spp > 0;
    bool due = spp > 0 && (!same_film || spp >= 2 * d->output_spp ||
                           (film_still && spp != d->output_spp));
    if (!due)
        return;
    if (!denoise_view_resize(d, desc->width, desc->height))
        die("out of memory for the denoised view of a %dx%d film", desc->width, desc->height);
    if (d->guide_generation != v->film_generation)
        render_guides(v);
    wavefront_read_film(v->wavefront, d->input);
    denoise_view_submit(d, v->film_generation, spp);
}

bool viewer_showing_denoised(const Viewer *v)
{
    return v->denoise_on && v->shown_spp > 0 && v->shown_generation == v->film_generation;
}
