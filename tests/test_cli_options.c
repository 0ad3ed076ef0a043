// SPDX-License-Identifier: MIT
/* The command-line conventions of issue 19 end to end: --opt=value, --version, --camera on
 * pt render, --time-limit, progress lines when stderr is not a terminal, and the one-line
 * messages for bad values, unknown scene keys (with the key's own line) and scene formats pt
 * does not read. */
#include <criterion/criterion.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb_image_write.h>

#include "app/cli.h"
#include "base/version.h"
#include "cli_run.h"
#include "io/image_io.h"
#include "support.h"

static bool parse(int argc, char **argv, Options *o)
{
    Error err = {0};
    bool ok = cli_parse(argc, argv, o, &err);
    cr_expect(ok, "%s", err.message);
    return ok;
}

/* --opt=value is --opt value, for options with a value of every kind. */
Test(cli_options, equals_form_is_the_spaced_form)
{
    char *spaced[] = {"pt", "render", "--spp", "8", "scene.json", "--time-limit", "2.5",
                      "--camera", "{\"eye\": [0, 1, 2]}", "--tonemap", "aces", "--bloom", "0.5,4",
                      "--noise-threshold", "0.02", "--min-spp", "4", "--aov", "albedo,depth",
                      "--sampler", "independent"};
    char *joined[] = {"pt", "render", "--spp=8", "scene.json", "--time-limit=2.5",
                      "--camera={\"eye\": [0, 1, 2]}", "--tonemap=aces", "--bloom=0.5,4",
                      "--noise-threshold=0.02", "--min-spp=4", "--aov=albedo,depth",
                      "--sampler=independent"};
    Options a, b;
    cr_assert(parse(sizeof spaced / sizeof spaced[0], spaced, &a));
    cr_assert(parse(sizeof joined / sizeof joined[0], joined, &b));
    cr_expect_eq(a.spp, 8);
    cr_expect_eq(b.spp, 8);
    cr_expect_str_eq(a.scene, "scene.json");
    cr_expect_str_eq(b.scene, "scene.json");
    cr_expect_eq(a.time_limit, 2.5);
    cr_expect_eq(b.time_limit, 2.5);
    cr_expect_str_eq(b.camera_json, a.camera_json);
    cr_expect_eq(a.tonemap, b.tonemap);
    cr_expect_eq(a.bloom_strength, b.bloom_strength);
    cr_expect_eq(a.bloom_radius, 4.0f);
    cr_expect_eq(b.bloom_radius, 4.0f);
    cr_expect_eq(a.noise_threshold, b.noise_threshold);
    cr_expect_eq(a.min_spp, 4);
    cr_expect_eq(b.min_spp, 4);
    cr_expect_neq(a.aov_mask, 0u);
    cr_expect_eq(a.aov_mask, b.aov_mask);
    cr_expect_eq(a.sampler, SAMPLER_INDEPENDENT);
    cr_expect_eq(b.sampler, SAMPLER_INDEPENDENT);
}

Test(cli_options, version_prints_the_version)
{
    const char *forms[] = {"--version", "version"};
    for (int i = 0; i < 2; i++) {
        Run r = run_pt(NULL, forms[i]);
        cr_expect_eq(r.exit_code, 0, "pt %s: %s", forms[i], r.err);
        cr_expect_str_eq(r.out, "pt " PT_VERSION "\n", "pt %s", forms[i]);
    }
}

/* A Cornell box scene file with the given camera object, 32x32 at 2 spp. */
static const char *write_box_scene(const char *dir, const char *name, const char *camera)
{
    char cwd[PATH_MAX], text[PATH_MAX + 512];
    cr_assert(getcwd(cwd, sizeof cwd));
    snprintf(text, sizeof text,
             "{\"camera\": %s, \"film\": {\"width\": 32, \"height\": 32},\n"
             " \"render\": {\"spp\": 2, \"max_depth\": 3},\n"
             " \"objects\": [{\"obj\": \"%s/scenes/cornell-box/CornellBox-Original.obj\"}]}\n",
             camera, cwd);
    return test_write_file(dir, name, text);
}

static float *render_exr(const char *scene, const char *extra, const char *out)
{
    char args[2048];
    snprintf(args, sizeof args, "render '%s' --device cpu --quiet -o '%s' %s", scene, out, extra);
    Run r = run_pt(NULL, args);
    cr_assert_eq(r.exit_code, 0, "%s: %s", args, r.err);
    float *rgb = NULL;
    int width = 0, height = 0;
    Error err = {0};
    cr_assert(image_read_exr(out, &rgb, &width, &height, &err), "%s", err.message);
    cr_assert(width == 32 && height == 32, "%dx%d", width, height);
    return rgb;
}

