// SPDX-License-Identifier: MIT
/* pt render under mpirun (OpenMPI on localhost, several ranks on PoCL): the image's pixels are
 * the same bits as one process's whatever the number of ranks and the unit size; ranks that
 * disagree about the render refuse it; a rank killed mid-run (PT_TEST_KILL_RANK, raised by the
 * rank itself after its units, never after a sleep) fails the job with a message naming it and
 * leaves no output. mpirun runs as a child with the settings a container needs: as root
 * (--allow-run-as-root), more ranks than cores (--oversubscribe), shared memory between ranks
 * without ptrace (btl self,vader without single-copy). */
#define _XOPEN_SOURCE 700 /* mkdtemp */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "exr_inspect.h"
#include "support.h"

#define MPIRUN                                                                                     \
    "OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none "                      \
    "OMPI_MCA_rmaps_base_oversubscribe=1 timeout 900 mpirun --allow-run-as-root --oversubscribe"
/* Small, with several tiles (--unit-rows 4: 8 of them) so that every rank finds work. */
#define SCENE "render scenes/cornell-box --width 48 --height 32 --spp 64 --unit-rows 4"

typedef struct {
    int exit_code;
    char err[32768];
} MpiRun;

/* Runs `env mpirun -n ranks pt args` (or, ranks 0, pt alone); stderr into r->err. */
static void run(MpiRun *r, const char *env, int ranks, const char *args)
{
    memset(r, 0, sizeof *r);
    char err_path[64], cmd[4096];
    snprintf(err_path, sizeof err_path, "/tmp/pt-mpi-err-%d", (int)getpid());
    /* OpenMPI's session folder of its own for each mpirun: Criterion runs this file's tests side
     * by side, and two mpiruns that create the shared /tmp/ompi.<host>.<uid> at once can fail
     * with "File exists" (seen once in CI). */
    char session[64] = "/tmp/pt-ompi-XXXXXX";
    cr_assert(ranks == 0 || mkdtemp(session), "mkdtemp for OpenMPI's session folder");
    char launcher[400] = "";
    if (ranks > 0)
        snprintf(launcher, sizeof launcher, "OMPI_MCA_orte_tmpdir_base=%s %s -n %d", session,
                 MPIRUN, ranks);
    snprintf(cmd, sizeof cmd, "env %s %s '%s' %s >/dev/null 2>%s", env ? env : "", launcher,
             test_pt_bin(), args, err_path);
    int status = system(cmd);
    if (ranks > 0) {
        char rm[128];
        snprintf(rm, sizeof rm, "rm -rf '%s'", session);
        cr_expect_eq(system(rm), 0, "removing %s", session);
    }
    r->exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    char *text = test_read_file(err_path, NULL);
    snprintf(r->err, sizeof r->err, "%s", text ? text : "");
    free(text);
    unlink(err_path);
}

static char g_dir[64];

static const char *path_in_dir(const char *name)
{
    static char paths[4][200];
    static int next;
    char *p = paths[next++ % 4];
    snprintf(p, sizeof paths[0], "%s/%s", g_dir, name);
    return p;
}

static void make_dir(void)
{
    snprintf(g_dir, sizeof g_dir, "/tmp/pt-mpi-XXXXXX");
    cr_assert(mkdtemp(g_dir));
}

/* Renders SCENE with the options extra into name in the test's folder, with mpirun -n ranks
 * (0: alone) and the environment env; returns the output's path. */
static const char *run_scene(MpiRun *r, const char *env, int ranks, const char *extra,
                             const char *name)
{
    const char *out = path_in_dir(name);
    char args[1024];
    snprintf(args, sizeof args, "%s %s -o %s", SCENE, extra, out);
    run(r, env, ranks, args);
    return out;
}

/* The same, where the render must succeed. */
static const char *render(int ranks, const char *extra, const char *name)
{
    MpiRun r;
    const char *out = run_scene(&r, NULL, ranks, extra, name);
    cr_assert_eq(r.exit_code, 0, "%d ranks, %s: exit %d; stderr:\n%s", ranks, extra, r.exit_code,
                 r.err);
    return out;
}

/* Every value of every channel of b is the same bits as a's. */
static void expect_same_pixels(const char *a, const char *b)
{
    ExrInspect fa, fb;
    exr_inspect_open(&fa, a);
    exr_inspect_open(&fb, b);
    cr_assert_eq(fa.width, fb.width);
    cr_assert_eq(fa.height, fb.height);
    cr_assert_eq(fa.channel_count, fb.channel_count);
    size_t n = (size_t)fa.width * (size_t)fa.height;
    for (int c = 0; c < fa.channel_count; c++) {
        float *va = exr_inspect_channel(&fa, fa.names[c]);
        float *vb = exr_inspect_channel(&fb, fa.names[c]);
        size_t differ = 0;
        double total = 0.0;
        for (size_t i = 0; i < n; i++) {
            differ += memcmp(&va[i], &vb[i], sizeof *va) != 0;
            total += va[i];
        }
        cr_expect_eq(differ, 0, "%s vs %s: channel %s differs in %zu of %zu pixels", a, b,
                     fa.names[c], differ, n);
        cr_expect_gt(total, 0.0, "channel %s is black", fa.names[c]);
        free(va), free(vb);
    }
    exr_inspect_close(&fa);
    exr_inspect_close(&fb);
}

