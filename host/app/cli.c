// SPDX-License-Identifier: MIT
#include "app/cli.h"

#include "io/gltf_loader.h"
#include "io/obj_loader.h"
#include "render/aov_layers.h"
#include "scene/scene.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void cli_print_help(void)
{
    puts("pt: a portable wavefront path tracer (OpenCL 1.2 on GPUs and CPUs)\n"
         "\n"
         "usage:\n"
         "  pt render SCENE [options]   render SCENE (a .json scene, a bare .obj, .ply, .gltf or\n"
         "                              .glb, or a folder with scene.json)\n"
         "  pt view SCENE [options]     interactive window\n"
         "  pt bench SCENE [options]    throughput: Mpaths/s and Mrays/s with and without compaction,\n"
         "                              per-stage times, the unit render on one device and (--device\n"
         "                              all or a list) on all, with each device's units and Mpaths/s\n"
         "                              (no image written; --csv FILE appends a row per mode, the\n"
         "                              profile to FILE_stages.csv, FILE_live.csv, the devices to\n"
         "                              FILE_units.csv)\n"
         "  pt devices                  list OpenCL platforms and devices\n"
         "  pt help                     this text\n"
         "  pt --version                the version\n"
         "\n");
    puts("options (--opt VALUE or --opt=VALUE, before or after SCENE):\n"
         "  --spp N            samples per pixel (default: the scene's, else 64)\n"
         "  --max-depth D      path segments from the camera: 1 = emitters seen directly,\n"
         "                     2 adds direct light (default: the scene's, else 8)\n"
         "  --width W, --height H   film size (default: the scene's, else 512x512)\n"
         "  --seed S           random seed (default 0); the image is a pure function of scene,\n"
         "                     settings, seed and spp\n"
         "  --device gpu|cpu|P:D    OpenCL device (default: first GPU, else first CPU)\n"
         "  --device all|P:D,P:D,...   render on several devices at once (all: every GPU, or\n"
         "                     every CPU device where there is none): the same image\n"
         "  --checkpoint S     every S seconds, save the film beside the output (OUTPUT.ptckpt,\n"
         "                     written atomically); --resume continues from it\n"
         "  --resume           continue the render of the checkpoint beside the output (the\n"
         "                     same scene and settings, or it is refused): the same bits as an\n"
         "                     uninterrupted render\n"
         "  --unit-spp N, --unit-rows N   work unit: N samples of a band of N rows (defaults:\n"
         "                     1 sample, bands of at most 2^20 pixels); the image is the same\n"
         "                     for every unit size\n"
         "  -o FILE            output .exr (linear) or .png (sRGB); overwrites FILE. Without -o:\n"
         "                     out/<scene>.exr and .png, numbered so nothing is overwritten\n"
         "  --preview          with -o FILE.exr, also write FILE.png\n"
         "  --exposure EV      exposure in stops for PNG output and the viewer (default 0)\n"
         "  --tonemap NAME     display curve for PNG output and the viewer (EXR stays linear):\n"
         "                     agx (default, Blender's look), aces (Hill's fit), filmic (Hable),\n"
         "                     pbr-neutral (Khronos), reinhard (per channel), clamp (hard clip)\n"
         "  --bloom S[,R]      glow around bright areas for PNG and the viewer (the EXR stays\n"
         "                     linear, without it): a share S in [0, 1] of the light above\n"
         "                     luminance 1 spread by a Gaussian of radius R pixels (3 sigma;\n"
         "                     default 1% of the image diagonal)\n"
         "  --clamp MAX        clamp each indirect sample's radiance to MAX (removes fireflies,\n"
         "                     biases the image; off by default)\n"
         "  --aov LIST         add layers to the EXR beside the image: albedo, normal, depth,\n"
         "                     variance, spp (comma-separated) or all\n"
         "  --noise-threshold T   adaptive sampling: pixels stop once their relative error is\n"
         "                     below T (after --min-spp samples); --spp is the most a pixel gets\n"
         "  --min-spp N        samples every pixel gets before adaptive sampling decides\n"
         "  --time-limit S     stop after S seconds of rendering, at a whole sample: the image is\n"
         "                     marked partial, the exit status is 0\n"
         "  --camera JSON      replace the scene's camera (render) or set the start pose (view),\n"
         "                     e.g. '{\"eye\": [0, 1, 3.9], \"target\": [0, 1, 0]}'"
         "");
    puts("  --no-nee           pure BSDF sampling (validation; same converged image)\n"
         "  --sort-materials, --no-sort-materials   shade paths grouped by the material they hit,\n"
         "                     or not (same image). Default: sorted when the scene has materials\n"
         "                     beyond Lambert, smooth mirrors and glass (pt bench measures both)\n"
         "  --no-compaction    keep dead paths in the wavefront (validation; same image)\n"
         "  --instancing auto|always|never   how objects become instances (same image): auto\n"
         "                     merges objects without a transform whose file is used once into\n"
         "                     one mesh and instances the rest (two-level BVH); always instances\n"
         "                     every object; never bakes every static object's transform into\n"
         "                     its vertices (memory grows with the objects)\n"
         "  --profile          per-kernel timing table\n"
         "  --no-cache         compile the kernels even if the kernel cache ($XDG_CACHE_HOME/pt,\n"
         "                     default ~/.cache/pt) holds them\n"
         "  --no-default-light a scene without any light (no emissive triangles, lights,\n"
         "                     environment or background) stays black; by default it gets a\n"
         "                     uniform white sky (background [1, 1, 1]) and a warning\n"
         "  --quiet            no progress output (and no summary)\n"
         "  --progress         progress lines at most once a second. Without it, progress goes\n"
         "                     to stderr as one line rewritten in place on a terminal, else as\n"
         "                     lines \"pt: progress: D/N spp (P%), S s\" after the first window,\n"
         "                     at most every 5 s, and at the end\n"
         "\n"
         "");
    puts("pt render stops early on SIGINT (Ctrl-C), SIGTERM or SIGHUP: it writes the image so far\n"
         "(marked partial) and exits with 130, 143 or 129 (128 + the signal). Other exits: 0 done\n"
         "or stopped by --time-limit, 1 bad input or a failure (one 'pt: ...' line on stderr).\n"
         "\n"
         "pt view (keys: press H in the window; --spp N stops sampling at N):\n"
         "  --camera JSON      start pose (keys of the scene's camera; the C key prints one)\n"
         "  --frames N         quit after N frames\n"
         "  --screenshot FILE  at exit, save the film as FILE.exr (linear, as pt render writes it)\n"
         "                     or else the window's framebuffer as a PNG\n"
         "  --events           print a line on stdout per input event read and per state change\n"
         "                     ('event: converged N spp'), for scripts and tests to wait on");
}

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

