// SPDX-License-Identifier: MIT
/* io/display_curve.h's tone curves against their published definitions, and the command line's
 * --tonemap / --exposure / --bloom checks. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/display_curve.h"
#include "support.h"

typedef struct {
    Tonemap tonemap;
    float in[3], out[3]; /* linear radiance; display-linear output, before the sRGB OETF */
} CurvePoint;

/* From tests/tonemap_reference.py: each curve re-implemented in double from its reference code
 * (three.js AgXToneMapping with its matrices inverted there, Hill's ACESFitted, Hable's
 * Uncharted2Tonemap, the Khronos PBR Neutral specification, three.js Reinhard), run once when this
 * test was written; the script says where each comes from. */
static const CurvePoint points[] = {
    {TONEMAP_AGX, {0, 0, 0}, {0, 0, 0}},
    {TONEMAP_AGX, {0.01, 0.01, 0.01}, {0.00599477127, 0.00599522954, 0.00599557083}},
    {TONEMAP_AGX, {0.18, 0.18, 0.18}, {0.214524295, 0.214520372, 0.214514509}},
    {TONEMAP_AGX, {0.5, 0.2, 0.05}, {0.444798391, 0.233077619, 0.101059608}},
    {TONEMAP_AGX, {1, 1, 1}, {0.590195809, 0.59016102, 0.59012355}},
    {TONEMAP_AGX, {2, 0.5, 0.1}, {0.816254644, 0.45382297, 0.263108114}},
    {TONEMAP_AGX, {0.1, 0.4, 3}, {0.291377713, 0.497888706, 0.916358837}},
    {TONEMAP_AGX, {16, 16, 16}, {0.995198282, 0.995108736, 0.995018087}},
    {TONEMAP_AGX, {100, 60, 10}, {0.996978349, 0.996878661, 0.996778974}},
    {TONEMAP_ACES, {0, 0, 0}, {0, 0, 0}},
    {TONEMAP_ACES, {0.01, 0.01, 0.01}, {0.00105253464, 0.00105253464, 0.00105252412}},
    {TONEMAP_ACES, {0.18, 0.18, 0.18}, {0.105591247, 0.105591247, 0.105590191}},
    {TONEMAP_ACES, {0.5, 0.2, 0.05}, {0.364497836, 0.128406351, 0.0225841368}},
    {TONEMAP_ACES, {1, 1, 1}, {0.619115427, 0.619115427, 0.619109236}},
    {TONEMAP_ACES, {2, 0.5, 0.1}, {0.901499261, 0.418689446, 0.105000791}},
    {TONEMAP_ACES, {0.1, 0.4, 3}, {0.178236453, 0.315639039, 0.890593632}},
    {TONEMAP_ACES, {16, 16, 16}, {0.98993531, 0.98993531, 0.989925411}},
    {TONEMAP_ACES, {100, 60, 10}, {1, 1, 0.993271538}},
    {TONEMAP_FILMIC, {0, 0, 0}, {0, 0, 0}},
    {TONEMAP_FILMIC, {0.01, 0.01, 0.01}, {0.00766365515, 0.00766365515, 0.00766365515}},
    {TONEMAP_FILMIC, {0.18, 0.18, 0.18}, {0.128338449, 0.128338449, 0.128338449}},
    {TONEMAP_FILMIC, {0.5, 0.2, 0.05}, {0.304300561, 0.141143665, 0.0379294202}},
    {TONEMAP_FILMIC, {1, 1, 1}, {0.492918546, 0.492918546, 0.492918546}},
    {TONEMAP_FILMIC, {2, 0.5, 0.1}, {0.713238011, 0.304300561, 0.0742147024}},
    {TONEMAP_FILMIC, {0.1, 0.4, 3}, {0.0742147024, 0.255308777, 0.837871185}},
    {TONEMAP_FILMIC, {16, 16, 16}, {1, 1, 1}},
    {TONEMAP_FILMIC, {100, 60, 10}, {1, 1, 1}},
    {TONEMAP_PBR_NEUTRAL, {0, 0, 0}, {0, 0, 0}},
    {TONEMAP_PBR_NEUTRAL, {0.01, 0.01, 0.01}, {0.000625, 0.000625, 0.000625}},
    {TONEMAP_PBR_NEUTRAL, {0.18, 0.18, 0.18}, {0.14, 0.14, 0.14}},
    {TONEMAP_PBR_NEUTRAL, {0.5, 0.2, 0.05}, {0.465625, 0.165625, 0.015625}},
    {TONEMAP_PBR_NEUTRAL, {1, 1, 1}, {0.869090909, 0.869090909, 0.869090909}},
    {TONEMAP_PBR_NEUTRAL, {2, 0.5, 0.1}, {0.96, 0.321135759, 0.150771961}},
    {TONEMAP_PBR_NEUTRAL, {0.1, 0.4, 3}, {0.239151463, 0.315417875, 0.976393443}},
    {TONEMAP_PBR_NEUTRAL, {16, 16, 16}, {0.99626943, 0.99626943, 0.99626943}},
    {TONEMAP_PBR_NEUTRAL, {100, 60, 10}, {0.999420756, 0.974179272, 0.942627416}},
    {TONEMAP_REINHARD, {0, 0, 0}, {0, 0, 0}},
    {TONEMAP_REINHARD, {0.01, 0.01, 0.01}, {0.0099009901, 0.0099009901, 0.0099009901}},
    {TONEMAP_REINHARD, {0.18, 0.18, 0.18}, {0.152542373, 0.152542373, 0.152542373}},
    {TONEMAP_REINHARD, {0.5, 0.2, 0.05}, {0.333333333, 0.166666667, 0.0476190476}},
    {TONEMAP_REINHARD, {1, 1, 1}, {0.5, 0.5, 0.5}},
    {TONEMAP_REINHARD, {2, 0.5, 0.1}, {0.666666667, 0.333333333, 0.0909090909}},
    {TONEMAP_REINHARD, {0.1, 0.4, 3}, {0.0909090909, 0.285714286, 0.75}},
    {TONEMAP_REINHARD, {16, 16, 16}, {0.941176471, 0.941176471, 0.941176471}},
    {TONEMAP_REINHARD, {100, 60, 10}, {0.99009901, 0.983606557, 0.909090909}},
    {TONEMAP_CLAMP, {0, 0, 0}, {0, 0, 0}},
    {TONEMAP_CLAMP, {0.01, 0.01, 0.01}, {0.01, 0.01, 0.01}},
    {TONEMAP_CLAMP, {0.18, 0.18, 0.18}, {0.18, 0.18, 0.18}},
    {TONEMAP_CLAMP, {0.5, 0.2, 0.05}, {0.5, 0.2, 0.05}},
    {TONEMAP_CLAMP, {1, 1, 1}, {1, 1, 1}},
    {TONEMAP_CLAMP, {2, 0.5, 0.1}, {1, 0.5, 0.1}},
    {TONEMAP_CLAMP, {0.1, 0.4, 3}, {0.1, 0.4, 1}},
    {TONEMAP_CLAMP, {16, 16, 16}, {1, 1, 1}},
    {TONEMAP_CLAMP, {100, 60, 10}, {1, 1, 1}},
};