/* pt render --camera replaces the scene's camera: the render equals, bit for bit, that of a scene
 * file with that camera (it used to be accepted and ignored). */
Test(cli_options, camera_option_renders_as_the_scene_camera, .timeout = 300)
{
    const char *camera = "{\"eye\": [0.6, 1.3, 3.2], \"target\": [-0.1, 0.8, 0], "
                         "\"up\": [0, 1, 0], \"fov_y\": 47}";
    const char *dir = test_temp_dir();
    char with[600], option[700], plain[600], a[600], b[600], c[600];
    snprintf(with, sizeof with, "%s", write_box_scene(dir, "with.json", camera));
    snprintf(plain, sizeof plain, "%s",
             write_box_scene(dir, "plain.json", "{\"eye\": [0, 1, 3.9], \"target\": [0, 1, 0]}"));
    snprintf(option, sizeof option, "--camera '%s'", camera);
    snprintf(a, sizeof a, "%s/a.exr", dir);
    snprintf(b, sizeof b, "%s/b.exr", dir);
    snprintf(c, sizeof c, "%s/c.exr", dir);
    float *expected = render_exr(with, "", a);
    float *got = render_exr(plain, option, b);
    float *unchanged = render_exr(plain, "", c);
    size_t bytes = 32 * 32 * RGB_CHANNELS * sizeof(float);
    cr_expect_eq(memcmp(expected, got, bytes), 0, "--camera differs from the scene's camera");
    cr_expect_neq(memcmp(expected, unchanged, bytes), 0, "the two cameras give the same image");
    free(expected), free(got), free(unchanged);
}

Test(cli_options, bad_camera_json_names_the_key)
{
    const char *render = "render scenes/cornell-box --width 8 --height 8 --spp 1 --device cpu "
                         "--quiet -o /tmp/pt-cli-camera.png";
    char args[512];
    snprintf(args, sizeof args, "%s --camera '{\"eye\": [1, 2]}'", render);
    expect_clean_error(run_pt(NULL, args), "two numbers", "--camera", "eye");
    snprintf(args, sizeof args, "%s --camera '{\"eye\": [0, 1, 3.9], \"fov_y\": 200}'", render);
    expect_clean_error(run_pt(NULL, args), "fov 200", "--camera", "fov_y");
    snprintf(args, sizeof args, "%s --camera '{\"eyes\": [0, 1, 3.9]}'", render);
    expect_clean_error(run_pt(NULL, args), "unknown key", "eyes", "accepted: eye, target");
    snprintf(args, sizeof args, "%s --camera '{\"eye\": [0, 1,'", render);
    expect_clean_error(run_pt(NULL, args), "malformed", "--camera", "malformed JSON");
    unlink("/tmp/pt-cli-camera.png");
}

/* An absurdly small limit stops after the first window, at a whole sample: fewer spp than asked,
 * a valid image, exit status 0 (a time limit is what the user asked for, not an error). Without
 * the limit the render takes seconds, not hours: the test fails rather than hangs. */
Test(cli_options, time_limit_stops_with_a_partial_image, .timeout = 120)
{
    const char *dir = test_temp_dir();
    char out[600], args[800];
    snprintf(out, sizeof out, "%s/limited.exr", dir);
    snprintf(args, sizeof args,
             "render scenes/cornell-box --width 8 --height 8 --spp 200000 --time-limit 0.001 "
             "--device cpu --quiet -o '%s'", out);
    Run r = run_pt(NULL, args);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    const char *holds = strstr(r.err, "the image holds ");
    int done = 0, asked = 0;
    cr_assert(holds && sscanf(holds, "the image holds %d of %d spp", &done, &asked) == 2, "%s",
              r.err);
    cr_expect(done >= 1 && done < asked && asked == 200000, "%d of %d spp", done, asked);
    float *rgb = NULL;
    int width = 0, height = 0;
    Error err = {0};
    cr_assert(image_read_exr(out, &rgb, &width, &height, &err), "%s", err.message);
    cr_assert(width == 8 && height == 8);
    double sum = 0.0;
    for (int i = 0; i < 8 * 8 * RGB_CHANNELS; i++) {
        cr_assert(isfinite(rgb[i]) && rgb[i] >= 0.0f, "pixel value %d is %g", i, rgb[i]);
        sum += rgb[i];
    }
    cr_expect_gt(sum, 0.0, "the partial image is black");
    free(rgb);
}

