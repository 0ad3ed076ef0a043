// SPDX-License-Identifier: MIT
/* `pt render --device all` and device lists, end to end: pt runs as a child process with
 * POCL_DEVICES="pthread pthread" in its environment, so that PoCL exposes two CPU devices. Its EXR
 * pixels are the bits of a one-device render for unit sizes 1, 7 and 64 spp and a row split
 * (pixels are compared, not files: the header holds render_time); bad device lists, no device and
 * what the unit path refuses are one clear line and exit 1; a time limit and SIGINT on the unit
 * path write a partial image marked partial. The SIGINT is sent once a progress line reports
 * finished paths (an event, never a sleep). */
#define _XOPEN_SOURCE 700 /* mkdtemp, kill */
#include <criterion/criterion.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_run.h"
#include "exr_inspect.h"
#include "io/image_io.h"
#include "support.h"

#define TWO_DEVICES "POCL_DEVICES='pthread pthread'"
#define SCENE_ARGS "render scenes/cornell-box --width 48 --height 32"

/* Removes a folder of test_temp_dir's with what the test wrote into it. */
static void remove_temp_dir(const char *dir)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect_eq(system(cmd), 0);
}

static float *read_rgb(const char *path)
{
    float *rgb = NULL;
    int width = 0, height = 0;
    Error err = {0};
    cr_assert(image_read_exr(path, &rgb, &width, &height, &err), "%s", err.message);
    cr_assert_eq(width, 48);
    cr_assert_eq(height, 32);
    return rgb;
}

static void expect_same_pixels(const char *a_path, const char *b_path, const char *what)
{
    float *a = read_rgb(a_path), *b = read_rgb(b_path);
    size_t n = 48 * 32 * 3, differ = 0, first = 0;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        sum += a[i];
        if (memcmp(&a[i], &b[i], sizeof a[i]) != 0 && differ++ == 0)
            first = i;
    }
    cr_expect_gt(sum, 0.0, "%s: the image is black", what);
    cr_expect_eq(differ, 0, "%s: %zu of %zu values differ, the first at pixel %zu (%.9g vs %.9g)",
                 what, differ, n, first / 3, differ ? a[first] : 0.0, differ ? b[first] : 0.0);
    free(a), free(b);
}

Test(multi_device, two_devices_give_the_bits_of_one_for_any_unit_size, .timeout = 600)
{
    const char *dir = test_temp_dir();
    char args[1024], one[512], many[512];
    snprintf(one, sizeof one, "%s/one.exr", dir);
    snprintf(args, sizeof args, SCENE_ARGS " --spp 64 --quiet -o %s", one);
    Run r = run_pt(NULL, args);
    cr_assert_eq(r.exit_code, 0, "one device: %s", r.err);
    const char *splits[] = {"--unit-spp 1", "--unit-spp 7", "--unit-spp 64",
                            "--unit-spp 7 --unit-rows 5", "--unit-rows 1"};
    for (size_t i = 0; i < sizeof splits / sizeof splits[0]; i++) {
        snprintf(many, sizeof many, "%s/many%zu.exr", dir, i);
        snprintf(args, sizeof args, SCENE_ARGS " --spp 64 --device all %s -o %s", splits[i], many);
        r = run_pt_env(NULL, TWO_DEVICES, args);
        cr_assert_eq(r.exit_code, 0, "%s: %s", splits[i], r.err);
        /* Both devices rendered (the report names each). */
        cr_expect(strstr(r.err, "device 0:0 ") && strstr(r.err, "device 0:1 "),
                  "%s: not two devices: %s", splits[i], r.err);
        expect_same_pixels(one, many, splits[i]);
    }
    remove_temp_dir(dir);
}

Test(multi_device, a_device_listed_twice_is_refused, .timeout = 120)
{
    Run r = run_pt(NULL, SCENE_ARGS " --spp 1 --device 0:0,0:0 -o /tmp/pt-never.exr");
    expect_clean_error(r, "0:0,0:0", "listed twice", "0:0");
    r = run_pt(NULL, SCENE_ARGS " --spp 1 --device cpu,0:0 -o /tmp/pt-never.exr");
    expect_clean_error(r, "cpu,0:0 (the same device named two ways)", "listed twice", "0:0");
}

