// SPDX-License-Identifier: MIT
/* bloom.c: the host side of bloom.h: the Gaussian's weights, the buffers, the two passes of
 * cl/post/bloom.cl, the read-back. */
#include "render/bloom.h"

#include <limits.h>
#include <math.h>

#include "io/image_io.h"

float bloom_default_radius(int width, int height)
{
    float radius = 0.01f * sqrtf((float)width * (float)width + (float)height * (float)height);
    return radius < 1.0f ? 1.0f : radius;
}

int bloom_weights(float radius, float *weights, int max_taps)
{
    int taps = (int)ceilf(radius);
    if (taps > max_taps - 1)
        taps = max_taps - 1;
    if (taps > (int)BLOOM_MAX_RADIUS)
        taps = (int)BLOOM_MAX_RADIUS;
    double sigma = radius / 3.0, sum = 0.0, exact[(int)BLOOM_MAX_RADIUS + 1];
    for (int k = 0; k <= taps; k++) {
        exact[k] = exp(-0.5 * (k / sigma) * (k / sigma));
        sum += k ? 2.0 * exact[k] : exact[k];
    }
    for (int k = 0; k <= taps; k++)
        weights[k] = (float)(exact[k] / sum);
    return taps;
}

static bool check_args(const float *rgb, int width, int height, float strength, float radius,
                       Error *err)
{
    if (!rgb || width < 1 || height < 1 ||
        (size_t)width * (size_t)height > INT_MAX / RGB_CHANNELS) {
        error_set(err, ERR_SETTINGS, NULL, 0, "bloom: a %dx%d image is not one it can work on", width,
                  height);
        return false;
    }
    if (!(strength >= 0.0f && strength <= 1.0f)) {
        error_set(err, ERR_SETTINGS, NULL, 0, "bloom: strength %g is not in [0, 1]", strength);
        return false;
    }
    if (!(radius == 0.0f || (radius >= 0.5f && radius <= BLOOM_MAX_RADIUS))) {
        error_set(err, ERR_SETTINGS, NULL, 0, "bloom: radius %g is not in [0.5, %g] pixels", radius,
                  BLOOM_MAX_RADIUS);
        return false;
    }
    return true;
}

static void release_buffers(cl_mem *buffers, int count)
{
    for (int i = 0; i < count; i++)
        if (buffers[i])
            device_release_buffer(buffers[i]);
}

bool bloom_apply_profiled(Device *dev, float *rgb, int width, int height, float strength,
                          float radius, double *kernel_ms, Error *err)
{
    if (!check_args(rgb, width, height, strength, radius, err))
        return false;
    if (strength == 0.0f)
        return true; /* the identity, bit for bit */
    float weights[(int)BLOOM_MAX_RADIUS + 1];
    cl_int taps = bloom_weights(radius > 0.0f ? radius : bloom_default_radius(width, height),
                                weights, (int)BLOOM_MAX_RADIUS + 1);
    size_t pixels = (size_t)width * (size_t)height, bytes = pixels * RGB_CHANNELS * sizeof(float);
    /* image: rgb, then the result; bright_part: its bright part; blurred: that blurred by rows. */
    cl_mem buffers[4] = {NULL, NULL, NULL, NULL};
    buffers[0] = device_buffer(dev, "bloom image", CL_MEM_READ_WRITE, bytes, rgb, err);
    if (buffers[0])
        buffers[1] = device_buffer(dev, "bloom bright part", CL_MEM_READ_WRITE, bytes, NULL, err);
    if (buffers[1])
        buffers[2] = device_buffer(dev, "bloom rows", CL_MEM_READ_WRITE, bytes, NULL, err);
    if (buffers[2])
        buffers[3] = device_buffer(dev, "bloom weights", CL_MEM_READ_ONLY,
                                   (size_t)(taps + 1) * sizeof(float), weights, err);
    cl_mem image = buffers[0], bright_part = buffers[1], blurred = buffers[2];
    cl_mem kernel_weights = buffers[3];
    if (!kernel_weights) {
        release_buffers(buffers, 4);
        return false;
    }
    cl_int w = width, h = height, n = (cl_int)pixels;
    cl_float threshold = BLOOM_THRESHOLD, s = strength;
    cl_kernel bright = device_kernel(dev, "bloom_bright_part");
    cl_kernel rows = device_kernel(dev, "bloom_blur_rows");
    cl_kernel columns = device_kernel(dev, "bloom_blur_columns_mix");
    KERNEL_ARGS(bright, 0, KARG(image), KARG(bright_part), KARG(n), KARG(threshold));
    KERNEL_ARGS(rows, 0, KARG(bright_part), KARG(blurred), KARG(kernel_weights), KARG(taps),
                KARG(w), KARG(h));
    KERNEL_ARGS(columns, 0, KARG(image), KARG(blurred), KARG(kernel_weights), KARG(taps), KARG(w),
                KARG(h), KARG(threshold), KARG(s));
    double ms[3] = {0.0, 0.0, 0.0};
    device_run(dev, bright, pixels, 0, kernel_ms ? &ms[0] : NULL);
    device_run(dev, rows, pixels, 0, kernel_ms ? &ms[1] : NULL);
    device_run(dev, columns, pixels, 0, kernel_ms ? &ms[2] : NULL);
    device_read(dev, image, 0, bytes, rgb);
    if (kernel_ms)
        *kernel_ms += ms[0] + ms[1] + ms[2];
    device_release_kernel(bright);
    device_release_kernel(rows);
    device_release_kernel(columns);
    release_buffers(buffers, 4);
    return true;
}

bool bloom_apply(Device *dev, float *rgb, int width, int height, float strength, float radius,
                 Error *err)
{
    return bloom_apply_profiled(dev, rgb, width, height, strength, radius, NULL, err);
}
