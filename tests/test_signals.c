// SPDX-License-Identifier: MIT
/* pt render under SIGINT, SIGTERM and SIGHUP: the image accumulated so far is written, no
 * temporary file is left, and the exit status is 128 + the signal. pt runs as a child process
 * whose stderr the test reads; signals are sent only after an event (the first "pt: progress:"
 * line of --progress, i.e. a window is done) or raised by pt itself at a named point
 * (PT_TEST_RAISE), never after a sleep. The renders ask for far more samples than they can finish,
 * so a signal sent after the event always finds the render running. The EXR of an interrupted
 * render says so in its header (partial = 1, spp = the samples it holds, read back with OpenEXR's
 * C API). */
#define _XOPEN_SOURCE 700 /* realpath, mkdtemp */
#include <criterion/criterion.h>
#include <dirent.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "exr_inspect.h"
#include "io/image_io.h"
#include "support.h"

#define FILM 64
#define ENDLESS_SPP "100000000"

typedef struct {
    pid_t pid;
    FILE *err; /* the child's stderr */
    char dir[256], output[300];
    char log[16384]; /* everything read from stderr */
} Child;

/* Starts `pt render scenes/cornell-box -o DIR/out.exr --device cpu --width 64 --height 64` plus
 * extra (NULL-terminated) with the environment assignment env (NULL = none) and the signals'
 * default dispositions, except `ignored` (0 = none), ignored as nohup does. */
static void start_pt(Child *c, const char *env, int ignored, const char *const *extra)
{
    memset(c, 0, sizeof *c);
    snprintf(c->dir, sizeof c->dir, "/tmp/pt-signals-XXXXXX");
    cr_assert(mkdtemp(c->dir));
    snprintf(c->output, sizeof c->output, "%s/out.exr", c->dir);
    const char *argv[32] = {test_pt_bin(), "render", "scenes/cornell-box", "-o", c->output, "--device",
                            "cpu", "--width", "64", "--height", "64"};
    int argc = 11;
    for (int i = 0; extra[i]; i++)
        argv[argc++] = extra[i];
    int fds[2];
    cr_assert_eq(pipe(fds), 0);
    c->pid = fork();
    cr_assert_neq(c->pid, -1);
    if (c->pid == 0) {
        dup2(fds[1], STDERR_FILENO);
        close(fds[0]), close(fds[1]);
        if (!freopen("/dev/null", "w", stdout))
            _exit(127);
        int signals[] = {SIGINT, SIGTERM, SIGHUP};
        for (int i = 0; i < 3; i++)
            signal(signals[i], signals[i] == ignored ? SIG_IGN : SIG_DFL);
        sigset_t none;
        sigemptyset(&none);
        sigprocmask(SIG_SETMASK, &none, NULL);
        if (env)
            putenv((char *)env);
        execv(argv[0], (char *const *)argv);
        _exit(127);
    }
    close(fds[1]);
    c->err = fdopen(fds[0], "r");
    cr_assert(c->err);
}

/* Reads stderr until a line starting with prefix; false at end of file. */
static bool wait_for_line(Child *c, const char *prefix, char *line, size_t size)
{
    while (fgets(line, (int)size, c->err)) {
        strncat(c->log, line, sizeof c->log - strlen(c->log) - 1);
        if (!strncmp(line, prefix, strlen(prefix)))
            return true;
    }
    return false;
}

