// SPDX-License-Identifier: MIT
/* Checkpoint faults (issue 42), pt as a child process on PoCL: a FIFO, folder or device where
 * --resume reads the checkpoint is refused by name before any read (a FIFO used to hang pt); a
 * checkpoint that cannot be written (a full disk: here a file-size limit, RLIMIT_FSIZE, that the
 * image fits under and the checkpoint does not) is one warning, and the render still writes its
 * image; a write SIGKILLed mid-way leaves OUTPUT.tmp-PID, which the next pt writing that output
 * removes, keeping anything not of that exact naming or whose process still runs. No timing: the
 * kill and the stop come at named points (PT_TEST_RAISE), every pt runs under timeout -s KILL. */
#define _XOPEN_SOURCE 700
#include <criterion/criterion.h>
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_run.h"
#include "exr_inspect.h"
#include "support.h"

#define RENDER "render scenes/cornell-box --device cpu --width 64 --height 48 --spp 64 --unit-rows 8"
#define KILL_AFTER "timeout -s KILL 300"

Test(checkpoint_faults, special_files_in_the_checkpoints_place_are_refused_by_name, .timeout = 900)
{
    const char *dir = test_temp_dir();
    char fifo[300], folder[300], device[300], args[1000];
    snprintf(fifo, sizeof fifo, "%s/fifo.exr.ptckpt", dir);
    snprintf(folder, sizeof folder, "%s/folder.exr.ptckpt", dir);
    snprintf(device, sizeof device, "%s/device.exr.ptckpt", dir);
    cr_assert_eq(mkfifo(fifo, 0600), 0);
    cr_assert_eq(mkdir(folder, 0700), 0);
    cr_assert_eq(symlink("/dev/zero", device), 0);
    const char *cases[][2] = {{"fifo", "is a FIFO, not a pt checkpoint"},
                              {"folder", "is a directory, not a pt checkpoint"},
                              {"device", "is a character device, not a pt checkpoint"}};
    for (size_t i = 0; i < 3; i++) {
        snprintf(args, sizeof args, RENDER " --quiet --resume -o %s/%s.exr", dir, cases[i][0]);
        Run r = run_pt_env(NULL, KILL_AFTER, args);
        char name[320];
        snprintf(name, sizeof name, "%s/%s.exr.ptckpt", dir, cases[i][0]);
        expect_clean_error(r, cases[i][0], name, cases[i][1]);
    }
}

/* pt with a file-size limit (a full disk for any file over `limit` bytes), SIGXFSZ ignored so that
 * the write fails with EFBIG as it would with ENOSPC; stderr into err_path. Returns the exit
 * status (128 + signal when killed). */