static bool dir_is_empty(void)
{
    DIR *d = opendir(g_dir);
    cr_assert(d);
    struct dirent *e;
    int entries = 0;
    while ((e = readdir(d)))
        entries += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    closedir(d);
    return entries == 0;
}

TestSuite(mpi, .timeout = 3000);

Test(mpi, three_ranks_render_the_bits_of_one_process)
{
    make_dir();
    const char *alone = render(0, "--device cpu", "alone.exr");
    MpiRun r;
    const char *three = run_scene(&r, NULL, 3, "", "three.exr");
    cr_assert_eq(r.exit_code, 0, "stderr:\n%s", r.err);
    /* Rank 0 reports the other ranks' devices and the films it merged. */
    cr_expect(strstr(r.err, "pt: rank 1 device ") && strstr(r.err, "pt: rank 2 device "), "%s",
              r.err);
    cr_expect(strstr(r.err, "films of 2 other ranks at rank 0: 2 messages"), "%s", r.err);
    expect_same_pixels(alone, three);
}

Test(mpi, one_rank_is_one_process)
{
    make_dir();
    expect_same_pixels(render(0, "--device cpu", "alone.exr"), render(1, "", "one.exr"));
}

Test(mpi, unit_sizes_1_7_64_give_the_same_bits)
{
    make_dir();
    const char *alone = render(0, "--device cpu", "alone.exr");
    expect_same_pixels(alone, render(3, "--unit-spp 1", "u1.exr"));
    expect_same_pixels(alone, render(3, "--unit-spp 7", "u7.exr"));
    expect_same_pixels(alone, render(2, "--unit-spp 64", "u64.exr"));
}

/* Each rank's device threads ask rank 0 through their own slot of the relay. */
Test(mpi, two_ranks_of_two_devices_each_render_the_bits_of_one_process)
{
    make_dir();
    const char *alone = render(0, "--device cpu", "alone.exr");
    MpiRun r;
    const char *four = run_scene(&r, "POCL_DEVICES='pthread pthread'", 2,
                                 "--device all", "four.exr");
    cr_assert_eq(r.exit_code, 0, "stderr:\n%s", r.err);
    cr_expect(strstr(r.err, "pt: rank 1 device 0:1 "), "%s", r.err);
    expect_same_pixels(alone, four);
}

Test(mpi, a_rank_killed_mid_run_fails_the_job_without_output)
{
    make_dir();
    MpiRun r;
    run_scene(&r, "PT_TEST_KILL_RANK=1@1", 3, "", "out.exr");
    cr_expect_neq(r.exit_code, 0, "stderr:\n%s", r.err);
    cr_expect(strstr(r.err, "pt: rank 1: PT_TEST_KILL_RANK: SIGKILL"), "%s", r.err);
    /* mpirun's own message names the rank (pt's rank 0 adds one when it gets mpirun's SIGTERM
     * in time, which no test can count on). */
    cr_expect(strstr(r.err, "process rank 1 "), "no message naming rank 1:\n%s", r.err);
    cr_expect(dir_is_empty(), "an output (or a temporary file) was left in %s:\n%s", g_dir, r.err);
}

Test(mpi, ranks_that_render_different_images_refuse)
{
    make_dir();
    char args[1024];
    const char *out = path_in_dir("out.exr");
    snprintf(args, sizeof args, "%s -o %s : -n 1 '%s' %s --spp 32 -o %s", SCENE, out,
             test_pt_bin(), SCENE, out);
    MpiRun r;
    run(&r, NULL, 2, args);
    cr_expect_eq(r.exit_code, 1, "stderr:\n%s", r.err);
    cr_expect(strstr(r.err, "pt: rank 2 renders another image than rank 0 (32 spp, not 64)"), "%s",
              r.err);
    cr_expect(dir_is_empty(), "an output was left in %s", g_dir);
}

Test(mpi, a_malformed_kill_test_setting_is_refused)
{
    make_dir();
    MpiRun r;
    run_scene(&r, "PT_TEST_KILL_RANK=one", 2, "-q", "out.exr");
    cr_expect_neq(r.exit_code, 0);
    cr_expect(strstr(r.err, "pt: PT_TEST_KILL_RANK=one: expected RANK@UNITS"), "%s", r.err);
}

/* --denoise under MPI: rank 0 alone denoises, once, the merged film (one "denoised with" line
 * among every rank's stderr), and the result is one process's denoised image bit for bit (the
 * same film and guides; OIDN's CPU device is deterministic). */
Test(mpi, two_ranks_denoise_the_merged_film_once_on_rank_0)
{
    make_dir();
    const char *alone = render(0, "--device cpu --denoise --denoise-device cpu", "alone.exr");
    MpiRun r;
    const char *two = run_scene(&r, NULL, 2, "--denoise --denoise-device cpu", "two.exr");
    cr_assert_eq(r.exit_code, 0, "stderr:\n%s", r.err);
    const char *first = strstr(r.err, "pt: denoised with");
    cr_expect(first && !strstr(first + 1, "pt: denoised with"), "not one denoising:\n%s", r.err);
    expect_same_pixels(alone, two);
}
