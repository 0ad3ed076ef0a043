/* SPDX-License-Identifier: MIT */
/* environment.h: the environment map (shared/DESIGN.md "Environment"): an equirectangular HDR or
 * EXR image, its radiance per texel (times scale) and the piecewise-constant distribution that
 * next-event estimation samples it from (a row by the rows' CDF, then a texel by its row's: the
 * inversion keeps a stratified sample stratified over the map). The
 * radiance is evaluated bilinearly everywhere; each texel's sampling weight is how far the largest
 * luminance of its 3 x 3 neighbourhood rises above that maximum's mean over the sphere (MIS
 * compensation) x sin(theta of its row centre), so the pdf is > 0 wherever the bilinear radiance
 * rises above the mean, and texels[].w is exactly the density the sampler draws from: MIS with it
 * is unbiased (cl/light/light_env.cl says why). */
#ifndef PT_ENVIRONMENT_H
#define PT_ENVIRONMENT_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"
#include "base/shared_types.h"

typedef struct {
    uint32_t width, height;   /* 0 x 0: no map (the constant background is the environment) */
    float4 *texels;           /* width * height, row 0 at the top: rgb radiance x scale; w: the
                                 sampling pdf in the texel's (u, v) cell per unit uv area */
    uint32_t *cdf;            /* height + width * height, 32-bit fixed point (2^32 = 1): the rows'
                                 marginal CDF (entry j: the weight above row j), then each row's
                                 conditional CDF over its texels; entry 0 of each is 0, the end
                                 (2^32) is implied; then as many entries again, laid out alike: each
                                 CDF's guide (environment.c build_guide) */
    float rotation;           /* DESIGN's theta as a fraction of a turn */
    double mean_luminance;    /* of the radiance over the sphere (solid-angle weighted) */
} Environment;

/* Builds from linear rgb (width * height * 3 floats, row 0 at the top). NaN, Inf and negative
 * values are clamped to 0 with one warning naming `name` and the count; a map of zero power is an
 * error. scale >= 0, rotation in degrees. */
bool environment_build(Environment *env, const float *rgb, int width, int height, float scale,
                       float rotation_degrees, const char *name, Error *err);
/* Reads path (.hdr through stb_image, .exr through io/exr_read.c) and builds. */
bool environment_load(Environment *env, const char *path, float scale, float rotation_degrees,
                      Error *err);
void environment_free(Environment *env);
/* The entries of env->cdf: 2 (height + width * height), 0 without a map (the layout above). */
static inline size_t environment_cdf_count(const Environment *env)
{
    return 2 * ((size_t)env->height + (size_t)env->width * env->height);
}

#endif
