// SPDX-License-Identifier: MIT
/* Numbered outputs never overwrite (issue 42): two `pt render` of one scene without -o, both
 * rendering at once, write two images (out/cornell-box.* and out/cornell-box-2.*). They used to
 * pick their name by looking at the folder at the start and both write out/cornell-box.exr; now
 * each claims its name with O_EXCL before rendering. No timing: the second pt starts once the
 * first has rendered a window (its first progress line: its name is chosen by then), and both are
 * stopped by SIGINT once the second has rendered one too, so both renders overlap every time. */
#define _XOPEN_SOURCE 700 /* realpath, mkdtemp */
#include <criterion/criterion.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "support.h"

typedef struct {
    pid_t pid;
    FILE *err;
    char out_path[300];
} Child;

/* pt render SCENE --progress (no -o) in folder dir, stdout into dir/stdout-<tag>. */
static void start(Child *c, const char *dir, const char *scene, char tag)
{
    snprintf(c->out_path, sizeof c->out_path, "%s/stdout-%c", dir, tag);
    const char *pt = test_pt_bin(); /* before chdir: PT_BIN may be relative */
    int fds[2];
    cr_assert_eq(pipe(fds), 0);
    c->pid = fork();
    cr_assert_neq(c->pid, -1);
    if (c->pid == 0) {
        dup2(fds[1], STDERR_FILENO);
        close(fds[0]), close(fds[1]);
        if (chdir(dir) != 0 || !freopen(c->out_path, "w", stdout))
            _exit(127);
        signal(SIGINT, SIG_DFL);
        execl(pt, pt, "render", scene, "--device", "cpu", "--width", "32",
              "--height", "32", "--spp", "100000000", "--progress", (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    c->err = fdopen(fds[0], "r");
    cr_assert(c->err);
}

static void wait_for_progress(Child *c)
{
    char line[1024];
    while (fgets(line, sizeof line, c->err))
        if (!strncmp(line, "pt: progress: ", 14))
            return;
    cr_assert_fail("pt ended before its first progress line");
}

/* Stops it with SIGINT; returns what it printed on stdout. */
static char *stop(Child *c)
{
    cr_assert_eq(kill(c->pid, SIGINT), 0);
    char line[1024];
    while (fgets(line, sizeof line, c->err))
        ;
    fclose(c->err);
    int status;
    cr_assert_eq(waitpid(c->pid, &status, 0), c->pid);
    cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 130, "status %d", status);
    char *out = test_read_file(c->out_path, NULL);
    cr_assert(out);
    return out;
}

Test(output_names, two_renders_at_once_without_o_write_two_images, .timeout = 900)
{
    char scene[PATH_MAX];
    cr_assert(realpath("scenes/cornell-box", scene));
    const char *dir = test_temp_dir();
    Child a, b;
    start(&a, dir, scene, 'a');
    wait_for_progress(&a);
    start(&b, dir, scene, 'b');
    wait_for_progress(&b);
    char *out_a = stop(&a), *out_b = stop(&b);
    cr_expect(strstr(out_a, "wrote out/cornell-box.exr\n") && strstr(out_a, "wrote out/cornell-box.png\n"),
              "the first: %s", out_a);
    cr_expect(strstr(out_b, "wrote out/cornell-box-2.exr\n") &&
                  strstr(out_b, "wrote out/cornell-box-2.png\n"),
              "the second: %s", out_b);
    const char *files[] = {"cornell-box.exr", "cornell-box.png", "cornell-box-2.exr",
                           "cornell-box-2.png"};
    for (int i = 0; i < 4; i++) {
        char path[400];
        snprintf(path, sizeof path, "%s/out/%s", dir, files[i]);
        size_t size = 0;
        char *data = test_read_file(path, &size);
        cr_expect(data && size > 0, "%s missing or empty", files[i]);
        free(data);
    }
    free(out_a), free(out_b);
}

/* A claimed name that is never written (pt fails after planning its outputs: adaptive sampling
 * on the unit path is refused there) is not left behind as an empty file. */
Test(output_names, a_render_that_fails_leaves_no_empty_claim, .timeout = 300)
{
    char scene[PATH_MAX];
    cr_assert(realpath("scenes/cornell-box", scene));
    const char *dir = test_temp_dir();
    char cmd[PATH_MAX + 600];
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' render '%s' --width 8 --height 8 --spp 4 "
             "--unit-spp 1 --noise-threshold 0.1 --device cpu --quiet >/dev/null 2>&1", dir,
             test_pt_bin(), scene);
    int status = system(cmd);
    cr_expect(WIFEXITED(status) && WEXITSTATUS(status) == 1, "status %d", status);
    char path[400];
    snprintf(path, sizeof path, "%s/out/cornell-box.exr", dir);
    cr_expect_neq(access(path, F_OK), 0, "out/cornell-box.exr was left");
    snprintf(path, sizeof path, "%s/out/cornell-box.png", dir);
    cr_expect_neq(access(path, F_OK), 0, "out/cornell-box.png was left");
}
