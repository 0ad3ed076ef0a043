// SPDX-License-Identifier: MIT
/* cli.c: the command line, read with the one list of options (app/cli_options.h): getopt_long's
 * table, `pt help` and the check that the command takes each option all come from it. */
#include "app/cli.h"

#include "app/cli_options.h"
#include "render/aov_layers.h"

#include <getopt.h>
#include <stdio.h>
#include <string.h>

/* getopt_long's codes: OPTION_CODE + the row of cli_options (short options return their char). */
#define OPTION_CODE 1000

/* The rows of one help section: "  USAGE" padded to the help column, then the help text. */
static void print_option_rows(HelpSection section)
{
    for (size_t i = 0; i < cli_option_count; i++) {
        const CliOption *c = &cli_options[i];
        if (c->section == section && c->help)
            printf("  %-*s%s\n", strlen(c->usage) < 19 ? 19 : (int)strlen(c->usage) + 3, c->usage,
                   c->help);
    }
}

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
         "  pt tonemap IN.exr -o OUT.png\n"
         "                              display an EXR again (--tonemap, --exposure, --bloom)\n"
         "                              without rendering it again\n"
         "  pt devices                  list OpenCL platforms and devices\n"
         "  pt help                     this text\n"
         "  pt --version                the version\n"
         "\n");
    puts("options (--opt VALUE or --opt=VALUE, before or after SCENE; a command refuses those it\n"
         "does not use):");
    print_option_rows(HELP_OPTIONS);
    puts("\n");
    puts("pt render stops early on SIGINT (Ctrl-C), SIGTERM or SIGHUP: it writes the image so far\n"
         "(marked partial) and exits with 130, 143 or 129 (128 + the signal). Other exits: 0 done\n"
         "or stopped by --time-limit, 1 bad input or a failure (one 'pt: ...' line on stderr).\n"
         "\n"
         "pt view (keys: press H in the window; --spp N stops sampling at N):");
    print_option_rows(HELP_VIEW);
}

/* getopt_long's view of the list: the long names and, as "o:qh", the short ones. */
#define MAX_OPTIONS 64
static struct option long_options[MAX_OPTIONS + 1];
static char short_options[2 * MAX_OPTIONS + 2];
/* "--name" of each row, for flag_of_setting: written before any render thread reads them. */
static char flags[MAX_OPTIONS][32];

static void build_getopt_tables(void)
{
    if (cli_option_count > MAX_OPTIONS)
        die("bug: %zu options, room for %d (MAX_OPTIONS)", cli_option_count, MAX_OPTIONS);
    size_t n = 0, s = 0;
    short_options[s++] = ':'; /* a missing value returns ':' */
    for (size_t i = 0; i < cli_option_count; i++) {
        const CliOption *c = &cli_options[i];
        snprintf(flags[i], sizeof flags[i], "--%s", c->name);
        if (c->kind == ARG_HELP_ONLY)
            continue;
        bool value = cli_option_takes_value(c);
        long_options[n++] = (struct option){c->name, value ? required_argument : no_argument, NULL,
                                            OPTION_CODE + (int)i};
        if (c->short_name) {
            short_options[s++] = c->short_name;
            if (value)
                short_options[s++] = ':';
        }
    }
    long_options[n] = (struct option){0};
    short_options[s] = '\0';
}

static const CliOption *option_of_code(int code)
{
    if (code >= OPTION_CODE && code < OPTION_CODE + (int)cli_option_count)
        return &cli_options[code - OPTION_CODE];
    for (size_t i = 0; i < cli_option_count; i++)
        if (code == cli_options[i].short_name)
            return &cli_options[i];
    return NULL;
}

/* An option the command would ignore is refused, naming the commands that take it. */
static bool check_command_takes(const CliOption *c, const char *arg, Command command,
                                const char *cmd, Error *err)
{
    if (command == CMD_HELP || command == CMD_VERSION || (c->commands & CMD_BIT(command)))
        return true;
    static const char *const names[] = {[CMD_RENDER] = "pt render", [CMD_VIEW] = "pt view",
                                        [CMD_BENCH] = "pt bench", [CMD_TONEMAP] = "pt tonemap"};
    char takers[64] = "";
    int count = 0, total = 0;
    for (int k = CMD_RENDER; k <= CMD_TONEMAP; k++)
        total += names[k] && (c->commands & CMD_BIT(k));
    for (int k = CMD_RENDER; k <= CMD_TONEMAP; k++)
        if (names[k] && (c->commands & CMD_BIT(k)))
            snprintf(takers + strlen(takers), sizeof takers - strlen(takers), "%s%s",
                     count == 0 ? "" : count == total - 1 ? " and " : ", ", names[k]), count++;
    error_set(err, ERR_USAGE, NULL, 0, "%s: 'pt %s' does not take this option (%s %s)", arg, cmd,
              takers, count > 1 ? "do" : "does");
    return false;
}

