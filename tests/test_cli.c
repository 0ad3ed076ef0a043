// SPDX-License-Identifier: MIT
/* The pt binary end to end: every bad input ends with one line on stderr naming what is wrong and
 * a non-zero exit (never a crash); a good render writes where it says and never overwrites what
 * it was not told to. PT_BIN names the binary (the Makefile sets it; default build/pt). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/cli.h"
#include "scene/scene.h"
#include "cli_run.h"
#include "support.h"

Test(cli, help_lists_the_commands)
{
    Run r = run_pt(NULL, "help");
    cr_expect_eq(r.exit_code, 0);
    const char *words[] = {"render", "view", "devices", "bench", "--spp", "--max-depth", "--device",
                           "--seed", "--aov", "--no-nee", "--no-compaction", "--exposure"};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        cr_expect(strstr(r.out, words[i]), "help does not mention %s", words[i]);
}

Test(cli, bad_command_line)
{
    expect_clean_error(run_pt(NULL, "frobnicate"), "unknown command", "frobnicate", NULL);
    expect_clean_error(run_pt(NULL, "render"), "missing scene", "SCENE", NULL);
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box --spp 0"), "spp 0", "--spp", NULL);
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box --spp lots"), "spp text", "lots", NULL);
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box --bogus"), "unknown option", "--bogus", NULL);
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box --aov shiny"), "bad aov", "shiny", NULL);
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box -o image.tiff --quiet"), "bad format", "image.tiff", NULL);
}

Test(cli, bad_scene_files)
{
    const char *dir = test_temp_dir();
    const char *path;
    char args[1024];
    expect_clean_error(run_pt(NULL, "render /nonexistent/scene.json"), "missing scene", "/nonexistent/scene.json", NULL);

    path = test_write_file(dir, "broken.json",
                           "{\n  \"film\": {\"width\": 64,\n  \"height\": 64}\n  \"objects\": []\n}\n");
    snprintf(args, sizeof args, "render '%s'", path);
    expect_clean_error(run_pt(NULL, args), "malformed JSON", "broken.json", ":4");

    path = test_write_file(dir, "unknown.json",
                           "{\"objects\": [{\"obj\": \"a.obj\"}], \"colour\": [1, 1, 1]}\n");
    snprintf(args, sizeof args, "render '%s'", path);
    expect_clean_error(run_pt(NULL, args), "unknown key", "colour", NULL);

    path = test_write_file(dir, "missing_obj.json", "{\"objects\": [{\"obj\": \"nowhere.obj\"}]}\n");
    snprintf(args, sizeof args, "render '%s'", path);
    expect_clean_error(run_pt(NULL, args), "missing OBJ", "nowhere.obj", NULL);

    path = test_write_file(dir, "bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    snprintf(args, sizeof args, "render '%s'", path);
    expect_clean_error(run_pt(NULL, args), "index out of range", "bad_index.obj", "4");

    path = test_write_file(dir, "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    snprintf(args, sizeof args, "render '%s'", path);
    expect_clean_error(run_pt(NULL, args), "non-finite vertex", "nan.obj", "2");

    path = test_write_file(dir, "empty.obj", "# nothing here\n");
    snprintf(args, sizeof args, "render '%s'", path);
    expect_clean_error(run_pt(NULL, args), "no triangles", "empty.obj", NULL);
}

Test(cli, bad_device_and_output)
{
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box --device 7:3 --quiet"), "unknown device", "7:3", NULL);
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box --device tpu --quiet"), "unknown device", "tpu", NULL);
    /* The output folder is checked before any rendering starts. */
    expect_clean_error(run_pt(NULL, "render scenes/cornell-box -o /nonexistent/dir/x.exr --quiet"),
                       "unwritable output", "/nonexistent/dir/x.exr", NULL);
}

