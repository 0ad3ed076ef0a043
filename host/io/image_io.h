/* SPDX-License-Identifier: MIT */
/* image_io.h: film output and EXR input. EXR through OpenEXR's C API (linear 32-bit float R, G, B,
 * optionally with named layers and header attributes; exr_write.c, exr_read.c), PNG through
 * stb_image_write (tone-mapped and sRGB-encoded after exposure; png_write.c). Images are linear
 * RGB float, RGB_CHANNELS floats a pixel, row 0 at the top. Files are written atomically
 * (base/fs.h: temporary name, flush, rename); fs_check_writable checks an output path before
 * rendering. */
#ifndef PT_IMAGE_IO_H
#define PT_IMAGE_IO_H

#include <stdbool.h>

#include "base/error.h"
#include "io/tonemap.h"

enum { RGB_CHANNELS = 3 };

/* A layer beside the beauty: channels "<name>.<letter>" for each letter of `channels` (OpenEXR's
 * layer convention, which Blender's compositor and the OpenEXR tools read as layers). */
typedef struct {
    const char *name;     /* "albedo" */
    const char *channels; /* "RGB", "XYZ", "Z", "Y": one channel a letter */
    const float *pixels;  /* width * height * strlen(channels) floats, interleaved, row 0 at the top */
} ImageLayer;

typedef enum { IMAGE_ATTR_INT, IMAGE_ATTR_FLOAT, IMAGE_ATTR_STRING } ImageAttrType;

/* A header attribute (the render's metadata): one of the values, as `type` says. */
typedef struct {
    const char *name;
    ImageAttrType type;
    int int_value;
    float float_value;
    const char *string_value;
} ImageAttribute;

/* The beauty (rgb, RGB_CHANNELS floats a pixel) with its layers and attributes. */
typedef struct {
    const float *rgb;
    int width, height;
    const ImageLayer *layers;
    int layer_count;
    const ImageAttribute *attributes;
    int attribute_count;
    const float *alpha; /* the beauty's A channel (one float a pixel); NULL: none */
} ExrImage;

/* One scanline part, 32-bit float channels (beauty R, G, B and every layer's), ZIP; non-finite
 * values are written as 0. */
bool image_write_exr_layers(const char *path, const ExrImage *image, Error *err);
/* The beauty alone, no attributes. */
bool image_write_exr(const char *path, const float *rgb, int width, int height, Error *err);
/* 8-bit sRGB after exposure and the tone curve (io/display_curve.h). */
bool image_write_png(const char *path, const float *rgb, int width, int height,
                     DisplaySettings display, Error *err);
/* Reads an RGB(A) EXR written by us or another tool; *rgb is malloc'ed. */
bool image_read_exr(const char *path, float **rgb, int *width, int *height, Error *err);

#endif
