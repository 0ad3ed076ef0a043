// SPDX-License-Identifier: MIT
/* png_write.c: the 8-bit sRGB preview through stb_image_write, after exposure and the tone
 * curve (io/display_curve.h), written atomically like the EXR. */
#include "io/image_io.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stb_image_write.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"
#include "io/display_curve.h"
#include "io/image_write.h"


typedef struct {
    FILE *file;
    bool failed;
} PngSink;

/* stbi_write_png ignores fwrite errors; writing through a callback lets us see them. */
static void png_sink_write(void *context, void *data, int size)
{
    PngSink *sink = context;
    if (fwrite(data, 1, (size_t)size, sink->file) != (size_t)size)
        sink->failed = true;
}

static bool png_write_file(const char *temp, const char *path, const unsigned char *pixels,
                           int width, int height, Error *err)
{
    PngSink sink = {.file = fopen(temp, "wb"), .failed = false};
    if (!sink.file) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot create %s (%s)", path, temp,
                  strerror(errno));
        return false;
    }
    int encoded = stbi_write_png_to_func(png_sink_write, &sink, width, height, RGB_CHANNELS,
                                         pixels, width * RGB_CHANNELS);
    int saved_errno = errno;
    bool closed = fclose(sink.file) == 0;
    if (!encoded || sink.failed || !closed) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: PNG write failed (%s)", path,
                  encoded ? strerror(saved_errno) : "encoder error");
        return false;
    }
    return true;
}

bool image_write_png(const char *path, const float *rgb, int width, int height,
                     DisplaySettings display, Error *err)
{
    if (!image_check_args(path, rgb, width, height, err))
        return false;
    if (!isfinite(display.exposure)) {
        error_set(err, ERR_SETTINGS, path, 0, "%s: exposure %g is not finite", path,
                  display.exposure);
        return false;
    }
    /* stb_image_write measures the image in int bytes. */
    size_t value_count = (size_t)width * (size_t)height * RGB_CHANNELS;
    if (value_count / (size_t)height / RGB_CHANNELS != (size_t)width || value_count > INT_MAX / 2) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: %dx%d is too large for PNG output", path,
                  width, height);
        return false;
    }
    if (!fs_check_writable(path, err))
        return false;
    unsigned char *pixels = malloc(value_count);
    if (!pixels) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: out of memory for %dx%d pixels", path, width,
                  height);
        return false;
    }
    float scale = exp2f(display.exposure);
    for (size_t i = 0; i < value_count; i += RGB_CHANNELS) {
        float linear[3], shown[3];
        for (int c = 0; c < 3; c++)
            linear[c] = image_finite_or_zero(rgb[i + (size_t)c]);
        display_map(display.tonemap, scale, linear, shown);
        for (int c = 0; c < 3; c++)
            pixels[i + (size_t)c] = (unsigned char)lrintf(shown[c] * 255.0f);
    }
    char temp[PATH_MAX];
    fs_temp_path(path, temp, sizeof temp);
    bool written = png_write_file(temp, path, pixels, width, height, err);
    free(pixels);
    return fs_finish_atomic_write(temp, path, written, err);
}
