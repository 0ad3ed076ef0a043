/* SPDX-License-Identifier: MIT */
/* render_denoise.h: `pt render --denoise` (or the scene's render.denoise): after the render (on
 * rank 0, once, on the merged film: MPI ranks, work units, checkpoints and adaptive sampling all
 * end in the one image rank 0 writes), the AOV pass makes the albedo and normal guides from the
 * image's own camera samples, OIDN denoises the beauty (render/denoise.h), and the raw image is
 * kept for the EXR's noisy layer. */
#ifndef PT_RENDER_DENOISE_H
#define PT_RENDER_DENOISE_H

#include <stdbool.h>
#include <stddef.h>

#include "app/render_output.h"
#include "render/denoise.h"
#include "render/session.h"

/* The guides' samples per pixel for an image of spp_done: all of its camera samples (the guides'
 * edges, depth of field and motion blur then average over the image's own lens, time and
 * sub-pixel positions), at most DENOISE_GUIDE_MAX_SPP (render_denoise.c says why). */
int denoise_guide_spp(int spp_done);

/* Allocates the albedo and normal layers as guides where --aov did not ask for them (the EXR
 * leaves them out); false when out of memory. */
bool render_images_add_guides(RenderImages *images, size_t num_pixels);

/* Denoises images->rgb in place, keeping the raw beauty in images->noisy. Without OIDN, or when
 * it fails, one warning line says why (and how to get OIDN) and the image stays noisy: the render
 * is not lost for a missing denoiser. Prints the time taken unless quiet. */
void render_images_denoise(RenderImages *images, const Session *session, DenoiseDevice device,
                           bool quiet);

#endif