/* The option as the user wrote it (argv[optind - 1] after getopt_long), for messages. */
static const char *option_as_written(char **argv, int index)
{
    return index > 0 ? argv[index - 1] : "?";
}

static bool parse_command(const char *cmd, Options *o, Error *err)
{
    if (!strcmp(cmd, "render")) o->command = CMD_RENDER;
    else if (!strcmp(cmd, "view")) o->command = CMD_VIEW;
    else if (!strcmp(cmd, "devices")) o->command = CMD_DEVICES;
    else if (!strcmp(cmd, "bench")) o->command = CMD_BENCH;
    else if (!strcmp(cmd, "tonemap")) o->command = CMD_TONEMAP;
    else if (!strcmp(cmd, "help") || !strcmp(cmd, "--help") || !strcmp(cmd, "-h")) o->command = CMD_HELP;
    else if (!strncmp(cmd, "--help=", 7) || !strncmp(cmd, "--version=", 10)) {
        error_set(err, ERR_USAGE, NULL, 0, "%.*s takes no value (given '%s')",
                  (int)strcspn(cmd, "="), cmd, cmd);
        return false;
    }
    else if (!strcmp(cmd, "version") || !strcmp(cmd, "--version")) o->command = CMD_VERSION;
    else {
        error_set(err, ERR_USAGE, NULL, 0, "unknown command '%s' (try 'pt help')", cmd);
        return false;
    }
    return true;
}

/* getopt_long's error codes as pt's messages: an unknown option, or one without its value. */
static void getopt_error(int code, char **sub_argv, Error *err)
{
    const char *written = option_as_written(sub_argv, optind);
    size_t name_length = strcspn(written, "=");
    const CliOption *flag = NULL; /* --flag=VALUE of a flag that takes none */
    for (size_t i = 0; written[name_length] && !strncmp(written, "--", 2) && i < cli_option_count; i++)
        if (strlen(cli_options[i].name) == name_length - 2 &&
            !strncmp(cli_options[i].name, written + 2, name_length - 2))
            flag = &cli_options[i];
    if (code == ':')
        error_set(err, ERR_USAGE, NULL, 0, "%s needs a value", written);
    else if (flag)
        error_set(err, ERR_USAGE, NULL, 0, "%.*s takes no value (given '%s')", (int)name_length,
                  written, written);
    else if (optopt && optopt < 256)
        error_set(err, ERR_USAGE, NULL, 0, "unknown option '-%c' (try 'pt help')", optopt);
    else
        error_set(err, ERR_USAGE, NULL, 0, "unknown option '%s' (try 'pt help')", written);
}

/* The options after the command, by getopt_long: --opt VALUE and --opt=VALUE alike, options and
 * the SCENE in any order ("--" ends the options). opterr = 0: pt words its own messages. */
static bool parse_options(int sub_argc, char **sub_argv, Options *o, Error *err)
{
    Command command = o->command; /* as named: --help may change o->command */
    build_getopt_tables();
    opterr = 0;
    optind = 0; /* 0, not 1: glibc's full reset, so that cli_parse can run more than once */
    int code;
    while ((code = getopt_long(sub_argc, sub_argv, short_options, long_options, NULL)) != -1) {
        const CliOption *c = option_of_code(code);
        if (code == '?' || code == ':' || !c) {
            getopt_error(code, sub_argv, err);
            return false;
        }
        char name[64];
        const char *written = option_as_written(sub_argv, optind);
        /* "--spp=x" is named "--spp" in messages; a value given separately is argv[optind - 1]. */
        if (optarg && written == optarg && optind >= 2)
            written = sub_argv[optind - 2];
        snprintf(name, sizeof name, "%.*s", (int)strcspn(written, "="), written);
        if (!check_command_takes(c, name, command, sub_argv[0], err) ||
            !cli_option_parse(c, name, optarg, o, err))
            return false;
    }
    return true;
}