/* 1e-4: a thousandth of an 8-bit step would pass; a transposed matrix, a wrong constant or a
 * missing 2.2 power moves these points by 1e-2 or more. */
#define CURVE_TOLERANCE 1e-4f

Test(tonemap, every_curve_matches_its_reference_at_the_tabulated_points)
{
    int per_curve[TONEMAP_COUNT] = {0};
    for (size_t i = 0; i < sizeof points / sizeof *points; i++) {
        const CurvePoint *p = &points[i];
        float out[3];
        display_tonemap_linear(p->tonemap, p->in, out);
        for (int c = 0; c < 3; c++)
            cr_expect(fabsf(out[c] - p->out[c]) <= CURVE_TOLERANCE,
                      "%s(%g, %g, %g)[%d] = %.7f, the reference says %.7f",
                      tonemap_name(p->tonemap), p->in[0], p->in[1], p->in[2], c, out[c], p->out[c]);
        per_curve[p->tonemap]++;
    }
    for (int t = 0; t < TONEMAP_COUNT; t++)
        cr_expect(per_curve[t] >= 8, "%s has %d tabulated points", tonemap_name((Tonemap)t),
                  per_curve[t]);
}

/* Over 1e-4 .. 1e4: a grey ramp never decreases in any channel, and a ramp of one channel (the
 * others fixed) never decreases in luminance; black is 0; everything in [0, 1] and finite. Single
 * channels may fall once they clip: AgX's outset and ACES' output matrix subtract the other
 * channels, which keep growing through the inset's crosstalk (the path to white); and AgX's
 * luminance along a green ramp dips by 7e-5 near 43 where the final clip to [0, 1] cuts a channel
 * (tonemap_reference.py's AgX does the same), hence 1e-4 on luminance. */
