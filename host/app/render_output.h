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
    unsigned mask;     /* AOV_MASK bits of the layers held */
    float *rgb;        /* the beauty, 3 floats a pixel */
    float *alpha;      /* the beauty's coverage (EXR A): the fraction of the AOV pass's camera
                        * samples that hit geometry; exact (hits / samples, one work item a
                        * pixel), so no order of samples can change it */
    float *layer[AOV_LAYER_COUNT]; /* indexed by AovLayer, its channel count floats a pixel */
} RenderImages;

/* Allocates the beauty and the layers of mask; false when out of memory. */
bool render_images_alloc(RenderImages *images, unsigned mask, size_t num_pixels);
void render_images_free(RenderImages *images);

/* The film's layers (spp, variance), read before the wavefront is released. */
void render_images_read_film(RenderImages *images, Wavefront *w);

/* Runs the AOV pass for the albedo, normal and depth layers held and the beauty's alpha, over
 * the first aov_pass_spp samples of the render's camera samples (only the camera rays when no
 * layer is asked for). */
bool render_images_aov_pass(RenderImages *images, Session *session, const RenderSettings *settings,
                            int spp_done, Error *err);

/* The samples the AOV pass takes of a render holding spp_done per pixel: a quarter, at least 1,
 * at most 16 (render_output.c says why). */
int aov_pass_spp(int spp_done);

/* The metadata of the EXR header. */
typedef struct {
    int spp_done, spp_requested;
    unsigned seed;
    double render_seconds;
    const char *scene;        /* the scene path as given */
    bool partial;             /* fewer samples than asked (a stop signal or a time limit) */
} RenderRecord;

/* Writes the EXR: beauty, layers (every channel 32-bit float, the spp counts too: what Blender's
 * compositor reads best; exact up to 2^24 samples) and the header attributes spp, spp_requested,
 * seed (a string: the full unsigned range), render_time (float seconds of path tracing), devices,
 * pt_version, scene, camera (the JSON object `--camera` takes) and partial (int 1/0). */
bool render_write_exr(const char *path, const RenderImages *images, const Session *session,
                      const RenderRecord *record, Error *err);

#endif