/* The flag that sets a render setting (error_set_setting's namer): render/ and dist/ word their
 * messages with the setting's name, pt's messages name what the user typed. */
static const char *flag_of_setting(const char *setting)
{
    for (size_t i = 0; i < cli_option_count; i++)
        if (cli_options[i].setting && strcmp(cli_options[i].setting, setting) == 0)
            return flags[i];
    return NULL;
}

bool cli_parse(int argc, char **argv, Options *o, Error *err)
{
    error_set_setting_namer(flag_of_setting);
    memset(o, 0, sizeof *o);
    o->tonemap = TONEMAP_DEFAULT;
    if (argc < 2) {
        o->command = CMD_HELP;
        return true;
    }
    const char *cmd = argv[1];
    int sub_argc = argc - 1;
    char **sub_argv = argv + 1;
    if (!parse_command(cmd, o, err) || !parse_options(sub_argc, sub_argv, o, err))
        return false;
    for (int i = optind; i < sub_argc; i++) {
        if (!o->scene)
            o->scene = sub_argv[i];
        else {
            error_set(err, ERR_USAGE, NULL, 0, "unexpected argument '%s'", sub_argv[i]);
            return false;
        }
    }
    /* Adaptive sampling asked for here with a checkpoint: refused before the scene loads (a
     * scene's own noise_threshold is refused once read, app/render_cmd_units.c). */
    if (o->command == CMD_RENDER && o->noise_threshold > 0.0f && (o->checkpoint_seconds > 0 || o->resume)) {
        const char *unit = o->checkpoint_seconds > 0 ? "--checkpoint" : "--resume";
        error_set(err, ERR_USAGE, NULL, 0,
                  "%s with --noise-threshold: adaptive sampling decides over the whole film and keeps "
                  "no checkpoint; drop %s, or --noise-threshold to sample every pixel alike", unit, unit);
        return false;
    }
    /* (A scene's spp below --min-spp is the render's to refuse: the scene is not read yet.) */
    if (o->min_spp && o->spp && o->min_spp > o->spp) {
        error_set(err, ERR_USAGE, NULL, 0, "--min-spp %d is more than --spp %d", o->min_spp, o->spp);
        return false;
    }
    if (o->command == CMD_TONEMAP && (!o->scene || !o->output)) {
        error_set(err, ERR_USAGE, NULL, 0, "'pt tonemap' needs an EXR and -o OUT.png (pt tonemap IN.exr -o OUT.png)");
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
                        .instancing = o->instancing, .camera_json = o->camera_json,
                        .no_ground = o->no_ground, .frame = o->frame, .up_axis = o->up_axis};
}

/* The one place the options become render settings: pt render, pt bench (its modes then vary
 * the switches they measure) and pt view (ViewerDesc.settings) all start from it. spp and
 * max_depth stay 0 (the scene's: session_settle_settings), material sorting is settled there
 * too, from o->sort_materials. The variance layer needs the samples' squares as adaptive sampling
 * does. */
RenderSettings cli_render_settings(const Options *o)
{
    return (RenderSettings){
        .seed = o->seed,
        .sampler = o->sampler,
        .no_nee = o->no_nee,
        .no_compaction = o->no_compaction,
        .profile = o->profile,
        .clamp_indirect = o->clamp_max,
        .noise_threshold = o->noise_threshold,
        .min_spp = o->min_spp,
        .moments = o->noise_threshold > 0.0f || (o->aov_mask & AOV_MASK(AOV_LAYER_VARIANCE)),
    };
}

ViewerDesc cli_viewer_desc(const Options *o)
{
    return (ViewerDesc){.render = cli_render_desc(o), .settings = cli_render_settings(o),
                        .exposure = o->exposure, .tonemap = o->tonemap,
                        .bloom_strength = o->bloom_strength, .bloom_radius = o->bloom_radius,
                        .sort_materials = o->sort_materials, .quiet = o->quiet,
                        .frames = o->frames, .screenshot = o->screenshot,
                        .print_events = o->print_events, .denoise = o->denoise,
                        .denoise_device = o->denoise_device};
}
