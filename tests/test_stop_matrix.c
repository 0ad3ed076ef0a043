// SPDX-License-Identifier: MIT
/* Every way to stop pt render (the time limit, SIGINT, SIGTERM, SIGHUP) on every render path (one
 * device, work units, a checkpointed render, two devices, MPI ranks), with and without --quiet:
 * pt ends by itself with the exit status of the stop and a partial image that says so. --quiet
 * once made the unit render spin past its deadline holding the lock its device threads needed to
 * end, so that neither the time limit nor a signal stopped it (issue 42).
 *
 * Nothing here depends on timing: the renders ask for far more samples than any machine finishes
 * within the limit (0.01 s) or before the signal, which pt raises itself at a named point
 * (PT_TEST_RAISE: after its second run of units, or its first window) or which the test sends
 * once an event is seen (the first checkpoint file appears). Every pt runs under `timeout -s KILL`
 * so that a render that never stops fails the test (exit 137) instead of outliving it. */
#define _XOPEN_SOURCE 700 /* mkdtemp */
#include <criterion/criterion.h>
#include <poll.h>
#include <sys/inotify.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cli_run.h"
#include "exr_inspect.h"
#include "support.h"

/* 65536 spp of 32x32 pixels: minutes on PoCL, never done within 0.01 s or two runs of units. */
#define SPP 65536
#define RENDER "render scenes/cornell-box --device cpu --width 32 --height 32 --spp 65536"
#define KILL_AFTER "timeout -s KILL 400" /* a render that does not stop: exit 137 */
#define MPIRUN                                                                                     \
    "OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none "                      \
    "OMPI_MCA_rmaps_base_oversubscribe=1 " KILL_AFTER " mpirun --allow-run-as-root --oversubscribe -n 2"

typedef struct {
    const char *name;
    const char *env;    /* environment assignments before the command */
    const char *launch; /* before pt: timeout, or mpirun */
    const char *args;   /* the path's options */
    const char *point;  /* the PT_TEST_RAISE point the path reaches */
} RenderPath;

static const RenderPath ONE_DEVICE = {"one device", "", KILL_AFTER, "", "render"};
static const RenderPath UNITS = {"work units", "", KILL_AFTER, "--unit-spp 1", "unit:2"};
static const RenderPath CHECKPOINTED = {"checkpointed", "", KILL_AFTER, "--checkpoint 1000", "unit:2"};
static const RenderPath TWO_DEVICES = {"two devices", "POCL_DEVICES=\"pthread pthread\"", KILL_AFTER,
                                       "--device all --unit-spp 1", "unit:2"};
static const RenderPath MPI = {"two MPI ranks", "", MPIRUN, "--unit-spp 1", "unit:2"};

typedef struct {
    const char *name;   /* as pt's "stopped by ..." line says it */
    const char *signal; /* for PT_TEST_RAISE; NULL: the time limit */
    int status;
} Stop;

static const Stop STOPS[] = {{"the time limit", NULL, 0},
                             {"SIGINT", "INT", 130},
                             {"SIGTERM", "TERM", 143},
                             {"SIGHUP", "HUP", 129}};

/* The image is whole-sized and marked partial, holding fewer samples than asked. */
static void expect_partial_image(const char *exr, const char *what, const char *log)
{
    ExrInspect f;
    exr_inspect_open(&f, exr);
    cr_expect_eq(f.width, 32, "%s", what);
    cr_expect_eq(exr_inspect_int(&f, "partial"), 1, "%s: stderr:\n%s", what, log);
    int held = exr_inspect_int(&f, "spp");
    cr_expect(held >= 1 && held < SPP, "%s: spp %d", what, held);
    cr_expect_eq(exr_inspect_int(&f, "spp_requested"), SPP, "%s", what);
    exr_inspect_close(&f);
}

static void stop_render(const RenderPath *p, const Stop *s, bool quiet)
{
    char dir[64] = "/tmp/pt-stop-XXXXXX", what[200], env[400], args[1000];
    cr_assert(mkdtemp(dir));
    snprintf(what, sizeof what, "%s, stopped by %s%s", p->name, s->name, quiet ? ", --quiet" : "");
    fprintf(stderr, "test_stop_matrix: %s\n", what);
    /* OpenMPI's session folder in the run's own (test_mpi.c says why): Criterion runs these tests
     * side by side, and two mpiruns that create the shared /tmp/ompi.<host>.<uid> at once can
     * fail with "File exists" (seen in CI: mpi_time_limit). Other paths ignore it. */
    if (s->signal)
        snprintf(env, sizeof env, "%s OMPI_MCA_orte_tmpdir_base=%s PT_TEST_RAISE=%s@%s %s", p->env,
                 dir, s->signal, p->point, p->launch);
    else
        snprintf(env, sizeof env, "%s OMPI_MCA_orte_tmpdir_base=%s %s", p->env, dir, p->launch);
    snprintf(args, sizeof args, RENDER " %s%s%s -o %s/out.exr", p->args,
             s->signal ? "" : " --time-limit 0.01", quiet ? " --quiet" : "", dir);
    Run r = run_pt_env(NULL, env, args);
    cr_expect_eq(r.exit_code, s->status, "%s: exit %d; stderr:\n%s", what, r.exit_code, r.err);
    char needle[100];
    snprintf(needle, sizeof needle, "pt: stopped by %s: the image holds ", s->name);
    cr_expect(strstr(r.err, needle), "%s: '%s' not in stderr:\n%s", what, needle, r.err);
    char exr[200];
    snprintf(exr, sizeof exr, "%s/out.exr", dir);
    expect_partial_image(exr, what, r.err);
    char cleanup[200];
    snprintf(cleanup, sizeof cleanup, "rm -rf '%s'", dir);
    cr_expect_eq(system(cleanup), 0);
}

