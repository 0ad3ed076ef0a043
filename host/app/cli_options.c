// SPDX-License-Identifier: MIT
/* cli_options.c: the table of options (app/cli_options.h) and the readers of their values. */
#include "app/cli_options.h"

#include "base/fs.h"
#include "io/gltf_loader.h"
#include "io/obj_loader.h"
#include "io/ply_reader.h"
#include "render/aov_layers.h"
#include "render/denoise.h"
#include "render/session.h"
#include "scene/import_mitsuba.h"
#include "scene/sampler.h"
#include "scene/scene.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool parse_int(const char *arg, const char *value, int min, int max, int *out, Error *err)
{
    if (!value) {
        error_set(err, ERR_USAGE, NULL, 0, "%s needs a value", arg);
        return false;
    }
    char *end;
    errno = 0;
    long v = strtol(value, &end, 10);
    if (errno || end == value || *end || v < min || v > max) {
        error_set(err, ERR_USAGE, NULL, 0, "%s: '%s' is not an integer in [%d, %d]", arg, value, min,
                  max);
        return false;
    }
    *out = (int)v;
    return true;
}

/* A finite number in [min, max]. */
static bool parse_number(const char *arg, const char *value, double min, double max, double *out,
                         Error *err)
{
    char *end;
    double v = value ? strtod(value, &end) : 0.0;
    if (!value || end == value || *end || !isfinite(v) || v < min || v > max) {
        error_set(err, ERR_USAGE, NULL, 0, "%s: '%s' is not a number in [%g, %g]", arg,
                  value ? value : "", min, max);
        return false;
    }
    *out = v;
    return true;
}

static bool parse_float_in(const char *arg, const char *value, double min, double max, float *out,
                           Error *err)
{
    double v;
    if (!parse_number(arg, value, min, max, &v, err))
        return false;
    *out = (float)v;
    return true;
}

/* The seed is a 32-bit unsigned: 0 to 4294967295 (strtoul alone would take "-1" as ULONG_MAX). */
static bool parse_seed(const char *arg, const char *value, Options *o, Error *err)
{
    char *end;
    errno = 0;
    unsigned long long v = strtoull(value, &end, 10);
    if (errno || end == value || *end || value[strspn(value, " \t")] == '-' || v > UINT_MAX) {
        error_set(err, ERR_USAGE, NULL, 0, "%s: '%s' is not an integer in [0, %u]", arg, value,
                  UINT_MAX);
        return false;
    }
    o->seed = (unsigned)v;
    o->seed_given = true;
    return true;
}

static bool parse_up(const char *arg, const char *v, Options *o, Error *err)
{
    if (!strcmp(v, "y") || !strcmp(v, "Y")) o->up_axis = UP_AXIS_Y;
    else if (!strcmp(v, "z") || !strcmp(v, "Z")) o->up_axis = UP_AXIS_Z;
    else {
        error_set(err, ERR_USAGE, NULL, 0, "%s: '%s' is not y or z", arg, v);
        return false;
    }
    return true;
}

static bool parse_instancing(const char *arg, const char *v, Options *o, Error *err)
{
    (void)arg;
    if (!strcmp(v, "auto")) o->instancing = INSTANCING_AUTO;
    else if (!strcmp(v, "always")) o->instancing = INSTANCING_ALWAYS;
    else if (!strcmp(v, "never")) o->instancing = INSTANCING_NEVER;
    else {
        error_set(err, ERR_USAGE, NULL, 0, "--instancing: '%s' is not auto, always or never", v);
        return false;
    }
    return true;
}

static bool parse_aov(const char *arg, const char *v, Options *o, Error *err)
{
    (void)arg;
    return aov_parse_list(v, &o->aov_mask, err);
}

static bool parse_denoise_device(const char *arg, const char *v, Options *o, Error *err)
{
    DenoiseDevice device;
    if (!denoise_device_from_name(v, &device)) {
        error_set(err, ERR_USAGE, NULL, 0, "%s: '%s' is not a denoising device (auto, cpu or gpu)",
                  arg, v);
        return false;
    }
    o->denoise_device = (int)device;
    return true;
}

static bool parse_tonemap(const char *arg, const char *v, Options *o, Error *err)
{
    (void)arg;
    if (tonemap_from_name(v, &o->tonemap))
        return true;
    char known[128] = "";
    for (int t = 0; t < TONEMAP_COUNT; t++)
        snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s", t ? ", " : "",
                 tonemap_name((Tonemap)t));
    error_set(err, ERR_USAGE, NULL, 0, "--tonemap: '%s' is not a tone map (%s)", v, known);
    return false;
}

