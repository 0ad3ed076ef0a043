/* SPDX-License-Identifier: MIT */
/* image_io.h: film output and EXR input. EXR through OpenEXR's C API (linear 32-bit float R, G, B;
 * exr_write.c, exr_read.c), PNG through stb_image_write (tone-mapped and sRGB-encoded after
 * exposure; png_write.c). Images are linear RGB float, RGB_CHANNELS floats a pixel, row 0 at the
 * top. Files are written atomically (base/fs.h: temporary name, flush, rename); fs_check_writable
 * checks an output path before rendering. */
#ifndef PT_IMAGE_IO_H
#define PT_IMAGE_IO_H

#include <stdbool.h>

#include "base/error.h"
#include "io/tonemap.h"

enum { RGB_CHANNELS = 3 };

bool image_write_exr(const char *path, const float *rgb, int width, int height, Error *err);
/* 8-bit sRGB after exposure and the tone curve (io/display_curve.h). */
bool image_write_png(const char *path, const float *rgb, int width, int height,
                     DisplaySettings display, Error *err);
/* Reads an RGB(A) EXR written by us or another tool; *rgb is malloc'ed. */
bool image_read_exr(const char *path, float **rgb, int *width, int *height, Error *err);

#endif