/* Reads stderr to its end and returns the exit status (-signal when killed). */
static int finish(Child *c)
{
    char line[4096];
    while (fgets(line, sizeof line, c->err))
        strncat(c->log, line, sizeof c->log - strlen(c->log) - 1);
    fclose(c->err);
    int status;
    cr_assert_eq(waitpid(c->pid, &status, 0), c->pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

/* Waits for the first progress line; returns the spp it reports. */
static int wait_for_first_window(Child *c)
{
    char line[1024];
    cr_assert(wait_for_line(c, "pt: progress: ", line, sizeof line),
              "no progress line before pt ended; stderr:\n%s", c->log);
    int done = -1;
    cr_assert_eq(sscanf(line, "pt: progress: %d/", &done), 1, "%s", line);
    return done;
}

/* The output is a whole EXR of the film with light in it, and nothing else is in the folder
 * (no "out.exr.tmp-PID"). */
static void expect_image_and_no_temporary_file(const Child *c)
{
    float *rgb = NULL;
    int width = 0, height = 0;
    Error err = {0};
    cr_assert(image_read_exr(c->output, &rgb, &width, &height, &err), "%s; stderr:\n%s",
              err.message, c->log);
    cr_expect_eq(width, FILM);
    cr_expect_eq(height, FILM);
    double sum = 0.0;
    for (int i = 0; i < 3 * width * height; i++)
        sum += rgb[i];
    cr_expect_gt(sum, 0.0, "the image is black");
    free(rgb);
    DIR *dir = opendir(c->dir);
    cr_assert(dir);
    struct dirent *entry;
    while ((entry = readdir(dir))) {
        cr_expect(!strstr(entry->d_name, ".tmp-"), "temporary file %s/%s left", c->dir,
                  entry->d_name);
        if (strcmp(entry->d_name, ".") && strcmp(entry->d_name, "..") &&
            !strstr(entry->d_name, ".tmp-")) {
            char path[600];
            snprintf(path, sizeof path, "%s/%s", c->dir, entry->d_name);
            unlink(path);
        }
    }
    closedir(dir);
    rmdir(c->dir);
}

/* "pt: stopped by NAME: the image holds N of M spp" with N >= at_least; returns N. */
static int expect_stopped_message(const Child *c, const char *name, int at_least, int of)
{
    char needle[64];
    snprintf(needle, sizeof needle, "pt: stopped by %s: the image holds ", name);
    const char *at = strstr(c->log, needle);
    cr_assert(at, "'%s' not in stderr:\n%s", needle, c->log);
    int held = -1, total = -1;
    cr_assert_eq(sscanf(at + strlen(needle), "%d of %d spp", &held, &total), 2, "%s", at);
    cr_expect_geq(held, at_least, "%s", at);
    cr_expect_eq(total, of, "%s", at);
    return held;
}

/* The EXR's header: partial as expected, spp = the samples held (as pt said), spp_requested; with
 * the spp layer, every pixel holds at least that many samples. */
static void expect_header(const Child *c, int partial, int held, int requested, bool spp_layer)
{
    ExrInspect f;
    exr_inspect_open(&f, c->output);
    cr_expect_eq(exr_inspect_int(&f, "partial"), partial, "stderr:\n%s", c->log);
    cr_expect_eq(exr_inspect_int(&f, "spp"), held);
    cr_expect_eq(exr_inspect_int(&f, "spp_requested"), requested);
    if (spp_layer) {
        float *spp = exr_inspect_channel(&f, "spp.Y");
        for (int i = 0; i < f.width * f.height; i++)
            cr_expect_geq(spp[i], (float)held, "spp.Y[%d] = %g", i, spp[i]);
        free(spp);
    }
    exr_inspect_close(&f);
}

static void signal_after_first_window(int signal_number, int count, const char *name, int status)
{
    Child c;
    const char *extra[] = {"--spp", ENDLESS_SPP, "--progress", NULL};
    start_pt(&c, NULL, 0, extra);
    int done = wait_for_first_window(&c);
    cr_expect_geq(done, 1, "the first window holds whole samples of a 64x64 film");
    for (int i = 0; i < count; i++)
        cr_assert_eq(kill(c.pid, signal_number), 0);
    cr_expect_eq(finish(&c), status, "stderr:\n%s", c.log);
    int held = expect_stopped_message(&c, name, done, atoi(ENDLESS_SPP));
    expect_header(&c, 1, held, atoi(ENDLESS_SPP), false);
    expect_image_and_no_temporary_file(&c);
}

Test(signals, sigint_keeps_the_image, .timeout = 300)
{
    signal_after_first_window(SIGINT, 1, "SIGINT", 130);
}

/* The second Ctrl-C used to kill pt (signal() is one-shot under -std=c11) and lose the image. */
Test(signals, second_sigint_right_after_the_first_keeps_the_image, .timeout = 300)
{
    signal_after_first_window(SIGINT, 2, "SIGINT", 130);
}

/* The second SIGINT after pt has acted on the first (it is reading the film or writing). */
Test(signals, sigint_while_stopping_keeps_the_image, .timeout = 300)
{
    Child c;
    const char *extra[] = {"--spp", ENDLESS_SPP, "--progress", NULL};
    start_pt(&c, NULL, 0, extra);
    int done = wait_for_first_window(&c);
    cr_assert_eq(kill(c.pid, SIGINT), 0);
    char line[1024];
    cr_assert(wait_for_line(&c, "pt: SIGINT received: stopping", line, sizeof line), "%s", c.log);
    cr_assert_eq(kill(c.pid, SIGINT), 0);
    cr_expect_eq(finish(&c), 130, "stderr:\n%s", c.log);
    expect_stopped_message(&c, "SIGINT", done, atoi(ENDLESS_SPP));
    expect_image_and_no_temporary_file(&c);
}

Test(signals, sigterm_keeps_the_image, .timeout = 300)
{
    signal_after_first_window(SIGTERM, 1, "SIGTERM", 143);
}

Test(signals, sighup_keeps_the_image, .timeout = 300)
{
    signal_after_first_window(SIGHUP, 1, "SIGHUP", 129);
}

/* SIGINT or SIGTERM raised by pt itself right after its first window (no timing involved), with
 * every AOV asked for: the AOV pass still runs on what is held, the file has every layer, and the
 * header says partial with the samples held, fewer than asked. */
static void raise_mid_render_with_aovs(const char *env, const char *name, int status)
{
    Child c;
    const char *extra[] = {"--aov", "all", "--spp", ENDLESS_SPP, NULL};
    start_pt(&c, env, 0, extra);
    cr_expect_eq(finish(&c), status, "stderr:\n%s", c.log);
    int held = expect_stopped_message(&c, name, 1, atoi(ENDLESS_SPP));
    cr_expect_lt(held, atoi(ENDLESS_SPP));
    expect_header(&c, 1, held, atoi(ENDLESS_SPP), true);
    ExrInspect f;
    exr_inspect_open(&f, c.output);
    cr_expect_eq(f.channel_count, 15, "beauty (with A) and every layer's channels");
    cr_expect_geq(exr_inspect_find(&f, "albedo.R"), 0);
    exr_inspect_close(&f);
    expect_image_and_no_temporary_file(&c);
}

Test(signals, sigint_mid_render_writes_every_layer_marked_partial, .timeout = 300)
{
    raise_mid_render_with_aovs("PT_TEST_RAISE=INT@render", "SIGINT", 130);
}

Test(signals, sigterm_mid_render_writes_every_layer_marked_partial, .timeout = 300)
{
    raise_mid_render_with_aovs("PT_TEST_RAISE=TERM@render", "SIGTERM", 143);
}

/* A signal once every sample is done (the first window holds all 4): the image is whole, so not
 * partial, though the exit status still reports the signal. */
Test(signals, signal_after_the_last_sample_is_not_partial, .timeout = 300)
{
    Child c;
    const char *extra[] = {"--aov", "albedo", "--spp", "4", NULL};
    start_pt(&c, "PT_TEST_RAISE=SIGINT@render", 0, extra);
    cr_expect_eq(finish(&c), 130, "stderr:\n%s", c.log);
    expect_stopped_message(&c, "SIGINT", 4, 4);
    expect_header(&c, 0, 4, 4, false);
    expect_image_and_no_temporary_file(&c);
}

/* A signal between the temporary file and its rename: the write finishes (the rename happens),
 * nothing named *.tmp-* stays, and the exit status still reports the signal. */
Test(signals, signal_during_the_write_finishes_it, .timeout = 300)
{
    Child c;
    const char *extra[] = {"--spp", "2", "--preview", NULL};
    start_pt(&c, "PT_TEST_RAISE=TERM@write", 0, extra);
    cr_expect_eq(finish(&c), 143, "stderr:\n%s", c.log);
    expect_stopped_message(&c, "SIGTERM", 2, 2);
    char png[400];
    snprintf(png, sizeof png, "%s/out.png", c.dir);
    cr_expect_eq(access(png, F_OK), 0, "the preview after the interrupted write is missing");
    expect_image_and_no_temporary_file(&c);
}

/* Started ignoring SIGHUP (nohup), pt keeps ignoring it: the SIGTERM after it decides. */
Test(signals, a_signal_ignored_at_start_stays_ignored, .timeout = 300)
{
    Child c;
    const char *extra[] = {"--spp", ENDLESS_SPP, "--progress", NULL};
    start_pt(&c, NULL, SIGHUP, extra);
    wait_for_first_window(&c);
    cr_assert_eq(kill(c.pid, SIGHUP), 0);
    cr_assert_eq(kill(c.pid, SIGTERM), 0);
    int status = finish(&c);
    cr_expect_eq(status, 143, "exit %d; stderr:\n%s", status, c.log);
    expect_image_and_no_temporary_file(&c);
}

/* PT_TEST_RAISE is checked like every PT_* variable. */
Test(signals, bad_test_raise_value_is_one_clear_line, .timeout = 60)
{
    Child c;
    const char *extra[] = {"--spp", "1", NULL};
    start_pt(&c, "PT_TEST_RAISE=SEGV@render", 0, extra);
    cr_expect_eq(finish(&c), 1, "stderr:\n%s", c.log);
    cr_expect(strstr(c.log, "PT_TEST_RAISE=SEGV@render:") && strstr(c.log, "INT, TERM, HUP, KILL"),
              "%s", c.log);
    cr_expect(!strchr(c.log, '\n') || strchr(c.log, '\n')[1] == '\0', "one line: %s", c.log);
    rmdir(c.dir);
}