/* With stderr not a terminal (here a file) and no --quiet, progress comes as lines: one after the
 * first window and one at the end (the ones in between depend on time; the test reads neither). */
Test(cli_options, progress_lines_when_stderr_is_not_a_terminal, .timeout = 120)
{
    const char *render = "render scenes/cornell-box --width 512 --height 512 --spp 2 "
                         "--max-depth 1 --device cpu -o /tmp/pt-cli-progress.exr";
    Run r = run_pt(NULL, render);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    const char *first = strstr(r.err, "pt: progress: "), *last = first;
    cr_assert(first, "no progress line in: %s", r.err);
    for (const char *next = first; (next = strstr(next + 1, "pt: progress: "));)
        last = next;
    int done = 0, spp = 0;
    cr_expect(sscanf(first, "pt: progress: %d/%d spp", &done, &spp) == 2 && done >= 0 &&
                  done <= 2 && spp == 2, "%s", first);
    cr_expect(strncmp(last, "pt: progress: 2/2 spp (100.0%), ", 32) == 0, "last line: %s", last);
    char quiet[256];
    snprintf(quiet, sizeof quiet, "%s --quiet", render);
    r = run_pt(NULL, quiet);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    cr_expect(!strstr(r.err, "progress"), "--quiet printed progress: %s", r.err);
    unlink("/tmp/pt-cli-progress.exr");
}

/* Unknown keys: the message lists the accepted keys and gives the key's own line, found along
 * its path (an unknown key of objects[1] used to be given the line of "objects"). */
Test(cli_options, unknown_scene_key_has_its_line_and_the_accepted_keys)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const char *path = test_write_file(dir, "render.json",
                                       "{\n"
                                       "  \"camera\": {\"eye\": [0, 0, 2], \"target\": [0, 0, 0]},\n"
                                       "  \"render\": {\n"
                                       "    \"spp\": 4,\n"
                                       "    \"sp\": 4\n"
                                       "  },\n"
                                       "  \"objects\": [{\"obj\": \"a.obj\"}]\n"
                                       "}\n");
    char args[700], needle[700];
    snprintf(args, sizeof args, "render '%s' --quiet", path);
    snprintf(needle, sizeof needle, "%s:5: render.sp: unknown key (accepted: spp, max_depth", path);
    expect_clean_error(run_pt(NULL, args), "render.sp", needle, NULL);
    path = test_write_file(dir, "objects.json",
                           "{\"objects\": [\n"
                           "  {\"obj\": \"a.obj\", \"smooth\": true},\n"
                           "  {\"obj\": \"a.obj\",\n"
                           "   \"smooth\": true, \"colour\": [1, 0, 0]}\n"
                           "]}\n");
    snprintf(args, sizeof args, "render '%s' --quiet", path);
    snprintf(needle, sizeof needle, "%s:4: objects[1].colour: unknown key (accepted: obj, ply,",
             path);
    expect_clean_error(run_pt(NULL, args), "objects[1].colour", needle, NULL);
}

/* Formats of other tools are named as such, with the ones pt reads (they used to be reported as
 * malformed JSON). */
Test(cli_options, unsupported_scene_formats_name_the_readable_ones)
{
    const char *dir = test_temp_dir();
    const char *names[] = {"scene.usda", "model.MAX", "scene.abc"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        const char *path = test_write_file(dir, names[i], "not a scene\n");
        char args[700];
        snprintf(args, sizeof args, "render '%s' --quiet", path);
        expect_clean_error(run_pt(NULL, args), names[i], "pt reads .json scenes, .obj, .ply, .gltf",
                           ".dae, .xml, .pbrt, .fbx, .stl");
    }
    /* Those pt imports (issue 37) are read, and a broken one is its reader's one line. */
    const char *read[] = {"model.fbx", "MODEL.STL", "scene.blend", "model.dae"};
    for (size_t i = 0; i < sizeof read / sizeof read[0]; i++) {
        const char *path = test_write_file(dir, read[i], "not a scene\n");
        char args[700];
        snprintf(args, sizeof args, "render '%s' --quiet", path);
        expect_clean_error(run_pt(NULL, args), read[i], read[i], NULL);
    }
}