static int run_with_file_size_limit(rlim_t limit, const char *env, const char *output,
                                    const char *err_path)
{
    const char *pt = test_pt_bin(); /* in the parent: it may fail the test */
    pid_t pid = fork();
    cr_assert_neq(pid, -1);
    if (pid == 0) {
        struct rlimit r = {limit, limit};
        if (setrlimit(RLIMIT_FSIZE, &r) != 0 || !freopen("/dev/null", "w", stdout) ||
            !freopen(err_path, "w", stderr))
            _exit(127);
        signal(SIGXFSZ, SIG_IGN);
        putenv((char *)env);
        execl(pt, pt, "render", "scenes/cornell-box", "--device", "cpu",
              "--width", "64", "--height", "48", "--spp", "64", "--unit-rows", "8", "--checkpoint",
              "0.001", "--quiet", "-o", output, (char *)NULL);
        _exit(127);
    }
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/* The checkpoint (98 KB here) cannot be written, the image (about 5 KB) can: stopped after its
 * second run (a stopped render always saves a checkpoint, so at least one write fails), pt writes
 * the image marked partial and says once that the checkpoint failed. */
Test(checkpoint_faults, a_checkpoint_that_cannot_be_written_keeps_the_image, .timeout = 900)
{
    const char *dir = test_temp_dir();
    char exr[300], err_path[300];
    snprintf(exr, sizeof exr, "%s/out.exr", dir);
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", dir);
    /* PoCL writes the source to its own cache at every build from source (pt's default there,
     * host/device/program.c), which the limit forbids; a program binary in pt's cache loads
     * without a write. So: the binary first, without the limit, then the limited run loads it. */
    setenv("PT_CACHE_BINARIES", "1", 1);
    char warm_args[400];
    snprintf(warm_args, sizeof warm_args, RENDER " --spp 1 --quiet -o %s/warm.exr", dir);
    Run warm = run_pt_env(NULL, KILL_AFTER, warm_args);
    cr_assert_eq(warm.exit_code, 0, "warm-up: %s", warm.err);
    int status = run_with_file_size_limit(50000, "PT_TEST_RAISE=TERM@unit:2", exr, err_path);
    char *log = test_read_file(err_path, NULL);
    cr_assert(log);
    cr_expect_eq(status, 143, "exit %d; stderr:\n%s", status, log);
    int warnings = 0;
    for (const char *at = log; (at = strstr(at, "pt: warning: checkpoint not written")); at++)
        warnings++;
    cr_expect_eq(warnings, 1, "one warning about the checkpoint; stderr:\n%s", log);
    cr_expect(strstr(log, "out.exr.ptckpt"), "the warning names the checkpoint:\n%s", log);
    ExrInspect f;
    exr_inspect_open(&f, exr);
    cr_expect_eq(exr_inspect_int(&f, "partial"), 1);
    exr_inspect_close(&f);
    DIR *d = opendir(dir);
    cr_assert(d);
    for (struct dirent *e; (e = readdir(d));)
        cr_expect(!strstr(e->d_name, ".tmp-") && !strstr(e->d_name, ".ptckpt"), "%s left", e->d_name);
    closedir(d);
    free(log);
}

static bool has_temp_file(const char *dir, const char *prefix)
{
    DIR *d = opendir(dir);
    cr_assert(d);
    bool found = false;
    for (struct dirent *e; (e = readdir(d));)
        found = found || !strncmp(e->d_name, prefix, strlen(prefix));
    closedir(d);
    return found;
}

/* SIGKILL between the checkpoint's temporary file and its rename leaves out.exr.ptckpt.tmp-PID;
 * the next checkpointed render of out.exr removes it. */
Test(checkpoint_faults, a_checkpoint_write_killed_midway_is_cleaned_up_next_time, .timeout = 900)
{
    const char *dir = test_temp_dir();
    char args[1000];
    snprintf(args, sizeof args, RENDER " --quiet --checkpoint 0.001 -o %s/out.exr", dir);
    Run r = run_pt_env(NULL, "PT_TEST_RAISE=KILL@write:1 " KILL_AFTER, args);
    cr_assert_eq(r.exit_code, 137, "exit %d: %s", r.exit_code, r.err);
    cr_assert(has_temp_file(dir, "out.exr.ptckpt.tmp-"), "the kill left no temporary file");
    snprintf(args, sizeof args, RENDER " --quiet --checkpoint 1000 -o %s/out.exr", dir);
    r = run_pt_env(NULL, KILL_AFTER, args);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    cr_expect(!has_temp_file(dir, "out.exr.ptckpt.tmp-"), "the stale temporary file stayed");
}

/* Only pt's exact naming for this output, and only for a process that is not running. */
Test(checkpoint_faults, only_stale_temporaries_of_pts_naming_are_removed, .timeout = 900)
{
    pid_t dead = fork();
    cr_assert_neq(dead, -1);
    if (dead == 0)
        _exit(0);
    cr_assert_eq(waitpid(dead, NULL, 0), dead); /* reaped: no process has this id now */
    const char *dir = test_temp_dir();
    char stale[64], alive[64], suffixed[64], other[64], args[1000];
    snprintf(stale, sizeof stale, "out.exr.tmp-%d", (int)dead);
    snprintf(alive, sizeof alive, "out.exr.tmp-%d", (int)getpid());
    snprintf(suffixed, sizeof suffixed, "out.exr.tmp-%dx", (int)dead);
    snprintf(other, sizeof other, "other.exr.tmp-%d", (int)dead);
    const char *names[] = {stale, alive, suffixed, other};
    for (int i = 0; i < 4; i++)
        test_write_file(dir, names[i], "partial image");
    snprintf(args, sizeof args, RENDER " --quiet --spp 1 -o %s/out.exr", dir);
    Run r = run_pt_env(NULL, KILL_AFTER, args);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    for (int i = 0; i < 4; i++) {
        char path[400];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        cr_expect_eq(access(path, F_OK) == 0, i != 0, "%s: %s", names[i],
                     i == 0 ? "the stale temporary stayed" : "removed though not stale");
    }
}