Test(multi_device, an_unknown_device_in_the_list_is_named, .timeout = 120)
{
    Run r = run_pt(NULL, SCENE_ARGS " --spp 1 --device 0:0,9:9 -o /tmp/pt-never.exr");
    expect_clean_error(r, "0:0,9:9", "9:9", "pt devices");
}

/* No OpenCL driver at all (the ICD loader reads an empty vendors folder), and PoCL with no device
 * (POCL_DEVICES naming a driver it does not have). */
Test(multi_device, device_all_without_devices_is_a_clear_error, .timeout = 120)
{
    const char *dir = test_temp_dir();
    char env[512];
    snprintf(env, sizeof env, "OCL_ICD_VENDORS='%s'", dir);
    Run r = run_pt_env(NULL, env, SCENE_ARGS " --spp 1 --device all -o /tmp/pt-never.exr");
    expect_clean_error(r, "no OpenCL platform", "no OpenCL platform", NULL);
    r = run_pt_env(NULL, "POCL_DEVICES=no-such-driver",
                   SCENE_ARGS " --spp 1 --device all -o /tmp/pt-never.exr");
    expect_clean_error(r, "POCL_DEVICES=no-such-driver", "--device all", "no GPU or CPU");
    remove_temp_dir(dir);
}

Test(multi_device, the_unit_path_refuses_adaptive_sampling_and_variance, .timeout = 300)
{
    const char *dir = test_temp_dir();
    char args[1024], out[512];
    snprintf(out, sizeof out, "%s/never.exr", dir);
    snprintf(args, sizeof args,
             SCENE_ARGS " --spp 4 --quiet --device all --noise-threshold 0.05 -o %s", out);
    Run r = run_pt_env(NULL, TWO_DEVICES, args);
    expect_clean_error(r, "--noise-threshold", "adaptive sampling", "one device");
    snprintf(args, sizeof args, SCENE_ARGS " --spp 4 --quiet --device all --aov variance -o %s",
             out);
    r = run_pt_env(NULL, TWO_DEVICES, args);
    expect_clean_error(r, "--aov variance", "--aov variance", "one-device");
    snprintf(args, sizeof args, SCENE_ARGS " --spp 4 --quiet --unit-spp 2 --aov variance -o %s",
             out);
    r = run_pt(NULL, args);
    expect_clean_error(r, "--unit-spp with --aov variance", "--unit-spp", "variance");
    cr_expect_neq(access(out, F_OK), 0, "an image was written");
    remove_temp_dir(dir);
}

/* The EXR header of an interrupted render: partial = 1, fewer spp than asked; returns its spp. */
static int expect_partial(const char *path, int requested)
{
    ExrInspect f;
    exr_inspect_open(&f, path);
    cr_expect_eq(exr_inspect_int(&f, "partial"), 1, "%s: not marked partial", path);
    int spp = exr_inspect_int(&f, "spp");
    cr_expect_lt(spp, requested);
    cr_expect_eq(exr_inspect_int(&f, "spp_requested"), requested);
    exr_inspect_close(&f);
    return spp;
}

#define ENDLESS_SPP 100000

Test(multi_device, a_time_limit_on_the_unit_path_writes_a_partial_image, .timeout = 600)
{
    const char *dir = test_temp_dir();
    char args[1024], out[512];
    snprintf(out, sizeof out, "%s/limited.exr", dir);
    snprintf(args, sizeof args, SCENE_ARGS " --spp %d --device all --time-limit 0.2 -o %s",
             ENDLESS_SPP, out);
    Run r = run_pt_env(NULL, TWO_DEVICES, args);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    cr_expect(strstr(r.err, "stopped by the time limit"), "%s", r.err);
    expect_partial(out, ENDLESS_SPP);
    remove_temp_dir(dir);
}

