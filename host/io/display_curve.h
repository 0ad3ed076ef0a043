/* SPDX-License-Identifier: MIT */
/* display_curve.h: linear radiance to display values, written once for both places that show an
 * image: the PNG writer (C, io/png_write.c) and the viewer's fragment shader (GLSL 1.10,
 * viewer/display.c). Every curve is a macro that expands to statements in the common subset of C
 * and GLSL 1.10, working in place on three float variables r, g, b (linear Rec.709/sRGB
 * primaries). C compiles the expansion (display_curve_<CURVE> below); the viewer pastes its text
 * into the shader (DISPLAY_CURVE_GLSL_PARTS), so the two cannot drift apart.
 *
 * The pipeline, the same in both: radiance x 2^exposure, DISPLAY_PREPARE (negative and NaN to 0,
 * huge to 1e15 so that the rational curves' squares stay finite in float), the curve (its output
 * is display-linear), then clamp to [0, 1] and the sRGB OETF (DISPLAY_SRGB_FROM_LINEAR).
 *
 * The curve macros take F, the prefix of the math functions they call (F##max, F##min, F##clamp,
 * F##pow, F##log2): empty for GLSL's built-ins, display_ for the C helpers below. Literals always
 * carry a decimal point (GLSL 1.10 has no int-to-float conversion and no f suffix). */
#ifndef PT_DISPLAY_CURVE_H
#define PT_DISPLAY_CURVE_H

#include <math.h>

#include "io/tonemap.h"

/* The exact piecewise sRGB OETF (IEC 61966-2-1) of x in [0, 1]; POW is C's pow or GLSL's. */
#define DISPLAY_SRGB_FROM_LINEAR(x, POW) \
    ((x) <= 0.0031308 ? 12.92 * (x) : 1.055 * POW((x), 1.0 / 2.4) - 0.055)

/* Variadic: the curves' text holds commas. */
#define DISPLAY_CURVE_STRING_(...) #__VA_ARGS__
#define DISPLAY_CURVE_STRING(...) DISPLAY_CURVE_STRING_(__VA_ARGS__)

/* (r, g, b) = M (r, g, b) with M given row by row. */
#define DISPLAY_MAT3(m00, m01, m02, m10, m11, m12, m20, m21, m22)                                \
    {                                                                                           \
        float r0 = r, g0 = g, b0 = b;                                                           \
        r = (m00) * r0 + (m01) * g0 + (m02) * b0;                                               \
        g = (m10) * r0 + (m11) * g0 + (m12) * b0;                                               \
        b = (m20) * r0 + (m21) * g0 + (m22) * b0;                                               \
    }

#define DISPLAY_PREPARE(F)                                                                      \
    r = F##clamp(r, 0.0, 1.0e15);                                                               \
    g = F##clamp(g, 0.0, 1.0e15);                                                               \
    b = F##clamp(b, 0.0, 1.0e15);

/* clamp: today's behaviour, the hard clip of the final clamp and nothing else. */
#define DISPLAY_TONEMAP_CLAMP(F)

/* reinhard: x / (1 + x) per channel (Reinhard et al. 2002, eq. 3, as three.js'
 * ReinhardToneMapping applies it), no white point: per channel keeps every value below 1, which a
 * luminance-only mapping does not for saturated colours. */
#define DISPLAY_TONEMAP_REINHARD(F)                                                             \
    r = r / (1.0 + r);                                                                          \
    g = g / (1.0 + g);                                                                          \
    b = b / (1.0 + b);

/* filmic: John Hable's Uncharted 2 curve with his published constants (A 0.15, B 0.50, C 0.10,
 * D 0.20, E 0.02, F 0.30), white point W = 11.2 and exposure bias 2 ("Filmic Tonemapping
 * Operators", filmicworlds.com, 2010), per channel; pt encodes with the sRGB OETF where the post
 * used pow(1/2.2). */
#define DISPLAY_HABLE(x)                                                                        \
    (((x) * (0.15 * (x) + 0.10 * 0.50) + 0.20 * 0.02) / ((x) * (0.15 * (x) + 0.50) + 0.20 * 0.30) \
     - 0.02 / 0.30)
#define DISPLAY_TONEMAP_FILMIC(F)                                                               \
    r = DISPLAY_HABLE(2.0 * r) / DISPLAY_HABLE(11.2);                                           \
    g = DISPLAY_HABLE(2.0 * g) / DISPLAY_HABLE(11.2);                                           \
    b = DISPLAY_HABLE(2.0 * b) / DISPLAY_HABLE(11.2);

/* aces: Stephen Hill's fit of the ACES RRT + sRGB ODT (github.com/TheRealMJP/BakingLab,
 * ACES.hlsl): sRGB -> AP1 with the RRT's saturation, the rational fit, back to sRGB. Without the
 * 1/0.6 exposure that three.js adds to match its older curve. */
#define DISPLAY_ACES_RRT_ODT(v) \
    (((v) * ((v) + 0.0245786) - 0.000090537) / ((v) * (0.983729 * (v) + 0.4329510) + 0.238081))