static void every_stop(const RenderPath *p, bool quiet)
{
    for (size_t i = 0; i < sizeof STOPS / sizeof STOPS[0]; i++)
        stop_render(p, &STOPS[i], quiet);
}

Test(stop_matrix, one_device, .timeout = 1800) { every_stop(&ONE_DEVICE, false); }
Test(stop_matrix, one_device_quiet, .timeout = 1800) { every_stop(&ONE_DEVICE, true); }
Test(stop_matrix, work_units, .timeout = 1800) { every_stop(&UNITS, false); }
Test(stop_matrix, work_units_quiet, .timeout = 1800) { every_stop(&UNITS, true); }
/* A time limit that passes before the device threads take their first run (PT_TEST_HOLD_FIRST_RUN
 * holds them until it has: the order a loaded machine's slow thread start gives by chance) still
 * leaves an image holding a run, as the one-device render holds its first pass. It once left none
 * ("stopped ... before the first samples: nothing written"): CI's work_units test failed so. */
Test(stop_matrix, time_limit_before_the_first_run, .timeout = 1800)
{
    char dir[64] = "/tmp/pt-stop-XXXXXX", args[400], exr[200];
    cr_assert(mkdtemp(dir));
    snprintf(exr, sizeof exr, "%s/out.exr", dir);
    snprintf(args, sizeof args, RENDER " --unit-spp 1 --time-limit 0.01 --quiet -o %s", exr);
    Run r = run_pt_env(NULL, "PT_TEST_HOLD_FIRST_RUN=1 " KILL_AFTER, args);
    cr_expect_eq(r.exit_code, 0, "exit %d; stderr:\n%s", r.exit_code, r.err);
    cr_expect(strstr(r.err, "pt: stopped by the time limit: the image holds "), "stderr:\n%s",
              r.err);
    expect_partial_image(exr, "a time limit before the first run", r.err);
    char cleanup[200];
    snprintf(cleanup, sizeof cleanup, "rm -rf '%s'", dir);
    cr_expect_eq(system(cleanup), 0);
}

Test(stop_matrix, checkpointed, .timeout = 1800) { every_stop(&CHECKPOINTED, false); }
Test(stop_matrix, checkpointed_quiet, .timeout = 1800) { every_stop(&CHECKPOINTED, true); }
Test(stop_matrix, two_devices, .timeout = 1800) { every_stop(&TWO_DEVICES, false); }
Test(stop_matrix, two_devices_quiet, .timeout = 1800) { every_stop(&TWO_DEVICES, true); }

/* MPI: rank 0 watches the time and tells the other ranks to stop. A signal under mpirun reaches
 * every rank; rank 0 then refuses to write an image that may lack a dead rank's units (see
 * render_units_ranks.c), so only the time limit is tested here. */
static void mpi_time_limit(bool quiet)
{
    if (system("command -v mpirun >/dev/null 2>&1") != 0)
        cr_skip_test("mpirun not found");
    stop_render(&MPI, &STOPS[0], quiet);
}

Test(stop_matrix, mpi_time_limit, .timeout = 1800) { mpi_time_limit(false); }
Test(stop_matrix, mpi_time_limit_quiet, .timeout = 1800) { mpi_time_limit(true); }

/* A signal from outside, to a quiet checkpointed render: sent once the first checkpoint file
 * exists (the render is under way; nothing on stderr to wait for). */
Test(stop_matrix, sigterm_from_outside_to_a_quiet_checkpointed_render, .timeout = 1800)
{
    char dir[64] = "/tmp/pt-stop-XXXXXX", exr[200], checkpoint[220];
    cr_assert(mkdtemp(dir));
    snprintf(exr, sizeof exr, "%s/out.exr", dir);
    snprintf(checkpoint, sizeof checkpoint, "%s.ptckpt", exr);
    const char *pt = test_pt_bin(); /* in the parent: it may fail the test */
    int watch = inotify_init1(IN_CLOEXEC);
    cr_assert(watch >= 0 && inotify_add_watch(watch, dir, IN_MOVED_TO | IN_CREATE) >= 0);
    pid_t pid = fork();
    cr_assert_neq(pid, -1);
    if (pid == 0) {
        if (!freopen("/dev/null", "w", stdout) || !freopen("/dev/null", "w", stderr))
            _exit(127);
        signal(SIGTERM, SIG_DFL);
        execl(pt, pt, "render", "scenes/cornell-box", "--device", "cpu",
              "--width", "32", "--height", "32", "--spp", "65536", "--unit-spp", "1",
              "--checkpoint", "0.001", "--quiet", "-o", exr, (char *)NULL);
        _exit(127);
    }
    struct stat st;
    int status = 0;
    /* Waits for the checkpoint's rename into place (an inotify event, not a timed poll); poll's
     * second only looks whether pt died first (it cannot: 65536 spp). Bounded by the test's
     * timeout. */
    while (stat(checkpoint, &st) != 0) {
        struct pollfd event = {.fd = watch, .events = POLLIN};
        if (poll(&event, 1, 1000) > 0) {
            char buffer[4096];
            cr_assert(read(watch, buffer, sizeof buffer) > 0);
        }
        cr_assert_eq(waitpid(pid, &status, WNOHANG), 0, "pt ended before its first checkpoint");
    }
    close(watch);
    cr_assert_eq(kill(pid, SIGTERM), 0);
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 143, "status %d", status);
    expect_partial_image(exr, "SIGTERM from outside", "(quiet)");
    char cleanup[200];
    snprintf(cleanup, sizeof cleanup, "rm -rf '%s'", dir);
    cr_expect_eq(system(cleanup), 0);
}