/* Out-of-range values of the film and output options: one line naming the option, exit 1. */
Test(cli_options, bad_values_are_one_line)
{
    static const char *const bad[][2] = {
        {"--noise-threshold 0", "--noise-threshold"}, {"--noise-threshold -1", "--noise-threshold"},
        {"--noise-threshold nan", "--noise-threshold"}, {"--noise-threshold=inf", "--noise-threshold"},
        {"--bloom 2", "--bloom"}, {"--bloom -0.5", "--bloom"}, {"--bloom 0.5,0", "--bloom"},
        {"--bloom 0.5,x", "--bloom"}, {"--clamp 0", "--clamp"}, {"--clamp -3", "--clamp"},
        {"--tonemap sepia", "sepia"}, {"--tonemap=", "--tonemap"}, {"--aov albedo,shiny", "shiny"},
        {"--aov ''", "--aov"}, {"--time-limit 0", "--time-limit"}, {"--min-spp 0", "--min-spp"},
        {"--min-spp 16 --spp 8", "--min-spp"}, {"--spp=", "--spp"},
        {"--sampler halton", "--sampler: 'halton' is not a sampler (sobol, independent)"},
        /* render/ finds this one (the scene's spp) and names min_spp; pt names the flag. */
        {"--min-spp 99999", "--min-spp 99999: more than the spp"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char args[256];
        snprintf(args, sizeof args, "render scenes/cornell-box --width 8 --height 8 --device cpu "
                 "--quiet -o /tmp/pt-cli-bad.png %s", bad[i][0]);
        expect_clean_error(run_pt(NULL, args), bad[i][0], bad[i][1], NULL);
    }
    unlink("/tmp/pt-cli-bad.png");
}

static bool parse_command(const char *command, const char *a1, const char *a2, Options *o,
                          Error *err)
{
    char *argv[] = {"pt", (char *)command, "scene.json", (char *)a1, (char *)a2, NULL};
    memset(err, 0, sizeof *err);
    return cli_parse(a2 ? 5 : 4, argv, o, err);
}

/* An option a command would ignore is one line naming the option, the command and the commands
 * that take it (pt bench and pt view used to accept --noise-threshold and the like and ignore
 * them). */
Test(cli_options, commands_refuse_the_options_they_do_not_use)
{
    static const char *const refused[][4] = {
        {"bench", "--noise-threshold", "0.1", "pt render and pt view do"},
        {"bench", "--min-spp", "4", "pt render and pt view do"},
        {"bench", "--no-compaction", NULL, "pt render and pt view do"},
        {"view", "--aov", "all", "pt render does"},
        {"view", "-o", "x.png", "pt render and pt tonemap do"},
        {"view", "--time-limit", "2", "pt render does"},
        {"render", "--frames", "3", "pt view does"},
        {"render", "--csv", "x.csv", "pt bench does"},
        {"devices", "--spp", "3", "pt render, pt view and pt bench do"},
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        Options o;
        Error err;
        const char *const *r = refused[i];
        cr_expect_not(parse_command(r[0], r[1], r[2], &o, &err), "pt %s %s accepted", r[0], r[1]);
        char needle[128];
        snprintf(needle, sizeof needle, "%s: 'pt %s' does not take this option (%s)", r[1], r[0],
                 r[3]);
        cr_expect(strstr(err.message, needle), "%s", err.message);
    }
}

/* --clamp and adaptive sampling become the settings of every command that takes them: pt bench
 * measures with --clamp, pt view renders with it (the viewer's film test checks the image). */
Test(cli_options, clamp_and_adaptive_reach_the_render_settings)
{
    const char *commands[] = {"render", "view", "bench"};
    for (int i = 0; i < 3; i++) {
        Options o;
        Error err;
        cr_assert(parse_command(commands[i], "--clamp", "2.5", &o, &err), "%s", err.message);
        cr_expect_eq(cli_render_settings(&o).clamp_indirect, 2.5f, "pt %s --clamp", commands[i]);
    }
    const char *adaptive[] = {"render", "view"};
    for (int i = 0; i < 2; i++) {
        Options o;
        Error err;
        cr_assert(parse_command(adaptive[i], "--noise-threshold", "0.05", &o, &err), "%s",
                  err.message);
        RenderSettings s = cli_render_settings(&o);
        cr_expect(s.noise_threshold == 0.05f && s.moments, "pt %s --noise-threshold", adaptive[i]);
        cr_assert(parse_command(adaptive[i], "--min-spp", "3", &o, &err), "%s", err.message);
        cr_expect_eq(cli_render_settings(&o).min_spp, 3, "pt %s --min-spp", adaptive[i]);
    }
}

/* --allow-outside-paths end to end (issue 42): an OBJ's MTL whose map_Kd climbs out of the
 * MTL's folder is one line naming the MTL, the statement and the path; with the option it
 * renders. */
Test(cli_options, allow_outside_paths_lets_an_mtl_name_a_texture_above_it, .timeout = 300)
{
    const char *dir = test_temp_dir();
    char sub[600], png[700];
    snprintf(sub, sizeof sub, "%s/model", dir);
    cr_assert_eq(mkdir(sub, 0700), 0);
    snprintf(png, sizeof png, "%s/red.png", dir);
    const unsigned char red[3] = {255, 0, 0};
    cr_assert(stbi_write_png(png, 1, 1, 3, red, 3));
    test_write_file(sub, "m.mtl", "newmtl red\nKd 1 1 1\nmap_Kd ../red.png\n");
    const char *obj = test_write_file(sub, "m.obj", "mtllib m.mtl\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\n"
                                                    "usemtl red\nf 1 2 3\n");
    char args[2000];
    snprintf(args, sizeof args, "render '%s' --width 8 --height 8 --spp 1 --device cpu --quiet "
             "-o '%s/out.png'", obj, dir);
    expect_clean_error(run_pt(NULL, args), "confined", "m.mtl: material 'red' map_Kd \"../red.png\"",
                       "--allow-outside-paths");
    strncat(args, " --allow-outside-paths", sizeof args - strlen(args) - 1);
    Run r = run_pt(NULL, args);
    cr_expect_eq(r.exit_code, 0, "%s", r.err);
}

/* A flag given a value (--help=1) says so, naming the flag (it was "unknown option '-h'"). */
Test(cli_options, a_flag_given_a_value_says_it_takes_none)
{
    expect_clean_error(run_pt(NULL, "--help=1"), "pt --help=1", "--help takes no value", "--help=1");
    expect_clean_error(run_pt(NULL, "render --help=1"), "pt render --help=1", "--help takes no value",
                       NULL);
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box --quiet=2"), "--quiet=2",
                       "--quiet takes no value", "'--quiet=2'");
}