static bool parse_sampler(const char *arg, const char *v, Options *o, Error *err)
{
    if (sampler_from_name(v, &o->sampler))
        return true;
    error_set(err, ERR_USAGE, NULL, 0, "%s: '%s' is not a sampler (sobol, independent)", arg, v);
    return false;
}

/* --bloom STRENGTH[,RADIUS]: strength in [0, 1] (the share of the bright part's energy spread
 * out), radius in pixels. */
static bool parse_bloom(const char *arg, const char *value, Options *o, Error *err)
{
    (void)arg;
    char strength[64];
    size_t len = strcspn(value, ",");
    if (len >= sizeof strength) {
        error_set(err, ERR_USAGE, NULL, 0, "--bloom: '%s' is not STRENGTH[,RADIUS]", value);
        return false;
    }
    memcpy(strength, value, len);
    strength[len] = '\0';
    if (!parse_float_in("--bloom (strength)", strength, 0.0, 1.0, &o->bloom_strength, err))
        return false;
    return !value[len] ||
           parse_float_in("--bloom (radius in pixels)", value + len + 1, 0.5, 1024.0,
                          &o->bloom_radius, err);
}

static bool parse_quiet(const char *arg, const char *value, Options *o, Error *err)
{
    (void)arg, (void)value, (void)err;
    o->quiet = true;
    obj_loader_set_quiet(true);  /* MTL statements pt does not use: no warnings */
    gltf_loader_set_quiet(true); /* nor glTF extensions pt ignores */
    ply_reader_set_quiet(true);  /* nor PLY header lines of other writers */
    device_set_build_notice(false); /* nor the first-time kernel build */
    return true;
}

/* -D NAME=VALUE: a Mitsuba scene parameter ($NAME), repeatable; kept by the importer. */
static bool parse_define(const char *arg, const char *value, Options *o, Error *err)
{
    (void)arg, (void)o;
    return mitsuba_import_define(value, err);
}

/* Paths named inside glTF, MTL and foreign scene files stay inside their file's folder unless
 * this is given (base/fs.h fs_resolve_inside): a render service may be handed untrusted scenes. */
static bool parse_allow_outside_paths(const char *arg, const char *value, Options *o, Error *err)
{
    (void)arg, (void)value, (void)o, (void)err;
    fs_set_allow_outside_paths(true);
    return true;
}


/* The columns between kind and commands, per kind. */
#define INT(f, lo, hi) ARG_INT, offsetof(Options, f), lo, hi, NULL, NULL
#define FLOAT(f, lo, hi) ARG_FLOAT, offsetof(Options, f), lo, hi, NULL, NULL
#define NUMBER(f, lo, hi) ARG_NUMBER, offsetof(Options, f), lo, hi, NULL, NULL
#define TEXT(f) ARG_TEXT, offsetof(Options, f), 0, 0, NULL, NULL
#define FLAG(f) ARG_FLAG, offsetof(Options, f), 0, 0, NULL, NULL
#define SET(f, v) ARG_SET, offsetof(Options, f), v, v, NULL, NULL
#define CUSTOM(fn) ARG_CUSTOM, 0, 0, 0, fn, NULL
#define CUSTOM_FLAG(fn) ARG_CUSTOM_FLAG, 0, 0, 0, fn, NULL
#define HELP_ONLY ARG_HELP_ONLY, 0, 0, 0, NULL, NULL
/* An option whose value render/ checks again (the scene may change what is valid) and names by
 * the RenderSettings field it sets. */
#define INT_SETTING(f, lo, hi, setting) ARG_INT, offsetof(Options, f), lo, hi, NULL, setting
#define FLOAT_SETTING(f, lo, hi, setting) ARG_FLOAT, offsetof(Options, f), lo, hi, NULL, setting
#define COMMAND(c) SET(command, c)

/* Who takes what: an option a command would ignore is refused (cli.c), so each set is what the
 * command uses. pt bench takes --clamp (its modes measure the render pt render does with it) but
 * not adaptive sampling (its unit modes cannot run it, and Mpaths/s of a render that stops pixels
 * early compares nothing), nor the switches its modes measure both ways. pt view takes --clamp and
 * adaptive sampling, as the scene's render.noise_threshold already was: the film at --spp N is
 * pt render's. */