#define DISPLAY_TONEMAP_ACES(F)                                                                 \
    DISPLAY_MAT3(0.59719, 0.35458, 0.04823,                                                     \
                 0.07600, 0.90834, 0.01566,                                                     \
                 0.02840, 0.13383, 0.83777)                                                     \
    r = DISPLAY_ACES_RRT_ODT(r);                                                                \
    g = DISPLAY_ACES_RRT_ODT(g);                                                                \
    b = DISPLAY_ACES_RRT_ODT(b);                                                                \
    DISPLAY_MAT3(1.60475, -0.53108, -0.07367,                                                   \
                 -0.10208, 1.10813, -0.00605,                                                   \
                 -0.00327, -0.07276, 1.07602)

/* pbr-neutral: the Khronos PBR Neutral reference (github.com/KhronosGroup/ToneMapping,
 * PBR_Neutral/README.md and pbrNeutral.glsl): F90 = 0.04, compression from Ks = 0.8 - F90,
 * desaturation Kd = 0.15, highlights mixed toward the new peak as the specification says. Below
 * the compression start it is c - f, f the small toe offset. */
#define DISPLAY_TONEMAP_PBR_NEUTRAL(F)                                                          \
    {                                                                                           \
        float x = F##min(r, F##min(g, b));                                                      \
        float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;                                      \
        r -= offset;                                                                            \
        g -= offset;                                                                            \
        b -= offset;                                                                            \
        float peak = F##max(r, F##max(g, b));                                                   \
        if (peak >= 0.8 - 0.04) {                                                               \
            float d = 1.0 - (0.8 - 0.04);                                                       \
            float new_peak = 1.0 - d * d / (peak + d - (0.8 - 0.04));                           \
            r *= new_peak / peak;                                                               \
            g *= new_peak / peak;                                                               \
            b *= new_peak / peak;                                                               \
            float k = 1.0 - 1.0 / (0.15 * (peak - new_peak) + 1.0);                             \
            r = r * (1.0 - k) + new_peak * k;                                                   \
            g = g * (1.0 - k) + new_peak * k;                                                   \
            b = b * (1.0 - k) + new_peak * k;                                                   \
        }                                                                                       \
    }

/* agx: Troy Sobotka's AgX base look as Blender 4 ships it, in the form three.js
 * (src/renderers/shaders/ShaderChunk/tonemapping_pars_fragment.glsl.js, AgXToneMapping) and
 * Filament (PR 7236) use: sRGB -> Rec.2020 (BT.2407), the inset matrix, log2 encoding over
 * [-12.47393, 4.026069] EV (middle grey 0.18 at -10 .. +6.5 stops), the 6th-order polynomial fit of
 * the default-contrast sigmoid (Benjamin Wrensch, iolite-engine.com "Minimal AgX"), the outset
 * matrix, the 2.2 power back to linear, Rec.2020 -> sRGB. The inverses that three.js computes in
 * the shader (inverse()) are written out here, computed in double. No "punchy" or "golden" look. */
#define DISPLAY_AGX_ENCODE(x, F) \
    F##clamp((F##log2(F##max((x), 1.0e-10)) + 12.47393) / (4.026069 + 12.47393), 0.0, 1.0)
#define DISPLAY_AGX_SIGMOID(x)                                                                  \
    ((((((15.5 * (x) - 40.14) * (x) + 31.96) * (x) - 6.868) * (x) + 0.4298) * (x) + 0.1191) *   \
         (x) - 0.00232)
#define DISPLAY_TONEMAP_AGX(F)                                                                  \
    DISPLAY_MAT3(0.6274094404617216, 0.3292602521938686, 0.0432718935897224,                    \
                 0.0691248390441791, 0.9195486137864191, 0.01132076676217352,                   \
                 0.016423358026501966, 0.08804784762388682, 0.895616713685177)                  \
    r = F##max(r, 0.0);                                                                         \
    g = F##max(g, 0.0);                                                                         \
    b = F##max(b, 0.0);                                                                         \
    DISPLAY_MAT3(0.856627153315983, 0.0951212405381588, 0.0482516061458583,                     \
                 0.137318972929847, 0.761241990602591, 0.101439036467562,                       \
                 0.11189821299995, 0.0767994186031903, 0.811302368396859)                       \
    r = DISPLAY_AGX_ENCODE(r, F);                                                               \
    g = DISPLAY_AGX_ENCODE(g, F);                                                               \
    b = DISPLAY_AGX_ENCODE(b, F);                                                               \
    r = DISPLAY_AGX_SIGMOID(r);                                                                 \
    g = DISPLAY_AGX_SIGMOID(g);                                                                 \
    b = DISPLAY_AGX_SIGMOID(b);                                                                 \
    DISPLAY_MAT3(1.1271005818144368, -0.11060664309660322, -0.01649393871783457,                \
                 -0.1413297634984383, 1.1578237022162718, -0.016493938717834257,                \
                 -0.14132976349843826, -0.11060664309660294, 1.2519364065950402)                \
    r = F##pow(F##max(r, 0.0), 2.2);                                                            \
    g = F##pow(F##max(g, 0.0), 2.2);                                                            \
    b = F##pow(F##max(b, 0.0), 2.2);                                                            \
    DISPLAY_MAT3(1.6605, -0.5876, -0.0728,                                                      \
                 -0.1246, 1.1329, -0.0083,                                                      \
                 -0.0182, -0.1006, 1.1187)