/* The seed is a 32-bit unsigned: 0 to 4294967295 (strtoul alone would take "-1" as ULONG_MAX). */
static bool parse_seed(const char *arg, const char *value, unsigned *out, Error *err)
{
    if (!value) {
        error_set(err, ERR_USAGE, NULL, 0, "%s needs a value", arg);
        return false;
    }
    char *end;
    errno = 0;
    unsigned long long v = strtoull(value, &end, 10);
    if (errno || end == value || *end || value[strspn(value, " \t")] == '-' || v > UINT_MAX) {
        error_set(err, ERR_USAGE, NULL, 0, "%s: '%s' is not an integer in [0, %u]", arg, value,
                  UINT_MAX);
        return false;
    }
    *out = (unsigned)v;
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

/* --bloom STRENGTH[,RADIUS]: strength in [0, 1] (the share of the bright part's energy spread
 * out), radius in pixels. */
static bool parse_bloom(const char *value, Options *o, Error *err)
{
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

/* Long options: the flag of those without a value, or a code for those with one. */
enum {
    OPT_SPP = 1000, OPT_MAX_DEPTH, OPT_WIDTH, OPT_HEIGHT, OPT_SEED, OPT_DEVICE, OPT_CSV, OPT_FRAMES,
    OPT_SCREENSHOT, OPT_CAMERA, OPT_EXPOSURE, OPT_INSTANCING, OPT_AOV, OPT_TONEMAP, OPT_BLOOM,
    OPT_CLAMP, OPT_NOISE_THRESHOLD, OPT_MIN_SPP, OPT_TIME_LIMIT, OPT_VERSION, OPT_PREVIEW,
    OPT_PROGRESS, OPT_NO_NEE, OPT_SORT, OPT_NO_SORT, OPT_NO_COMPACTION, OPT_PROFILE, OPT_NO_CACHE,
    OPT_NO_DEFAULT_LIGHT, OPT_EVENTS, OPT_CHECKPOINT, OPT_RESUME, OPT_UNIT_SPP, OPT_UNIT_ROWS,
};

static const struct option long_options[] = {
    {"spp", required_argument, NULL, OPT_SPP},
    {"max-depth", required_argument, NULL, OPT_MAX_DEPTH},
    {"width", required_argument, NULL, OPT_WIDTH},
    {"height", required_argument, NULL, OPT_HEIGHT},
    {"seed", required_argument, NULL, OPT_SEED},
    {"device", required_argument, NULL, OPT_DEVICE},
    {"output", required_argument, NULL, 'o'},
    {"csv", required_argument, NULL, OPT_CSV},
    {"frames", required_argument, NULL, OPT_FRAMES},
    {"screenshot", required_argument, NULL, OPT_SCREENSHOT},
    {"camera", required_argument, NULL, OPT_CAMERA},
    {"exposure", required_argument, NULL, OPT_EXPOSURE},
    {"instancing", required_argument, NULL, OPT_INSTANCING},
    {"aov", required_argument, NULL, OPT_AOV},
    {"tonemap", required_argument, NULL, OPT_TONEMAP},
    {"bloom", required_argument, NULL, OPT_BLOOM},
    {"clamp", required_argument, NULL, OPT_CLAMP},
    {"noise-threshold", required_argument, NULL, OPT_NOISE_THRESHOLD},
    {"min-spp", required_argument, NULL, OPT_MIN_SPP},
    {"time-limit", required_argument, NULL, OPT_TIME_LIMIT},
    {"quiet", no_argument, NULL, 'q'},
    {"help", no_argument, NULL, 'h'},
    {"version", no_argument, NULL, OPT_VERSION},
    {"preview", no_argument, NULL, OPT_PREVIEW},
    {"progress", no_argument, NULL, OPT_PROGRESS},
    {"no-nee", no_argument, NULL, OPT_NO_NEE},
    {"sort-materials", no_argument, NULL, OPT_SORT},
    {"no-sort-materials", no_argument, NULL, OPT_NO_SORT},
    {"no-compaction", no_argument, NULL, OPT_NO_COMPACTION},
    {"profile", no_argument, NULL, OPT_PROFILE},
    {"no-cache", no_argument, NULL, OPT_NO_CACHE},
    {"no-default-light", no_argument, NULL, OPT_NO_DEFAULT_LIGHT},
    {"events", no_argument, NULL, OPT_EVENTS},
    {"checkpoint", required_argument, NULL, OPT_CHECKPOINT},
    {"resume", no_argument, NULL, OPT_RESUME},
    {"unit-spp", required_argument, NULL, OPT_UNIT_SPP},
    {"unit-rows", required_argument, NULL, OPT_UNIT_ROWS},
    {NULL, 0, NULL, 0},
};

static bool parse_option(int code, const char *a, const char *v, Options *o, Error *err)
{
    switch (code) {
    case OPT_SPP: return parse_int(a, v, 1, INT_MAX, &o->spp, err);
    case OPT_MAX_DEPTH: return parse_int(a, v, 1, MAX_DEPTH_LIMIT, &o->max_depth, err);
    case OPT_WIDTH: return parse_int(a, v, 1, FILM_SIZE_LIMIT, &o->width, err);
    case OPT_HEIGHT: return parse_int(a, v, 1, FILM_SIZE_LIMIT, &o->height, err);
    case OPT_SEED: o->seed_given = true; return parse_seed(a, v, &o->seed, err);
    case OPT_DEVICE: o->device = v; return true;
    case 'o': o->output = v; return true;
    case OPT_CSV: o->csv = v; return true;
    case OPT_FRAMES: return parse_int(a, v, 1, INT_MAX, &o->frames, err);
    case OPT_SCREENSHOT: o->screenshot = v; return true;
    case OPT_CAMERA: o->camera_json = v; return true;
    case OPT_EXPOSURE: return parse_float_in(a, v, -64.0, 64.0, &o->exposure, err);
    case OPT_INSTANCING:
        if (!strcmp(v, "auto")) o->instancing = INSTANCING_AUTO;
        else if (!strcmp(v, "always")) o->instancing = INSTANCING_ALWAYS;
        else if (!strcmp(v, "never")) o->instancing = INSTANCING_NEVER;
        else {
            error_set(err, ERR_USAGE, NULL, 0, "--instancing: '%s' is not auto, always or never", v);
            return false;
        }
        return true;
    case OPT_AOV: return aov_parse_list(v, &o->aov_mask, err);
    case OPT_TONEMAP:
        if (!tonemap_from_name(v, &o->tonemap)) {
            char known[128] = "";
            for (int t = 0; t < TONEMAP_COUNT; t++)
                snprintf(known + strlen(known), sizeof known - strlen(known), "%s%s",
                         t ? ", " : "", tonemap_name((Tonemap)t));
            error_set(err, ERR_USAGE, NULL, 0, "--tonemap: '%s' is not a tone map (%s)", v, known);
            return false;
        }
        return true;
    case OPT_BLOOM: return parse_bloom(v, o, err);
    case OPT_CLAMP: return parse_float_in(a, v, 1e-6, 1e30, &o->clamp_max, err);
    case OPT_NOISE_THRESHOLD: return parse_float_in(a, v, 1e-9, 1e9, &o->noise_threshold, err);
    case OPT_MIN_SPP: return parse_int(a, v, 1, INT_MAX, &o->min_spp, err);
    case OPT_TIME_LIMIT: return parse_number(a, v, 1e-3, 1e9, &o->time_limit, err);
    case 'q':
        o->quiet = true;
        obj_loader_set_quiet(true); /* MTL statements pt does not use: no warnings */
        gltf_loader_set_quiet(true); /* nor glTF extensions pt ignores */
        return true;
    case 'h': o->command = CMD_HELP; return true;
    case OPT_VERSION: o->command = CMD_VERSION; return true;
    case OPT_PREVIEW: o->preview = true; return true;
    case OPT_PROGRESS: o->progress = true; return true;
    case OPT_NO_NEE: o->no_nee = true; return true;
    case OPT_SORT: o->sort_materials = SORT_MATERIALS_ON; return true;
    case OPT_NO_SORT: o->sort_materials = SORT_MATERIALS_OFF; return true;
    case OPT_NO_COMPACTION: o->no_compaction = true; return true;
    case OPT_PROFILE: o->profile = true; return true;
    case OPT_NO_CACHE: o->no_cache = true; return true;
    case OPT_NO_DEFAULT_LIGHT: o->no_default_light = true; return true;
    case OPT_EVENTS: o->print_events = true; return true;
    case OPT_CHECKPOINT: return parse_number(a, v, 1e-3, 1e9, &o->checkpoint_seconds, err);
    case OPT_RESUME: o->resume = true; return true;
    case OPT_UNIT_SPP: return parse_int(a, v, 1, INT_MAX, &o->unit_spp, err);
    case OPT_UNIT_ROWS: return parse_int(a, v, 1, FILM_SIZE_LIMIT, &o->unit_rows, err);
    }
    return true;
}

/* The option as the user wrote it (argv[optind - 1] after getopt_long), for messages. */
static const char *option_as_written(char **argv, int index)
{
    return index > 0 ? argv[index - 1] : "?";
}

bool cli_parse(int argc, char **argv, Options *o, Error *err)
{
    memset(o, 0, sizeof *o);
    o->tonemap = TONEMAP_DEFAULT;
    if (argc < 2) {
        o->command = CMD_HELP;
        return true;
    }
    const char *cmd = argv[1];
    if (!strcmp(cmd, "render")) o->command = CMD_RENDER;
    else if (!strcmp(cmd, "view")) o->command = CMD_VIEW;
    else if (!strcmp(cmd, "devices")) o->command = CMD_DEVICES;
    else if (!strcmp(cmd, "bench")) o->command = CMD_BENCH;
    else if (!strcmp(cmd, "help") || !strcmp(cmd, "--help") || !strcmp(cmd, "-h")) o->command = CMD_HELP;
    else if (!strcmp(cmd, "version") || !strcmp(cmd, "--version")) o->command = CMD_VERSION;
    else {
        error_set(err, ERR_USAGE, NULL, 0, "unknown command '%s' (try 'pt help')", cmd);
        return false;
    }
    /* getopt_long over the arguments after the command: --opt VALUE and --opt=VALUE alike,
     * options and the SCENE in any order ("--" ends the options). opterr = 0: pt words its own
     * messages. */
    int sub_argc = argc - 1;
    char **sub_argv = argv + 1;
    opterr = 0;
    optind = 0; /* 0, not 1: glibc's full reset, so that cli_parse can run more than once */
    int code;
    while ((code = getopt_long(sub_argc, sub_argv, ":o:qh", long_options, NULL)) != -1) {
        if (code == '?') {
            const char *written = option_as_written(sub_argv, optind);
            if (optopt && optopt < 256)
                error_set(err, ERR_USAGE, NULL, 0, "unknown option '-%c' (try 'pt help')", optopt);
            else
                error_set(err, ERR_USAGE, NULL, 0, "unknown option '%s' (try 'pt help')", written);
            return false;
        }
        if (code == ':') {
            error_set(err, ERR_USAGE, NULL, 0, "%s needs a value", option_as_written(sub_argv, optind));
            return false;
        }
        char name[64];
        const char *written = option_as_written(sub_argv, optind);
        /* "--spp=x" is named "--spp" in messages; a value given separately is argv[optind - 1]. */
        if (optarg && written == optarg && optind >= 2)
            written = sub_argv[optind - 2];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(written, "="), written);
        if (!parse_option(code, name, optarg, o, err))
            return false;
    }
    for (int i = optind; i < sub_argc; i++) {
        if (!o->scene)
            o->scene = sub_argv[i];
        else {
            error_set(err, ERR_USAGE, NULL, 0, "unexpected argument '%s'", sub_argv[i]);
            return false;
        }
    }
    /* (A scene's spp below --min-spp is the render's to refuse: the scene is not read yet.) */
    if (o->min_spp && o->spp && o->min_spp > o->spp) {
        error_set(err, ERR_USAGE, NULL, 0, "--min-spp %d is more than --spp %d", o->min_spp, o->spp);
        return false;
    }
    if ((o->command == CMD_RENDER || o->command == CMD_VIEW || o->command == CMD_BENCH) && !o->scene) {
        error_set(err, ERR_USAGE, NULL, 0, "'pt %s' needs a SCENE (a .json scene or an .obj)", cmd);
        return false;
    }
    return true;
}

RenderDesc cli_render_desc(const Options *o)
{
    return (RenderDesc){.scene = o->scene, .device = o->device, .width = o->width,
                        .height = o->height, .spp = o->spp, .max_depth = o->max_depth,
                        .no_cache = o->no_cache, .no_default_light = o->no_default_light,
                        .instancing = o->instancing, .camera_json = o->camera_json};
}

ViewerDesc cli_viewer_desc(const Options *o)
{
    return (ViewerDesc){.render = cli_render_desc(o), .seed = o->seed, .exposure = o->exposure,
                        .tonemap = o->tonemap, .bloom_strength = o->bloom_strength,
                        .bloom_radius = o->bloom_radius,
                        .no_nee = o->no_nee, .no_compaction = o->no_compaction,
                        .sort_materials = o->sort_materials, .quiet = o->quiet,
                        .frames = o->frames, .screenshot = o->screenshot,
                        .print_events = o->print_events};
}
