// SPDX-License-Identifier: MIT
#include "app/render_denoise.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/env.h"

/* An AOV sample costs about an eighth of a beauty sample on PoCL (render_output.c), so guides
 * over all the image's samples add about 12% to the render; past 64 samples the guides' edges and
 * bokeh are converged well beyond what OIDN's prefilter leaves, and the pass's share only falls. */
#define DENOISE_GUIDE_MAX_SPP 64

int denoise_guide_spp(int spp_done)
{
    return spp_done < 1 ? 1 : spp_done < DENOISE_GUIDE_MAX_SPP ? spp_done : DENOISE_GUIDE_MAX_SPP;
}

bool render_images_add_guides(RenderImages *images, size_t num_pixels)
{
    static const AovLayer guides[] = {AOV_LAYER_ALBEDO, AOV_LAYER_NORMAL};
    for (int g = 0; g < 2; g++) {
        float **layer = &images->layer[guides[g]];
        if (!*layer)
            *layer = calloc(num_pixels * 3, sizeof(float));
        if (!*layer)
            return false;
    }
    return true;
}

void render_images_denoise(RenderImages *images, const Session *session, DenoiseDevice device,
                           bool quiet)
{
    const SceneDesc *desc = &session->scene.desc;
    size_t floats = (size_t)desc->width * (size_t)desc->height * 3;
    double start = seconds_now();
    Error err = {0};
    /* PT_DENOISE_COLOR_ONLY=1: no guides, for measurements (tools/bench_denoise.sh). */
    bool color_only = false;
    if (!env_flag("PT_DENOISE_COLOR_ONLY", false, &color_only, &err))
        die("%s", err.message);
    bool on_nvidia_gpu = session->dev.is_nvidia && (session->dev.type & CL_DEVICE_TYPE_GPU);
    Denoiser *denoiser = denoiser_open(device, on_nvidia_gpu, &err);
    float *noisy = denoiser ? malloc(floats * sizeof *noisy) : NULL;
    if (denoiser && !noisy)
        error_set(&err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for the noisy image");
    if (noisy) {
        memcpy(noisy, images->rgb, floats * sizeof *noisy);
        DenoiseInput input = {.color = noisy,
                              .albedo = color_only ? NULL : images->layer[AOV_LAYER_ALBEDO],
                              .normal = color_only ? NULL : images->layer[AOV_LAYER_NORMAL],
                              .width = desc->width,
                              .height = desc->height};
        if (denoiser_run(denoiser, &input, images->rgb, &err)) {
            images->noisy = noisy;
            noisy = NULL;
            snprintf(images->denoiser, sizeof images->denoiser, "Intel Open Image Denoise %s",
                     denoiser_version(denoiser));
            snprintf(images->denoise_device, sizeof images->denoise_device, "%s",
                     denoiser_device(denoiser));
        } else {
            memcpy(images->rgb, noisy, floats * sizeof *noisy); /* a failed filter may have written */
        }
    }
    free(noisy);
    denoiser_close(denoiser);
    if (!images->noisy)
        fprintf(stderr, "pt: warning: --denoise: %s; the image is written noisy\n", err.message);
    else if (!quiet)
        fprintf(stderr, "pt: denoised with %s (%s device) in %.2f s\n", images->denoiser,
                images->denoise_device, seconds_now() - start);
}