/* The shader's functions as string literals, each one below the 4095 characters ISO C promises,
 * separated by commas for an array initializer (glShaderSource takes the array):
 * float srgb_from_linear(float linear) (clamp to [0, 1], then the OETF),
 * void display_prepare(inout float r, inout float g, inout float b), and
 * void tonemap_<CURVE>(inout float r, inout float g, inout float b) for every curve of
 * TONEMAP_CURVES. */
#define DISPLAY_CURVE_GLSL_SRGB                                                                 \
    "float srgb_from_linear(float linear) {\n"                                                  \
    "    float x = clamp(linear, 0.0, 1.0);\n"                                                  \
    "    return " DISPLAY_CURVE_STRING(DISPLAY_SRGB_FROM_LINEAR(x, pow)) ";\n"                  \
    "}\n"
#define DISPLAY_CURVE_GLSL_PREPARE                                                              \
    "void display_prepare(inout float r, inout float g, inout float b) {\n    "                 \
    DISPLAY_CURVE_STRING(DISPLAY_PREPARE()) "\n}\n"
#define DISPLAY_CURVE_GLSL_FUNCTION(e, name)                                                    \
    "void tonemap_" #e "(inout float r, inout float g, inout float b) {\n    "                  \
    DISPLAY_CURVE_STRING(DISPLAY_TONEMAP_##e()) "\n}\n",
#define DISPLAY_CURVE_GLSL_PARTS                                                                \
    DISPLAY_CURVE_GLSL_SRGB, DISPLAY_CURVE_GLSL_PREPARE, TONEMAP_CURVES(DISPLAY_CURVE_GLSL_FUNCTION)

/* The C side of F: GLSL's built-ins in float. fmaxf maps NaN to the other operand, so
 * DISPLAY_PREPARE shows NaN as black. */
static inline float display_max(float a, float b) { return fmaxf(a, b); }
static inline float display_min(float a, float b) { return fminf(a, b); }
static inline float display_clamp(float x, float lo, float hi) { return fminf(fmaxf(x, lo), hi); }
static inline float display_pow(float x, float y) { return powf(x, y); }
static inline float display_log2(float x) { return log2f(x); }

/* display_curve_<CURVE>(float rgb[3]): the curve in place, on prepared values. */
#define DISPLAY_CURVE_C(e, name)                                                                \
    static inline void display_curve_##e(float *rgb)                                            \
    {                                                                                           \
        float r = rgb[0], g = rgb[1], b = rgb[2];                                               \
        DISPLAY_TONEMAP_##e(display_)                                                           \
        rgb[0] = r, rgb[1] = g, rgb[2] = b;                                                     \
    }
TONEMAP_CURVES(DISPLAY_CURVE_C)
#undef DISPLAY_CURVE_C

/* The sRGB OETF in C for a display-linear value: NaN shows as 0, +Inf and everything above 1
 * as 1. */
static inline float display_srgb_from_linear(float linear)
{
    double x = fmin(fmax((double)linear, 0.0), 1.0); /* fmax maps NaN to 0 */
    return (float)DISPLAY_SRGB_FROM_LINEAR(x, pow);
}

/* Linear radiance already scaled by 2^exposure to display-linear values in [0, 1] through the
 * curve (before the sRGB OETF). */
static inline void display_tonemap_linear(Tonemap tonemap, const float in[3], float out[3])
{
    float r = in[0], g = in[1], b = in[2];
    DISPLAY_PREPARE(display_)
    float rgb[3] = {r, g, b};
    switch (tonemap) {
#define DISPLAY_CURVE_CASE(e, name) case TONEMAP_##e: display_curve_##e(rgb); break;
        TONEMAP_CURVES(DISPLAY_CURVE_CASE)
#undef DISPLAY_CURVE_CASE
    default: break; /* not a curve: treated as clamp */
    }
    for (int c = 0; c < 3; c++)
        out[c] = display_clamp(rgb[c], 0.0f, 1.0f);
}

/* The whole pipeline for one pixel: sRGB-encoded display values in [0, 1]. */
static inline void display_map(Tonemap tonemap, float exposure_scale, const float linear[3],
                               float out[3])
{
    float scaled[3] = {linear[0] * exposure_scale, linear[1] * exposure_scale,
                       linear[2] * exposure_scale};
    display_tonemap_linear(tonemap, scaled, out);
    for (int c = 0; c < 3; c++)
        out[c] = display_srgb_from_linear(out[c]);
}

#endif