#define RENDER CMD_BIT(CMD_RENDER)
#define VIEW CMD_BIT(CMD_VIEW)
#define BENCH CMD_BIT(CMD_BENCH)
#define SCENE_COMMANDS (RENDER | VIEW | BENCH)
#define TONEMAP CMD_BIT(CMD_TONEMAP)
#define EVERY_COMMAND (SCENE_COMMANDS | CMD_BIT(CMD_DEVICES) | TONEMAP)

/* In `pt help` order. */
const CliOption cli_options[] = {
    {"spp", 0, INT(spp, 1, INT_MAX), SCENE_COMMANDS, HELP_OPTIONS, "--spp N",
     "samples per pixel (default: the scene's, else 64)"},
    {"max-depth", 0, INT(max_depth, 1, MAX_DEPTH_LIMIT), SCENE_COMMANDS, HELP_OPTIONS, "--max-depth D",
     "path segments from the camera: 1 = emitters seen directly,\n"
     "                     2 adds direct light (default: the scene's, else 8)"},
    {"width", 0, INT(width, 1, FILM_SIZE_LIMIT), SCENE_COMMANDS, HELP_OPTIONS,
     "--width W, --height H", "film size (default: the scene's, else 512x512)"},
    {"height", 0, INT(height, 1, FILM_SIZE_LIMIT), SCENE_COMMANDS, HELP_OPTIONS, "--height H", NULL},
    {"seed", 0, CUSTOM(parse_seed), SCENE_COMMANDS, HELP_OPTIONS, "--seed S",
     "random seed (default 0); the image is a pure function of scene,\n"
     "                     settings, seed and spp"},
    {"sampler", 0, CUSTOM(parse_sampler), SCENE_COMMANDS, HELP_OPTIONS, "--sampler NAME",
     "sobol (default: Owen-scrambled Sobol, lower error) or independent;\n"
     "                     the scene's render.sampler unless given"},
    {"define", 'D', CUSTOM(parse_define), SCENE_COMMANDS, HELP_OPTIONS, "-D NAME=VALUE",
     "a Mitsuba scene's parameter $NAME (overrides its <default>);\n"
     "                     repeatable"},
    {"device", 0, TEXT(device), SCENE_COMMANDS | TONEMAP, HELP_OPTIONS, "--device gpu|cpu|P:D",
     "OpenCL device (default: first GPU, else first CPU)"},
    {"device", 0, HELP_ONLY, 0, HELP_OPTIONS, "--device all|P:D,P:D,...",
     "render on several devices at once (all: every GPU, or\n"
     "                     every CPU device where there is none): the same image"},
    {"checkpoint", 0, NUMBER(checkpoint_seconds, 1e-3, 1e9), RENDER, HELP_OPTIONS, "--checkpoint S",
     "every S seconds, save the film beside the output (OUTPUT.ptckpt,\n"
     "                     written atomically); --resume continues from it"},
    {"resume", 0, FLAG(resume), RENDER, HELP_OPTIONS, "--resume",
     "continue the render of the checkpoint beside the output (the\n"
     "                     same scene and settings, or it is refused): the same bits as an\n"
     "                     uninterrupted render"},
    {"unit-spp", 0, INT(unit_spp, 1, INT_MAX), RENDER | BENCH, HELP_OPTIONS,
     "--unit-spp N, --unit-rows N",
     "work unit: N samples of a band of N rows (defaults:\n"
     "                     1 sample, bands of at most 2^20 pixels); the image is the same\n"
     "                     for every unit size"},
    {"unit-rows", 0, INT(unit_rows, 1, FILM_SIZE_LIMIT), RENDER | BENCH, HELP_OPTIONS, "--unit-rows N",
     NULL},
    {"output", 'o', TEXT(output), RENDER | TONEMAP, HELP_OPTIONS, "-o FILE",
     "output .exr (linear) or .png (sRGB); overwrites FILE. Without -o:\n"
     "                     out/<scene>.exr and .png, numbered so nothing is overwritten"},
    {"preview", 0, FLAG(preview), RENDER, HELP_OPTIONS, "--preview", "with -o FILE.exr, also write FILE.png"},
    {"exposure", 0, FLOAT(exposure, -64.0, 64.0), RENDER | VIEW | TONEMAP, HELP_OPTIONS, "--exposure EV",
     "exposure in stops for PNG output and the viewer (default 0)"},
    {"tonemap", 0, CUSTOM(parse_tonemap), RENDER | VIEW | TONEMAP, HELP_OPTIONS, "--tonemap NAME",
     "display curve for PNG output and the viewer (EXR stays linear):\n"
     "                     agx (default, Blender's look), aces (Hill's fit), filmic (Hable),\n"
     "                     pbr-neutral (Khronos), reinhard (per channel), clamp (hard clip)"},
    {"bloom", 0, CUSTOM(parse_bloom), RENDER | VIEW | TONEMAP, HELP_OPTIONS, "--bloom S[,R]",
     "glow around bright areas for PNG and the viewer (the EXR stays\n"
     "                     linear, without it): a share S in [0, 1] of the light above\n"
     "                     luminance 1 spread by a Gaussian of radius R pixels (3 sigma;\n"
     "                     default 1% of the image diagonal)"},
    {"clamp", 0, FLOAT_SETTING(clamp_max, 1e-6, 1e30, "clamp_indirect"), SCENE_COMMANDS,
     HELP_OPTIONS, "--clamp MAX",
     "clamp each indirect sample's radiance to MAX (removes fireflies,\n"
     "                     biases the image; off by default)"},
    {"aov", 0, CUSTOM(parse_aov), RENDER, HELP_OPTIONS, "--aov LIST",
     "add layers to the EXR beside the image: albedo, normal, depth,\n"
     "                     variance, spp (comma-separated) or all"},
    {"denoise", 0, FLAG(denoise), RENDER | VIEW, HELP_OPTIONS, "--denoise",
     "denoise the image with Intel Open Image Denoise (albedo and normal\n"
     "                     guides); the EXR keeps the raw image as noisy.R/G/B. pt view:\n"
     "                     start with the denoised view (Ctrl+D toggles it)"},
    {"denoise-device", 0, CUSTOM(parse_denoise_device), RENDER | VIEW, HELP_OPTIONS,
     "--denoise-device D",
     "auto (default: OIDN's CUDA device when rendering on an NVIDIA GPU,\n"
     "                     else its CPU device), cpu or gpu"},
    {"noise-threshold", 0, FLOAT_SETTING(noise_threshold, 1e-9, 1e9, "noise_threshold"),
     RENDER | VIEW, HELP_OPTIONS,
     "--noise-threshold T",
     "adaptive sampling: pixels stop once their relative error is\n"
     "                     below T (after --min-spp samples); --spp is the most a pixel gets"},
    {"min-spp", 0, INT_SETTING(min_spp, 1, INT_MAX, "min_spp"), RENDER | VIEW, HELP_OPTIONS,
     "--min-spp N",
     "samples every pixel gets before adaptive sampling decides"},
    {"time-limit", 0, NUMBER(time_limit, 1e-3, 1e9), RENDER, HELP_OPTIONS, "--time-limit S",
     "stop after S seconds of rendering, at a whole sample: the image is\n"
     "                     marked partial, the exit status is 0"},
    {"camera", 0, TEXT(camera_json), SCENE_COMMANDS, HELP_OPTIONS, "--camera JSON",
     "replace the scene's camera (render) or set the start pose (view),\n"
     "                     e.g. '{\"eye\": [0, 1, 3.9], \"target\": [0, 1, 0]}'"},
    {"no-nee", 0, FLAG(no_nee), SCENE_COMMANDS, HELP_OPTIONS, "--no-nee",
     "pure BSDF sampling (validation; same converged image)"},
    {"sort-materials", 0, SET(sort_materials, SORT_MATERIALS_ON), RENDER | VIEW, HELP_OPTIONS,
     "--sort-materials, --no-sort-materials",
     "shade paths grouped by the material they hit,\n"
     "                     or not (same image). Default: sorted when the scene has materials\n"
     "                     beyond Lambert, smooth mirrors and glass (pt bench measures both)"},
    {"no-sort-materials", 0, SET(sort_materials, SORT_MATERIALS_OFF), RENDER | VIEW, HELP_OPTIONS,
     "--no-sort-materials", NULL},
    {"no-compaction", 0, FLAG(no_compaction), RENDER | VIEW, HELP_OPTIONS, "--no-compaction",
     "keep dead paths in the wavefront (validation; same image)"},
    {"instancing", 0, CUSTOM(parse_instancing), SCENE_COMMANDS, HELP_OPTIONS,
     "--instancing auto|always|never",
     "how objects become instances (same image): auto\n"
     "                     merges objects without a transform whose file is used once into\n"
     "                     one mesh and instances the rest (two-level BVH, or one flat BVH\n"
     "                     over static instances of at most 2^20 triangles); always instances\n"
     "                     every object, with two levels; never bakes every static object's\n"
     "                     transform into its vertices (memory grows with the objects)"},
    {"profile", 0, FLAG(profile), RENDER, HELP_OPTIONS, "--profile", "per-kernel timing table"},
    {"no-cache", 0, FLAG(no_cache), SCENE_COMMANDS, HELP_OPTIONS, "--no-cache",
     "compile the kernels even if the kernel cache ($XDG_CACHE_HOME/pt,\n"
     "                     default ~/.cache/pt) holds them"},
    {"no-default-light", 0, FLAG(no_default_light), SCENE_COMMANDS, HELP_OPTIONS, "--no-default-light",
     "no default rig: a scene without any light (no emissive triangles,\n"
     "                     lights, environment or background) stays black, a bare model\n"
     "                     with tiny emitters keeps only them. By default they get the\n"
     "                     default rig (a sky, a sun, and under a bare model a ground;\n"
     "                     README \"The first image\") and a warning"},
    {"no-ground", 0, FLAG(no_ground), SCENE_COMMANDS, HELP_OPTIONS, "--no-ground",
     "the default rig without its ground"},
    {"up", 0, CUSTOM(parse_up), SCENE_COMMANDS, HELP_OPTIONS, "--up y|z",
     "which axis of a bare model is up, for its framing and the default\n"
     "                     rig (default y; z for Blender or CAD exports in Z-up)"},
    {"frame", 0, FLAG(frame), SCENE_COMMANDS, HELP_OPTIONS, "--frame",
     "ignore the file's own camera: frame the model in a 3/4 view"},
    {"allow-outside-paths", 0, CUSTOM_FLAG(parse_allow_outside_paths), SCENE_COMMANDS, HELP_OPTIONS,
     "--allow-outside-paths",
     "let glTF, MTL and imported scene files name files outside their\n"
     "                     own folder (absolute paths, \"..\" above it); a JSON scene's\n"
     "                     own paths are never confined"},
    {"quiet", 'q', CUSTOM_FLAG(parse_quiet), EVERY_COMMAND, HELP_OPTIONS, "--quiet",
     "no progress output (and no summary)"},
    {"progress", 0, FLAG(progress), RENDER, HELP_OPTIONS, "--progress",
     "progress lines at most once a second. Without it, progress goes\n"
     "                     to stderr as one line rewritten in place on a terminal, else as\n"
     "                     lines \"pt: progress: D/N spp (P%), S s\" after the first window,\n"
     "                     at most every 5 s, and at the end"},
    {"camera", 0, HELP_ONLY, 0, HELP_VIEW, "--camera JSON",
     "start pose (keys of the scene's camera; the C key prints one)"},
    {"frames", 0, INT(frames, 1, INT_MAX), VIEW, HELP_VIEW, "--frames N", "quit after N frames"},
    {"screenshot", 0, TEXT(screenshot), VIEW, HELP_VIEW, "--screenshot FILE",
     "at exit, save the film as FILE.exr (linear, as pt render writes it)\n"
     "                     or else the window's framebuffer as a PNG"},
    {"events", 0, FLAG(print_events), VIEW, HELP_VIEW, "--events",
     "print a line on stdout per input event read and per state change\n"
     "                     ('event: converged N spp'), for scripts and tests to wait on"},
    {"csv", 0, TEXT(csv), BENCH, HELP_NONE, "--csv FILE", NULL},
    {"help", 'h', COMMAND(CMD_HELP), EVERY_COMMAND, HELP_NONE, "--help", NULL},
    {"version", 0, COMMAND(CMD_VERSION), EVERY_COMMAND, HELP_NONE, "--version", NULL},
};
const size_t cli_option_count = sizeof cli_options / sizeof cli_options[0];

bool cli_option_parse(const CliOption *c, const char *arg, const char *value, Options *o,
                      Error *err)
{
    void *field = (char *)o + c->field;
    if (cli_option_takes_value(c) && !value) {
        error_set(err, ERR_USAGE, NULL, 0, "%s needs a value", arg);
        return false;
    }
    switch (c->kind) {
    case ARG_INT: return parse_int(arg, value, (int)c->min, (int)c->max, field, err);
    case ARG_FLOAT: return parse_float_in(arg, value, c->min, c->max, field, err);
    case ARG_NUMBER: return parse_number(arg, value, c->min, c->max, field, err);
    case ARG_TEXT: *(const char **)field = value; return true;
    case ARG_FLAG: *(bool *)field = true; return true;
    case ARG_SET: *(int *)field = (int)c->min; return true;
    case ARG_CUSTOM:
    case ARG_CUSTOM_FLAG: return c->parse(arg, value, o, err);
    case ARG_HELP_ONLY: break;
    }
    return true;
}
