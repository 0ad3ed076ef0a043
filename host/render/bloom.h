/* SPDX-License-Identifier: MIT */
/* bloom.h: --bloom STRENGTH[,RADIUS], the glow around bright areas, as an OpenCL post stage
 * (cl/post/bloom.cl) on the linear film before the PNG's tone curve. The bright part of each
 * pixel (the share of its light above BLOOM_THRESHOLD in luminance, hue kept) is blurred with a
 * separable Gaussian, and the image becomes
 *
 *   out = rgb - strength * bright(rgb) + strength * blur(bright(rgb)),
 *
 * so a share `strength` of the bright light is spread out and none is created or lost: the image's
 * total is unchanged (the blur mirrors at the borders; bloom.cl says why that conserves). The EXR
 * stays the linear estimate without bloom. Radius R pixels: sigma = R / 3, taps out to ceil(R)
 * (3 sigma) on each side, the kernel renormalised to sum 1. Default radius: 1% of the image's
 * diagonal (44 pixels at 3840x2160), at least 1. */
#ifndef PT_BLOOM_H
#define PT_BLOOM_H

#include <stdbool.h>

#include "base/error.h"
#include "device/device.h"

/* Scene-linear luminance where glow starts: 1, the white of the `clamp` curve. */
#define BLOOM_THRESHOLD 1.0f
#define BLOOM_MAX_RADIUS 1024.0f

float bloom_default_radius(int width, int height);

/* The half kernel for a radius in pixels: weights[k] for |tap| = k, k = 0 .. returned tap radius
 * (at most max_taps - 1); the full kernel sums to 1. */
int bloom_weights(float radius, float *weights, int max_taps);

/* Applies bloom to rgb (width x height RGB floats, in place) on dev, whose program holds
 * cl/post/bloom.cl (every pt program does). strength in [0, 1]: 0 returns at once with rgb
 * untouched; radius in pixels, 0 = bloom_default_radius. ERR_SETTINGS for values out of range,
 * ERR_ALLOC_TOO_LARGE when the buffers do not fit the device. */
bool bloom_apply(Device *dev, float *rgb, int width, int height, float strength, float radius,
                 Error *err);

/* The same, adding the two kernels' device time to *kernel_ms (for tools/bench_bloom.c). */
bool bloom_apply_profiled(Device *dev, float *rgb, int width, int height, float strength,
                          float radius, double *kernel_ms, Error *err);

#endif