Test(cli, render_writes_outputs_and_never_overwrites_without_o, .timeout = 120)
{
    const char *dir = test_temp_dir();
    char cwd[PATH_MAX], args[PATH_MAX + 200];
    cr_assert(getcwd(cwd, sizeof cwd));
    snprintf(args, sizeof args,
             "render '%s/scenes/cornell-box' --width 16 --height 16 --spp 1 --device cpu --quiet", cwd);
    Run first = run_pt(dir, args);
    cr_assert_eq(first.exit_code, 0, "%s", first.err);
    cr_expect(strstr(first.out, "out/cornell-box.exr") && strstr(first.out, "out/cornell-box.png"), "%s", first.out);
    Run second = run_pt(dir, args);
    cr_assert_eq(second.exit_code, 0, "%s", second.err);
    cr_expect(strstr(second.out, "out/cornell-box-2.exr") && strstr(second.out, "out/cornell-box-2.png"), "%s", second.out);
    struct stat st;
    char path[1024];
    const char *files[] = {"cornell-box.exr", "cornell-box.png", "cornell-box-2.exr", "cornell-box-2.png"};
    for (int i = 0; i < 4; i++) {
        snprintf(path, sizeof path, "%s/out/%s", dir, files[i]);
        cr_expect(stat(path, &st) == 0 && st.st_size > 0, "%s missing", path);
    }
    /* -o names the file and its format. */
    snprintf(args, sizeof args,
             "render '%s/scenes/cornell-box' --width 16 --height 16 --spp 1 --device cpu --quiet -o named.png", cwd);
    Run named = run_pt(dir, args);
    cr_assert_eq(named.exit_code, 0, "%s", named.err);
    snprintf(path, sizeof path, "%s/named.png", dir);
    cr_expect(stat(path, &st) == 0 && st.st_size > 0);
}

/* Every PT_* variable is checked: a bad value is one line naming the variable, the value and
 * what is allowed (PT_LOCAL_SIZE=0 used to divide by zero, =abc to hang). */
Test(cli, bad_environment_variables, .timeout = 120)
{
    const char *render = "render scenes/cornell-box --width 8 --height 8 --spp 1 --device cpu --quiet -o /tmp/pt-cli-env.exr";
    expect_clean_error(run_pt_env(NULL, "PT_LOCAL_SIZE=0", render), "local size 0", "PT_LOCAL_SIZE=0:", "from 1 to");
    expect_clean_error(run_pt_env(NULL, "PT_LOCAL_SIZE=abc", render), "local size abc", "PT_LOCAL_SIZE=abc:", "integer");
    expect_clean_error(run_pt_env(NULL, "PT_LOCAL_SIZE=99999999", render), "local size huge", "PT_LOCAL_SIZE=99999999:", "from 1 to");
    expect_clean_error(run_pt_env(NULL, "PT_LOCAL_SIZE=-8", render), "local size negative", "PT_LOCAL_SIZE=-8:", NULL);
    expect_clean_error(run_pt_env(NULL, "PT_BVH_WIDTH=3", render), "bvh width 3", "PT_BVH_WIDTH=3:", "2, 4 and 8");
    expect_clean_error(run_pt_env(NULL, "PT_BVH_WIDTH=8x", render), "bvh width 8x", "PT_BVH_WIDTH=8x:", NULL);
    expect_clean_error(run_pt_env(NULL, "PT_BVH_QUANTIZED=yes", render), "quantized yes", "PT_BVH_QUANTIZED=yes:", "0 or 1");
    expect_clean_error(run_pt_env(NULL, "PT_NO_CACHE=yes", render), "no cache yes", "PT_NO_CACHE=yes:", "0 or 1");
    expect_clean_error(run_pt_env(NULL, "PT_MEGAKERNEL=2", render), "megakernel 2", "PT_MEGAKERNEL=2:", "0 or 1");
    expect_clean_error(run_pt_env(NULL, "PT_PACKETS=on", render), "packets on", "PT_PACKETS=on:", "0 or 1");
    expect_clean_error(run_pt_env(NULL, "PT_CL_OPTIONS=\"$(printf 'a\\001b')\"", render), "options control character",
                       "PT_CL_OPTIONS", "not printable");
    char *long_options = malloc(2000);
    cr_assert(long_options);
    strcpy(long_options, "PT_CL_OPTIONS='");
    for (int i = 0; i < 300; i++)
        strcat(long_options, "-DX ");
    strcat(long_options, "'");
    expect_clean_error(run_pt_env(NULL, long_options, render), "options too long", "PT_CL_OPTIONS", "at most");
    free(long_options);
    /* Valid values still render. */
    Run good = run_pt_env(NULL, "PT_LOCAL_SIZE=32 PT_BVH_WIDTH=2 PT_BVH_QUANTIZED=1 PT_NO_CACHE=0", render);
    cr_expect_eq(good.exit_code, 0, "%s", good.err);
    unlink("/tmp/pt-cli-env.exr");
}

