/* SPDX-License-Identifier: MIT */
/* aov.h: the AOV layers of the EXR beside the beauty (shared/DESIGN.md "Film and outputs"):
 * albedo, normal and depth from the render_aov pass (cl/stages/render_aov.cl: the beauty's camera
 * rays, delta surfaces followed to the first non-delta hit), and the per-pixel sample count and
 * variance of the mean read from the beauty's film. */
#ifndef PT_AOV_H
#define PT_AOV_H

#include <stdbool.h>

#include "device/device.h"
#include "scene/scene.h"
#include "render/scene_upload.h"
#include "render/wavefront.h"

/* The depth of a pixel that no camera sample hit: finite (EXR readers and compositors choke on
 * inf) and far beyond any scene, the value Blender's Z pass gives the background. */
#define AOV_DEPTH_MISS 1e10f

/* What the pass renders: camera samples first_sample .. first_sample + spp - 1 (the beauty's),
 * delta surfaces followed for at most max_depth segments. */
typedef struct {
    int spp, max_depth;
    unsigned seed;
    unsigned first_sample;
} AovSettings;

/* Per pixel, row 0 at the top; any pointer may be NULL (not wanted). */
typedef struct {
    float *albedo; /* rgb: the first non-delta hit's albedo, mean over the samples (0: miss) */
    float *normal; /* xyz: its shading normal toward the viewer, world space, mean (0: miss) */
    float *depth;  /* the camera ray's distance to its first hit, mean over the samples that hit;
                    * AOV_DEPTH_MISS where none did */
    float *coverage; /* the fraction of the samples whose camera ray hit geometry (EXR's A) */
} AovImages;

/* Runs render_aov; false with the device's error (e.g. out of memory). */
bool aov_render_layers(Device *dev, const Scene *scene, const SceneBuffers *buffers,
                       const AovSettings *settings, const AovImages *out, Error *err);

/* Older single-AOV interface (the viewer's focus probe, tests): aov = AOV_ALBEDO, AOV_NORMAL or
 * AOV_DEPTH (cl/shared/render.h) into rgb (3 floats a pixel; depth repeated, 0 on a miss), spp
 * samples, delta surfaces followed for up to 8 segments. Dies on a device error. */
void aov_render(Device *dev, const Scene *scene, const SceneBuffers *buffers, unsigned aov, int spp,
                unsigned seed, float *rgb);

#endif