static float luminance(const float c[3])
{
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

Test(tonemap, curves_are_monotonic_black_at_zero_and_bounded)
{
    for (int t = 0; t < TONEMAP_COUNT; t++) {
        const char *name = tonemap_name((Tonemap)t);
        float zero[3] = {0, 0, 0}, out[3];
        display_tonemap_linear((Tonemap)t, zero, out);
        cr_expect(out[0] == 0.0f && out[1] == 0.0f && out[2] == 0.0f, "%s(0) = %g %g %g", name,
                  out[0], out[1], out[2]);
        for (int channel = -1; channel < 3; channel++) { /* -1: grey */
            float previous[3] = {0, 0, 0}, previous_luminance = 0.0f;
            for (int i = 0; i <= 4000; i++) {
                float x = 1e-4f * powf(10.0f, (float)i / 500.0f);
                float in[3] = {0.1f, 0.1f, 0.1f};
                for (int c = 0; c < 3; c++)
                    if (channel < 0 || c == channel)
                        in[c] = x;
                display_tonemap_linear((Tonemap)t, in, out);
                for (int c = 0; c < 3; c++) {
                    cr_assert(isfinite(out[c]) && out[c] >= 0.0f && out[c] <= 1.0f,
                              "%s(%g)[%d] = %g", name, x, c, out[c]);
                    /* 2e-6: float rounding in the matrices; a real reversal is far larger */
                    cr_assert(channel >= 0 || out[c] >= previous[c] - 2e-6f,
                              "%s not monotonic on grey at %g: %g < %g", name, x, out[c],
                              previous[c]);
                    previous[c] = out[c];
                }
                cr_assert(luminance(out) >= previous_luminance - 1e-4f,
                          "%s: luminance falls along channel %d at %g: %g < %g", name, channel, x,
                          luminance(out), previous_luminance);
                previous_luminance = luminance(out);
            }
        }
    }
}

/* PBR Neutral below the compression start (peak < 0.76 after the offset) is the input minus the
 * Fresnel offset: exactly c - 0.04 once min(c) >= 0.08, c - (x - 6.25 x^2) below. */
Test(tonemap, pbr_neutral_is_the_identity_minus_the_offset_below_compression)
{
    for (int i = 0; i < 100; i++) {
        float r = 0.08f + 0.0068f * (float)i, in[3] = {r, 0.5f * r + 0.04f, 0.09f}, out[3];
        display_tonemap_linear(TONEMAP_PBR_NEUTRAL, in, out);
        for (int c = 0; c < 3; c++)
            cr_expect(fabsf(out[c] - (in[c] - 0.04f)) <= 1e-6f, "in %g -> %g", in[c], out[c]);
    }
    float low[3] = {0.05f, 0.3f, 0.7f}, out[3];
    display_tonemap_linear(TONEMAP_PBR_NEUTRAL, low, out);
    float offset = 0.05f - 6.25f * 0.05f * 0.05f;
    for (int c = 0; c < 3; c++)
        cr_expect(fabsf(out[c] - (low[c] - offset)) <= 1e-6f, "toe: %g -> %g", low[c], out[c]);
}

/* The PNG pipeline: exposure scales before the curve, NaN and negatives are black, +Inf white,
 * and the result is the sRGB OETF of the curve's output. */
Test(tonemap, display_map_is_exposure_curve_then_srgb)
{
    for (int t = 0; t < TONEMAP_COUNT; t++) {
        float in[3] = {0.3f, 0.6f, 1.2f}, doubled[3] = {0.6f, 1.2f, 2.4f}, a[3], b[3], lin[3];
        display_map((Tonemap)t, 2.0f, in, a);
        display_map((Tonemap)t, 1.0f, doubled, b);
        display_tonemap_linear((Tonemap)t, doubled, lin);
        for (int c = 0; c < 3; c++) {
            cr_expect(a[c] == b[c], "%s: exposure x2 differs from doubling", tonemap_name(t));
            cr_expect(b[c] == display_srgb_from_linear(lin[c]), "%s: not the sRGB of the curve",
                      tonemap_name(t));
        }
        float nans[3] = {NAN, NAN, NAN}, negative[3] = {-5.0f, -1e-3f, -INFINITY};
        float infinite[3] = {INFINITY, INFINITY, INFINITY}, shown[3];
        display_map((Tonemap)t, 1.0f, nans, shown);
        cr_expect(shown[0] == 0.0f && shown[1] == 0.0f && shown[2] == 0.0f, "%s: NaN shows %g",
                  tonemap_name(t), shown[0]);
        display_map((Tonemap)t, 1.0f, negative, shown);
        cr_expect(shown[0] == 0.0f && shown[1] == 0.0f && shown[2] == 0.0f,
                  "%s: negative shows %g", tonemap_name(t), shown[0]);
        display_map((Tonemap)t, 1.0f, infinite, shown);
        for (int c = 0; c < 3; c++)
            cr_expect(shown[c] >= 0.99f && shown[c] <= 1.0f, "%s: +Inf shows %g",
                      tonemap_name(t), shown[c]);
    }
    float grey[3] = {0.18f, 0.18f, 0.18f}, clamp_out[3];
    display_map(TONEMAP_CLAMP, 1.0f, grey, clamp_out);
    cr_expect(clamp_out[0] == display_srgb_from_linear(0.18f), "clamp is today's sRGB curve");
}

/* The shader gets every curve as text from the same macros. */
Test(tonemap, the_shader_text_has_every_curve)
{
    const char *parts[] = {DISPLAY_CURVE_GLSL_PARTS NULL};
    size_t count = sizeof parts / sizeof *parts - 1;
    cr_assert_eq(count, 2 + TONEMAP_COUNT);
    cr_expect(strstr(parts[0], "float srgb_from_linear(float linear)"), "%s", parts[0]);
    cr_expect(strstr(parts[1], "void display_prepare(inout float r"), "%s", parts[1]);
    static const char *const enum_names[] = {"AGX", "ACES", "FILMIC", "PBR_NEUTRAL", "REINHARD",
                                             "CLAMP"};
    cr_assert_eq(sizeof enum_names / sizeof *enum_names, TONEMAP_COUNT);
    for (int t = 0; t < TONEMAP_COUNT; t++) {
        char head[64];
        snprintf(head, sizeof head, "void tonemap_%s(inout float r,", enum_names[t]);
        cr_expect(strstr(parts[2 + t], head), "%s", parts[2 + t]);
        /* GLSL 1.10 has no f suffix and no C helpers */
        cr_expect(!strstr(parts[2 + t], "display_"), "%s", parts[2 + t]);
    }
    cr_expect(strstr(parts[2 + TONEMAP_AGX], "4.026069") && strstr(parts[2 + TONEMAP_AGX], "log2("),
              "%s", parts[2 + TONEMAP_AGX]);
    cr_expect(strstr(parts[2 + TONEMAP_ACES], "0.0245786"), "%s", parts[2 + TONEMAP_ACES]);
}

typedef struct {
    int exit_code;
    char err[4096];
} Run;

static Run run_pt(const char *args)
{
    Run r = {0};
    char err_path[64], cmd[1024];
    snprintf(err_path, sizeof err_path, "/tmp/pt-tonemap-err-%d", (int)getpid());
    snprintf(cmd, sizeof cmd, "'%s' %s >/dev/null 2>%s", test_pt_bin(), args, err_path);
    int status = system(cmd);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    char *text = test_read_file(err_path, NULL);
    snprintf(r.err, sizeof r.err, "%s", text ? text : "");
    free(text);
    unlink(err_path);
    return r;
}

/* Bad values: one "pt: " line naming the option and the value, exit 1, before any rendering. */
Test(tonemap, bad_tonemap_exposure_and_bloom_values_give_one_line)
{
    static const struct {
        const char *args, *needle;
    } cases[] = {
        {"render scenes/cornell-box --tonemap agx2", "agx2"},
        {"render scenes/cornell-box --tonemap=", "--tonemap"},
        {"render scenes/cornell-box --exposure nan", "--exposure"},
        {"render scenes/cornell-box --exposure 1e9", "--exposure"},
        {"render scenes/cornell-box --bloom 1.5", "--bloom"},
        {"render scenes/cornell-box --bloom -0.1", "--bloom"},
        {"render scenes/cornell-box --bloom 0.5,0", "--bloom"},
        {"render scenes/cornell-box --bloom 0.5,1e6", "--bloom"},
        {"render scenes/cornell-box --bloom 0.5,abc", "--bloom"},
        {"view scenes/cornell-box --tonemap ACES", "ACES"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        Run r = run_pt(cases[i].args);
        cr_expect_eq(r.exit_code, 1, "%s: exit %d (%s)", cases[i].args, r.exit_code, r.err);
        const char *newline = strchr(r.err, '\n');
        cr_expect(strncmp(r.err, "pt: ", 4) == 0 && newline && newline[1] == '\0',
                  "%s: not one 'pt: ' line: %s", cases[i].args, r.err);
        cr_expect(strstr(r.err, cases[i].needle), "%s: '%s' not named: %s", cases[i].args,
                  cases[i].needle, r.err);
    }
}
