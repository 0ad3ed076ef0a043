// SPDX-License-Identifier: MIT
/* io/display_curve.h: the one display curve that the PNG writer runs in C and the viewer pastes
 * into its shader. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "io/display_curve.h"

Test(display_curve, srgb_values_and_edges)
{
    cr_expect_eq(display_srgb_from_linear(0.0f), 0.0f);
    cr_expect_eq(display_srgb_from_linear(1.0f), 1.0f);
    cr_expect_float_eq(display_srgb_from_linear(0.0031308f), 0.0404500f, 1e-6f, "the knee");
    cr_expect_float_eq(display_srgb_from_linear(0.5f), 0.7353570f, 1e-6f);
    cr_expect_float_eq(display_srgb_from_linear(0.18f), 0.4613561f, 1e-6f, "mid grey");
    cr_expect_eq(display_srgb_from_linear(NAN), 0.0f, "NaN shows black");
    cr_expect_eq(display_srgb_from_linear(INFINITY), 1.0f);
    cr_expect_eq(display_srgb_from_linear(-3.0f), 0.0f);
    cr_expect_eq(display_srgb_from_linear(7.0f), 1.0f);
    float previous = -1.0f;
    for (int i = 0; i <= 1000; i++) { /* monotonic, including across the knee */
        float v = display_srgb_from_linear((float)i / 1000.0f);
        cr_assert(v >= previous, "not monotonic at %d", i);
        previous = v;
    }
}

Test(display_curve, the_shader_text_is_the_same_expression)
{
    const char *glsl = DISPLAY_CURVE_GLSL_SRGB;
    cr_expect(strstr(glsl, "float srgb_from_linear(float linear)"), "%s", glsl);
    cr_expect(strstr(glsl, "clamp(linear, 0.0, 1.0)"), "%s", glsl);
    cr_expect(strstr(glsl, "12.92 * (x)") && strstr(glsl, "1.055 * pow((x), 1.0 / 2.4) - 0.055"),
              "%s", glsl);
}