/* An environment map that is missing or damaged is named with its key, as a texture is; an EXR's
 * damage is a sentence, not OpenEXR's function and code (issue 42). */
Test(cli_options, environment_map_errors_name_the_key_and_say_what_is_wrong, .timeout = 300)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    char args[1200], exr[600];
    snprintf(exr, sizeof exr, "%s/good.exr", dir);
    snprintf(args, sizeof args, "render '%s/m.obj' --width 128 --height 128 --spp 1 --device cpu --quiet "
             "-o '%s'", dir, exr);
    cr_assert_eq(run_pt(NULL, args).exit_code, 0);
    size_t size = 0;
    char *good = test_read_file(exr, &size);
    cr_assert(good && size > 100);
    FILE *f = fopen(exr, "wb"); /* its last pixel rows cut off */
    cr_assert(f && fwrite(good, 1, size - size / 4, f) == size - size / 4 && fclose(f) == 0);
    free(good);
    test_write_file(dir, "header.exr", "this is no image, only text that is long enough");
    static const char *const cases[][2] = {{"missing.hdr", "no such file"},
                                           {"good.exr", "its pixel data is damaged or truncated"},
                                           {"header.exr", "is not an OpenEXR image"}};
    for (int i = 0; i < 3; i++) {
        char scene[300];
        snprintf(scene, sizeof scene,
                 "{\"objects\": [{\"obj\": \"m.obj\"}], \"environment\": {\"file\": \"%s\"}}",
                 cases[i][0]);
        const char *path = test_write_file(dir, "scene.json", scene);
        snprintf(args, sizeof args, "render '%s' --width 8 --height 8 --spp 1 --device cpu --quiet "
                 "-o '%s/out.exr'", path, dir);
        Run r = run_pt(NULL, args);
        expect_clean_error(r, cases[i][0], "environment.file", cases[i][1]);
        cr_expect(strstr(r.err, cases[i][0]) && !strstr(r.err, "EXR_ERR") && !strstr(r.err, "failed"),
                  "%s", r.err);
    }
}

/* environment.scale past 1e9 (1e39 is not even a float) is refused naming the key. */
Test(cli_options, an_environment_scale_beyond_float_is_refused)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const char *scales[] = {"1e39", "1e10", "-1"};
    for (int i = 0; i < 3; i++) {
        char scene[300], args[1000];
        snprintf(scene, sizeof scene, "{\"objects\": [{\"obj\": \"m.obj\"}], \"environment\": "
                 "{\"file\": \"../shared/x.hdr\", \"scale\": %s}}", scales[i]);
        const char *path = test_write_file(dir, "scene.json", scene);
        snprintf(args, sizeof args, "render '%s' --width 8 --height 8 --spp 1 --device cpu --quiet "
                 "-o '%s/out.exr'", path, dir);
        expect_clean_error(run_pt(NULL, args), scales[i], "environment.scale", NULL);
    }
}
