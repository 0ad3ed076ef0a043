// SPDX-License-Identifier: MIT
#include "app/cli.h"

#include "io/obj_loader.h"
#include "scene/scene.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void cli_print_help(void)
{
    puts("pt: a portable wavefront path tracer (OpenCL 1.2 on GPUs and CPUs)\n"
         "\n"
         "usage:\n"
         "  pt render SCENE [options]   render SCENE (.json scene, bare .obj or .ply, or a\n"
         "                              folder with scene.json)\n"
         "  pt view SCENE [options]     interactive window\n"
         "  pt bench SCENE [options]    throughput: Mpaths/s and Mrays/s with and without compaction,\n"
         "                              per-stage times (no image written; --csv FILE appends a row\n"
         "                              per mode, and the profile to FILE_stages.csv, FILE_live.csv)\n"
         "  pt devices                  list OpenCL platforms and devices\n"
         "  pt help                     this text\n"
         "\n"
         "options:\n"
         "  --spp N            samples per pixel (default: the scene's, else 64)\n"
         "  --max-depth D      path segments from the camera: 1 = emitters seen directly,\n"
         "                     2 adds direct light (default: the scene's, else 8)\n"
         "  --width W, --height H   film size (default: the scene's, else 512x512)\n"
         "  --seed S           random seed (default 0); the image is a pure function of scene,\n"
         "                     settings, seed and spp\n"
         "  --device gpu|cpu|P:D    OpenCL device (default: first GPU, else first CPU)\n"
         "  -o FILE            output .exr (linear) or .png (sRGB); overwrites FILE. Without -o:\n"
         "                     out/<scene>.exr and .png, numbered so nothing is overwritten\n"
         "  --preview          with -o FILE.exr, also write FILE.png\n"
         "  --exposure EV      exposure in stops applied to PNG output (default 0)\n"
         "  --aov albedo|normal|depth   write a first-hit AOV instead of the path-traced image\n"
         "  --no-nee           pure BSDF sampling (validation; same converged image)\n"
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
         "  --quiet            no progress output\n"
         "  --progress         progress as lines on stderr, even when it is not a terminal:\n"
         "                     \"pt: progress: D/N spp (P%), S s\" after the first window, then at\n"
         "                     most once a second\n"
         "\n"
         "pt render stops early on SIGINT (Ctrl-C), SIGTERM or SIGHUP: it writes the image so far\n"
         "and exits with 130, 143 or 129 (128 + the signal).\n"
         "\n"
         "pt view (keys: press H in the window; --spp N stops sampling at N):\n"
         "  --camera JSON      start pose, e.g. '{\"eye\": [0, 1, 3.9], \"target\": [0, 1, 0]}'\n"
         "                     (keys of the scene's camera; the C key prints one)\n"
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

static bool parse_float(const char *arg, const char *value, float *out, Error *err)
{
    char *end;
    if (!value || (strtof(value, &end), end == value || *end)) {
        error_set(err, ERR_USAGE, NULL, 0, "%s needs a number", arg);
        return false;
    }
    *out = strtof(value, NULL);
    return true;
}

static bool need_value(const char *arg, const char *value, Error *err)
{
    if (!value)
        error_set(err, ERR_USAGE, NULL, 0, "%s needs a value", arg);
    return value != NULL;
}

bool cli_parse(int argc, char **argv, Options *o, Error *err)
{
    memset(o, 0, sizeof *o);
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
    else {
        error_set(err, ERR_USAGE, NULL, 0, "unknown command '%s' (try 'pt help')", cmd);
        return false;
    }
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        bool ok = true, takes_value = true;
        if (!strcmp(a, "--spp")) ok = parse_int(a, v, 1, INT_MAX, &o->spp, err);
        else if (!strcmp(a, "--max-depth")) ok = parse_int(a, v, 1, MAX_DEPTH_LIMIT, &o->max_depth, err);
        else if (!strcmp(a, "--width")) ok = parse_int(a, v, 1, FILM_SIZE_LIMIT, &o->width, err);
        else if (!strcmp(a, "--height")) ok = parse_int(a, v, 1, FILM_SIZE_LIMIT, &o->height, err);
        else if (!strcmp(a, "--seed")) ok = parse_seed(a, v, &o->seed, err), o->seed_given = true; else if (!strcmp(a, "--device")) ok = need_value(a, v, err), o->device = v;
        else if (!strcmp(a, "-o") || !strcmp(a, "--output")) ok = need_value(a, v, err), o->output = v;
        else if (!strcmp(a, "--csv")) ok = need_value(a, v, err), o->csv = v;
        else if (!strcmp(a, "--frames")) ok = parse_int(a, v, 1, INT_MAX, &o->frames, err);
        else if (!strcmp(a, "--screenshot")) ok = need_value(a, v, err), o->screenshot = v;
        else if (!strcmp(a, "--camera")) ok = need_value(a, v, err), o->camera_json = v;
        else if (!strcmp(a, "--exposure")) ok = parse_float(a, v, &o->exposure, err);
        else if (!strcmp(a, "--instancing")) {
            ok = need_value(a, v, err);
            if (ok && !strcmp(v, "auto")) o->instancing = INSTANCING_AUTO;
            else if (ok && !strcmp(v, "always")) o->instancing = INSTANCING_ALWAYS;
            else if (ok && !strcmp(v, "never")) o->instancing = INSTANCING_NEVER;
            else if (ok) {
                error_set(err, ERR_USAGE, NULL, 0, "--instancing: '%s' is not auto, always or never", v);
                ok = false;
            }
        }
        else if (!strcmp(a, "--aov")) {
            ok = need_value(a, v, err);
            if (ok && strcmp(v, "albedo") && strcmp(v, "normal") && strcmp(v, "depth")) {
                error_set(err, ERR_USAGE, NULL, 0, "--aov: '%s' is not albedo, normal or depth", v);
                ok = false;
            }
            o->aov = v;
        } else {
            takes_value = false;
            if (!strcmp(a, "--quiet") || !strcmp(a, "-q")) {
                o->quiet = true;
                obj_loader_set_quiet(true); /* MTL statements pt does not use: no warnings */
            }
            else if (!strcmp(a, "--preview")) o->preview = true;
            else if (!strcmp(a, "--progress")) o->progress = true;
            else if (!strcmp(a, "--no-nee")) o->no_nee = true;
            else if (!strcmp(a, "--sort-materials")) o->sort_materials = SORT_MATERIALS_ON;
            else if (!strcmp(a, "--no-sort-materials")) o->sort_materials = SORT_MATERIALS_OFF;
            else if (!strcmp(a, "--no-compaction")) o->no_compaction = true;
            else if (!strcmp(a, "--profile")) o->profile = true;
            else if (!strcmp(a, "--no-cache")) o->no_cache = true;
            else if (!strcmp(a, "--no-default-light")) o->no_default_light = true;
            else if (!strcmp(a, "--events")) o->print_events = true;
            else if (!strcmp(a, "--help") || !strcmp(a, "-h")) o->command = CMD_HELP;
            else if (a[0] == '-' && a[1]) {
                error_set(err, ERR_USAGE, NULL, 0, "unknown option '%s' (try 'pt help')", a);
                return false;
            } else if (!o->scene) o->scene = a;
            else {
                error_set(err, ERR_USAGE, NULL, 0, "unexpected argument '%s'", a);
                return false;
            }
        }
        if (!ok)
            return false;
        if (takes_value)
            i++;
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
                        .instancing = o->instancing};
}

ViewerDesc cli_viewer_desc(const Options *o)
{
    return (ViewerDesc){.render = cli_render_desc(o), .seed = o->seed, .exposure = o->exposure,
                        .no_nee = o->no_nee, .no_compaction = o->no_compaction,
                        .sort_materials = o->sort_materials, .quiet = o->quiet,
                        .frames = o->frames, .screenshot = o->screenshot,
                        .print_events = o->print_events,
                        .camera_json = o->camera_json};
}