/* --device gpu on a machine without one says so and lists what there is (it used to call 'gpu'
 * an unknown device name). */
Test(cli, missing_gpu_is_named_as_missing, .timeout = 60)
{
    Run list = run_pt(NULL, "devices");
    cr_assert_eq(list.exit_code, 0, "%s", list.err);
    if (!strstr(list.out, "no GPU found"))
        cr_skip_test("this machine has a GPU");
    Run r = run_pt(NULL, "render scenes/cornell-box --device gpu --quiet");
    expect_clean_error(r, "no GPU", "no GPU", "0:0");
    /* ... with the hint that pt devices gives for a GPU whose driver is not registered. */
    cr_expect(strstr(r.err, "OCL_ICD_VENDORS=/tmp/icd"), "no ICD hint in: %s", r.err);
    cr_expect(!strstr(r.err, "unknown device"), "%s", r.err);
}

/* A 100 KB file name is shown as its start and end, not in full (nor cut off mid-way with the
 * rest of the message lost). */
Test(cli, long_file_names_are_shortened_in_messages)
{
    size_t n = 100 * 1024;
    char *name = malloc(n + 32);
    cr_assert(name);
    strcpy(name, "/nonexistent/");
    for (size_t i = strlen(name); i < n; i++)
        name[i] = (i - strlen("/nonexistent/")) % 2 ? '/' : 'd';
    strcpy(name + n, "end-of-name.json");
    char *args = malloc(n + 128);
    cr_assert(args);
    snprintf(args, n + 128, "render '%s'", name);
    Run r = run_pt(NULL, args);
    expect_clean_error(r, "long name", "/nonexistent/d/d/", "end-of-name.json");
    cr_expect_lt(strlen(r.err), 300, "the message is %zu bytes: %.400s", strlen(r.err), r.err);
    cr_expect(strstr(r.err, "\xe2\x80\xa6"), "no ellipsis in: %s", r.err);
    /* An output name too long for pt is refused as such (it used to be cut to 1099 bytes). */
    strcpy(name + n, "end-of-name.exr");
    snprintf(args, n + 128, "render scenes/cornell-box --device cpu --quiet -o '%s'", name);
    r = run_pt(NULL, args);
    expect_clean_error(r, "long output", "too long", "end-of-name.exr");
    cr_expect_lt(strlen(r.err), 300, "the message is %zu bytes: %.400s", strlen(r.err), r.err);
    free(args);
    free(name);
}

static bool parse_args(const char *a1, const char *a2, Options *o, Error *err)
{
    char *argv[] = {"pt", "render", "scene.json", (char *)a1, (char *)a2, NULL};
    memset(err, 0, sizeof *err);
    return cli_parse(5, argv, o, err);
}

/* The seed is a uint: all of 0..4294967295 (it stopped at INT_MAX), and nothing else. */
Test(cli, seed_takes_every_unsigned_value)
{
    Options o;
    Error err;
    cr_expect(parse_args("--seed", "4294967295", &o, &err), "%s", err.message);
    cr_expect_eq(o.seed, 4294967295u);
    cr_expect(parse_args("--seed", "2147483648", &o, &err), "%s", err.message);
    cr_expect_eq(o.seed, 2147483648u);
    cr_expect(parse_args("--seed", "0", &o, &err), "%s", err.message);
    cr_expect_eq(o.seed, 0u);
    const char *bad[] = {"4294967296", "-1", " -1", "18446744073709551615", "1e3", "x"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        cr_expect_not(parse_args("--seed", bad[i], &o, &err), "--seed %s accepted", bad[i]);
        cr_expect(strstr(err.message, "4294967295"), "%s", err.message);
    }
}

/* --max-depth and render.max_depth share MAX_DEPTH_LIMIT; --width/--height FILM_SIZE_LIMIT. */
Test(cli, depth_and_film_limits_are_the_scenes)
{
    Options o;
    Error err;
    char value[32];
    snprintf(value, sizeof value, "%d", MAX_DEPTH_LIMIT);
    cr_expect(parse_args("--max-depth", value, &o, &err), "%s", err.message);
    snprintf(value, sizeof value, "%d", MAX_DEPTH_LIMIT + 1);
    cr_expect_not(parse_args("--max-depth", value, &o, &err));
    snprintf(value, sizeof value, "%d", FILM_SIZE_LIMIT + 1);
    cr_expect_not(parse_args("--width", value, &o, &err));
}

