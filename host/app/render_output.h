/* SPDX-License-Identifier: MIT */
/* render_output.h: what `pt render` writes into its EXR: the beauty, the AOV layers asked for
 * (render/aov_layers.h: albedo, normal and depth from the AOV pass, variance and spp from the
 * film) and the render's metadata as header attributes (shared/DESIGN.md "Film and outputs"). */
#ifndef PT_RENDER_OUTPUT_H
#define PT_RENDER_OUTPUT_H

#include <stdbool.h>
#include <stddef.h>

#include "render/aov_layers.h"
#include "render/session.h"
#include "render/wavefront.h"

/* Per pixel, row 0 at the top; a layer not asked for is NULL. */
typedef struct {
    unsigned mask;     /* AOV_MASK bits of the layers asked for: those the EXR gets */
    float *rgb;        /* the beauty, 3 floats a pixel */
    float *alpha;      /* the beauty's coverage (EXR A): the fraction of the AOV pass's camera
                        * samples that hit geometry; exact (hits / samples, one work item a
                        * pixel), so no order of samples can change it */
    float *layer[AOV_LAYER_COUNT]; /* indexed by AovLayer, its channel count floats a pixel; the
                                    * denoiser's guides (albedo, normal) may be held unasked */
    float *noisy;      /* --denoise: the beauty before denoising (rgb is denoised); else NULL */
    char denoiser[64]; /* "Intel Open Image Denoise 2.5.1" once rgb is denoised, else "" */
    char denoise_device[16]; /* OIDN's device: "CPU" or "CUDA" */
    int guide_spp;     /* the samples per pixel of the AOV pass (albedo, normal, depth) */
} RenderImages;

/* Allocates the beauty and the layers of mask; false when out of memory. */
bool render_images_alloc(RenderImages *images, unsigned mask, size_t num_pixels);
void render_images_free(RenderImages *images);

/* The film's layers (spp, variance), read before the wavefront is released. */
void render_images_read_film(RenderImages *images, Wavefront *w);

/* Runs the AOV pass for the albedo, normal and depth layers held and the beauty's alpha, over
 * the first aov_spp samples of the render's camera samples (aov_pass_spp, or denoise_guide_spp
 * when denoising; only the camera rays' first hits when no layer is held). */
bool render_images_aov_pass(RenderImages *images, Session *session, const RenderSettings *settings,
                            int aov_spp, Error *err);

/* The samples the AOV pass takes of a render holding spp_done per pixel: a quarter, at least 1,
 * at most 16 (render_output.c says why). */
int aov_pass_spp(int spp_done);

/* The metadata of the EXR header. */
typedef struct {
    int spp_done, spp_requested;
    unsigned seed;
    double render_seconds;
    const char *scene;        /* the scene path as given */
    bool partial;             /* fewer samples than asked (a stop signal or a time limit); a
                               * denoised image is then the denoised partial one */
} RenderRecord;

/* Writes the EXR: beauty, layers (every channel 32-bit float, the spp counts too: what Blender's
 * compositor reads best; exact up to 2^24 samples) and the header attributes spp, spp_requested,
 * seed (a string: the full unsigned range), render_time (float seconds of path tracing), devices,
 * pt_version, scene, camera (the JSON object `--camera` takes) and partial (int 1/0). A
 * denoised image adds the layer noisy.R/G/B (the raw beauty) and the attributes denoised (int 1),
 * denoiser ("Intel Open Image Denoise 2.5.1"), denoise_device ("CPU"/"CUDA") and denoise_guides. */
bool render_write_exr(const char *path, const RenderImages *images, const Session *session,
                      const RenderRecord *record, Error *err);

#endif