/* pt with --progress, its stderr on a pipe; SIGINT once a progress line shows finished paths. */
Test(multi_device, sigint_on_the_unit_path_writes_a_partial_image, .timeout = 600)
{
    const char *dir = test_temp_dir();
    char out[512], spp[32];
    snprintf(out, sizeof out, "%s/interrupted.exr", dir);
    snprintf(spp, sizeof spp, "%d", ENDLESS_SPP);
    /* --time-limit: a bound on a run that would never stop if the test failed before its signal. */
    const char *argv[] = {test_pt_bin(), "render", "scenes/cornell-box", "--width", "48",
                          "--height", "32", "--spp", spp, "--device", "all", "--progress",
                          "--time-limit", "300", "-o", out, NULL};
    int fds[2];
    cr_assert_eq(pipe(fds), 0);
    pid_t pid = fork();
    cr_assert_neq(pid, -1);
    if (pid == 0) {
        dup2(fds[1], STDERR_FILENO);
        close(fds[0]), close(fds[1]);
        if (!freopen("/dev/null", "w", stdout))
            _exit(127);
        signal(SIGINT, SIG_DFL);
        setenv("POCL_DEVICES", "pthread pthread", 1);
        execv(argv[0], (char *const *)argv);
        _exit(127);
    }
    close(fds[1]);
    FILE *err = fdopen(fds[0], "r");
    cr_assert(err);
    static char log[32768];
    log[0] = '\0';
    char line[1024];
    bool signalled = false;
    while (fgets(line, sizeof line, err)) {
        strncat(log, line, sizeof log - strlen(log) - 1);
        int done = 0, asked = 0;
        double percent = 0.0;
        if (!signalled &&
            sscanf(line, "pt: progress: %d/%d spp (%lf%%)", &done, &asked, &percent) == 3 &&
            percent > 0.0) {
            cr_assert_eq(kill(pid, SIGINT), 0);
            signalled = true;
        }
    }
    fclose(err);
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    cr_assert(signalled, "no progress line with finished paths; stderr:\n%s", log);
    cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 130, "exit status %d; stderr:\n%s",
              status, log);
    cr_expect(strstr(log, "stopped by SIGINT"), "%s", log);
    /* A run had finished before the signal: the image holds its samples. */
    int held = expect_partial(out, ENDLESS_SPP);
    cr_expect_geq(held, 1, "the image holds no sample; stderr:\n%s", log);
    remove_temp_dir(dir);
}

/* pt bench's unit modes: "units" (one device through the scheduler) next to the default mode, and
 * "units-all" over both devices, in the table and the CSV files; the devices' units add up to the
 * grid's. */
Test(multi_device, bench_reports_the_unit_modes_per_device, .timeout = 600)
{
    const char *dir = test_temp_dir();
    char args[1024], csv[512];
    snprintf(csv, sizeof csv, "%s/bench.csv", dir);
    snprintf(args, sizeof args,
             "bench scenes/cornell-box --width 32 --height 16 --spp 6 --unit-spp 2 --device all "
             "--csv %s",
             csv);
    Run r = run_pt_env(NULL, TWO_DEVICES, args);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    cr_expect(strstr(r.out, "\nunits "), "no units row: %s", r.out);
    cr_expect(strstr(r.out, "\nunits-all "), "no units-all row: %s", r.out);
    cr_expect(strstr(r.out, "of the default mode's Mpaths/s"), "%s", r.out);
    char *text = test_read_file(csv, NULL);
    cr_assert(text);
    cr_expect(strstr(text, ",units,") && strstr(text, ",units-all,"), "%s", text);
    free(text);
    char path[600];
    snprintf(path, sizeof path, "%s/bench_units.csv", dir);
    text = test_read_file(path, NULL);
    cr_assert(text, "no %s", path);
    /* 3 sample blocks of one tile: "units" on 0:0, then "units-all" split over 0:0 and 0:1. */
    unsigned units = 0, all_units = 0, rows = 0;
    for (const char *line = strchr(text, '\n'); line && line[1]; line = strchr(line + 1, '\n')) {
        char mode[32], spec[16];
        unsigned n = 0;
        const char *format = "%31[^,],%15[^,],\"%*[^\"]\",\"%*[^\"]\",%*d,%*d,%*d,%u";
        cr_assert_eq(sscanf(line + 1, format, mode, spec, &n), 3, "%s", line + 1);
        if (!strcmp(mode, "units"))
            units += n;
        else
            all_units += n;
        rows++;
    }
    cr_expect_eq(rows, 3, "%s", text);
    cr_expect_eq(units, 3, "%s", text);
    cr_expect_eq(all_units, 3, "%s", text);
    free(text);
    remove_temp_dir(dir);
}
