/* SPDX-License-Identifier: MIT */
/* viewer_display.h: the film on screen with OpenGL 2.1 (what Mesa's llvmpipe and every desktop
 * driver offer). The linear film is streamed through a pixel buffer object into a float texture and
 * drawn as one quad; a fragment shader applies the exposure and the tone curve of the PNG writer
 * (io/display_curve.h), so the window shows what 'pt render' writes. Needs a current GL context. */
#ifndef PT_VIEWER_DISPLAY_H
#define PT_VIEWER_DISPLAY_H

#include <stdbool.h>

#include "base/error.h"
#include "io/tonemap.h"

typedef struct {
    unsigned texture, pixel_buffer, program;
    int exposure_scale_location, tonemap_location;
    int width, height; /* the texture's size: the film's */
} ViewerDisplay;

/* Compiles the shader and allocates a width x height texture; ERR_SYSTEM if the GL lacks shaders
 * or float textures. */
bool viewer_display_create(ViewerDisplay *d, int width, int height, Error *err);
void viewer_display_resize(ViewerDisplay *d, int width, int height);

/* The film streamed into the texture: a pointer to width * height * 3 floats (row 0 at the top)
 * that the caller fills, then viewer_display_upload_end. Between the two, no other GL call. */
float *viewer_display_upload_begin(ViewerDisplay *d);
void viewer_display_upload_end(ViewerDisplay *d);

/* Draws the film over the whole viewport (framebuffer_width x framebuffer_height). */
void viewer_display_draw(const ViewerDisplay *d, DisplaySettings display, int framebuffer_width,
                         int framebuffer_height);

/* What was drawn into the back buffer (call before swapping) as an 8-bit sRGB PNG. */
bool viewer_display_save_screenshot(const char *path, int width, int height, Error *err);

void viewer_display_destroy(ViewerDisplay *d);

#endif