/* Without -o, when every numbered name up to the limit (9999) exists, pt refuses instead of
 * overwriting the last one. */
Test(cli, numbered_outputs_never_overwrite_the_last_name, .timeout = 120)
{
    const char *dir = test_temp_dir();
    char cwd[PATH_MAX], args[PATH_MAX + 200], path[1024];
    cr_assert(getcwd(cwd, sizeof cwd));
    snprintf(path, sizeof path, "%s/out", dir);
    cr_assert_eq(mkdir(path, 0777), 0);
    for (int n = 1; n <= 9999; n++) {
        if (n == 1)
            snprintf(path, sizeof path, "%s/out/cornell-box.png", dir);
        else
            snprintf(path, sizeof path, "%s/out/cornell-box-%d.png", dir, n);
        FILE *f = fopen(path, "w");
        cr_assert(f, "cannot create %s", path);
        fclose(f);
    }
    snprintf(args, sizeof args,
             "render '%s/scenes/cornell-box' --width 8 --height 8 --spp 1 --device cpu --quiet", cwd);
    Run r = run_pt(dir, args);
    expect_clean_error(r, "all names taken", "cornell-box-9999", "-o");
    struct stat st;
    snprintf(path, sizeof path, "%s/out/cornell-box-9999.png", dir);
    cr_expect(stat(path, &st) == 0 && st.st_size == 0, "out/cornell-box-9999.png was overwritten");
    snprintf(path, sizeof path, "%s/out/cornell-box-9999.exr", dir);
    cr_expect(stat(path, &st) != 0, "out/cornell-box-9999.exr was written");
    snprintf(path, sizeof path, "%s/out/cornell-box-10000.exr", dir);
    cr_expect(stat(path, &st) != 0, "out/cornell-box-10000.exr was written");
}

/* pt bench prints no empty section: no stage row of a stage never launched, no heading without
 * lines under it (the megakernel keeps no live-path counts). */
Test(cli, bench_prints_no_empty_sections, .timeout = 600)
{
    Run r = run_pt(NULL, "bench scenes/cornell-box --spp 1 --width 16 --height 16");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    const char *all[] = {r.out, r.err};
    for (int k = 0; k < 2; k++) {
        const char *line = all[k];
        while (*line) {
            size_t n = strcspn(line, "\n");
            cr_expect(n == 0 || line[n - 1] != ':', "an empty section: %.*s", (int)n, line);
            char name[64];
            unsigned launches;
            if (sscanf(line, "%63s %u", name, &launches) == 2 && strchr(name, '_'))
                cr_expect(launches > 0, "a stage never launched: %.*s", (int)n, line);
            line += n + (line[n] == '\n');
        }
    }
}

/* Adaptive sampling says how it spent the samples; with a checkpoint it is refused before the
 * scene is read (the scene here does not exist: the refusal comes first), naming what to drop. */
Test(cli, adaptive_reports_spp_and_refuses_a_checkpoint_first, .timeout = 300)
{
    Run r = run_pt(NULL, "render /nonexistent/scene.json --noise-threshold 0.1 --checkpoint 5");
    cr_expect_eq(r.exit_code, 1);
    cr_expect(strstr(r.err, "drop --checkpoint") && !strstr(r.err, "nonexistent"), "%s", r.err);
    r = run_pt(NULL, "render /nonexistent/scene.json --noise-threshold 0.1 --resume");
    cr_expect(strstr(r.err, "drop --resume"), "%s", r.err);
    const char *dir = test_temp_dir();
    char args[1024];
    snprintf(args, sizeof args, "render scenes/cornell-box --width 16 --height 16 --spp 8 --min-spp 2 "
             "--noise-threshold 0.5 -o '%s/a.exr'", dir);
    r = run_pt(NULL, args);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    const char *line = strstr(r.err, "pt: adaptive sampling (noise threshold 0.5): ");
    cr_assert(line, "%s", r.err);
    double mean;
    int lo, hi;
    cr_assert_eq(sscanf(line, "pt: adaptive sampling (noise threshold 0.5): %lf spp per pixel on average, %d to %d",
                        &mean, &lo, &hi), 3, "%s", line);
    cr_expect(lo >= 2 && hi <= 8 && lo <= mean && mean <= hi, "%g %d %d", mean, lo, hi);
}
