/* SPDX-License-Identifier: MIT */
/* image_io.h: film output. EXR through OpenEXR's C API (linear 32-bit float R, G, B), PNG
 * through stb_image_write (sRGB-encoded after exposure). Images are linear RGB float, 3 floats a
 * pixel, row 0 at the top. Files are written to a temporary name and renamed. */
#ifndef PT_IMAGE_IO_H
#define PT_IMAGE_IO_H

#include <stdbool.h>

#include "base/error.h"

bool image_write_exr(const char *path, const float *rgb, int width, int height, Error *err);
bool image_write_png(const char *path, const float *rgb, int width, int height, float exposure,
                     Error *err);
/* Reads an RGB(A) EXR written by us or another tool; *rgb is malloc'ed. */
bool image_read_exr(const char *path, float **rgb, int *width, int *height, Error *err);
/* Called once a file's temporary copy is complete, just before it is renamed into place (pt's
 * signal tests raise a signal there: the rename must still happen). NULL = none. */
void image_set_before_rename_hook(void (*hook)(void));
/* Checks before rendering that path can be created (folder exists and is writable). */
bool image_check_writable(const char *path, Error *err);

#endif
