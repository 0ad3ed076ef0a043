/* SPDX-License-Identifier: MIT */
/* display_curve.h: linear radiance to display values, written once for both places that show an
 * image: the PNG writer (C, io/image_io.c) and the viewer's fragment shader (GLSL 1.10,
 * viewer/display.c). The curve is one expression in the common subset of C and GLSL; C expands
 * it as code, the viewer pastes its text into the shader (DISPLAY_CURVE_GLSL), so the two cannot
 * drift apart. Exposure (a scale of 2^EV) is applied before the curve by both. */
#ifndef PT_DISPLAY_CURVE_H
#define PT_DISPLAY_CURVE_H

#include <math.h>

/* The exact piecewise sRGB OETF (IEC 61966-2-1) of x in [0, 1]; POW is C's pow or GLSL's. */
#define DISPLAY_SRGB_FROM_LINEAR(x, POW) \
    ((x) <= 0.0031308 ? 12.92 * (x) : 1.055 * POW((x), 1.0 / 2.4) - 0.055)

#define DISPLAY_CURVE_STRING_(text) #text
#define DISPLAY_CURVE_STRING(text) DISPLAY_CURVE_STRING_(text)

/* The shader's float srgb_from_linear(float linear): clamp to [0, 1], then the curve. */
#define DISPLAY_CURVE_GLSL                                                                      \
    "float srgb_from_linear(float linear) {\n"                                                  \
    "    float x = clamp(linear, 0.0, 1.0);\n"                                                  \
    "    return " DISPLAY_CURVE_STRING(DISPLAY_SRGB_FROM_LINEAR(x, pow)) ";\n"                  \
    "}\n"

/* The same in C, for a linear value already scaled by the exposure: NaN shows as 0, +Inf and
 * everything above 1 as 1. */
static inline float display_srgb_from_linear(float linear)
{
    double x = fmin(fmax((double)linear, 0.0), 1.0); /* fmax maps NaN to 0 */
    return (float)DISPLAY_SRGB_FROM_LINEAR(x, pow);
}

#endif
