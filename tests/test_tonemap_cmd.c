// SPDX-License-Identifier: MIT
/* pt tonemap IN.exr -o OUT.png: the PNG is byte for byte the one pt render writes beside its EXR
 * with the same --tonemap, --exposure and --bloom (the same film, the same bloom and curve); other
 * settings give another PNG; bad use is one line. An image given to pt render as SCENE is refused
 * naming pt tonemap. A first-time kernel build is announced before it starts, once per cache. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "support.h"

static int run(const char *dir, const char *args, char *err, size_t size)
{
    char cmd[4096], err_path[1024];
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", dir);
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s 2>'%s' >/dev/null", dir, test_pt_bin(), args, err_path);
    int status = system(cmd);
    char *text = test_read_file(err_path, NULL);
    snprintf(err, size, "%s", text ? text : "");
    free(text);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

static bool same_file(const char *a, const char *b)
{
    size_t na, nb;
    char *x = test_read_file(a, &na), *y = test_read_file(b, &nb);
    bool same = x && y && na == nb && memcmp(x, y, na) == 0;
    free(x), free(y);
    return same;
}

static const char *scene(const char *dir)
{
    test_write_file(dir, "tri.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
    return test_write_file(dir, "s.json",
                           "{\"camera\": {\"eye\": [0, 0, 3], \"target\": [0, 0, 0]},"
                           " \"objects\": [{\"obj\": \"tri.obj\"}], \"background\": [4, 2, 0.5]}");
}

Test(tonemap_cmd, equals_the_png_pt_render_writes, .timeout = 300)
{
    const char *dir = test_temp_dir();
    char err[8192];
    scene(dir);
    const char *display[] = {"", "--tonemap aces --exposure 1.5", "--bloom 0.4,3"};
    for (int k = 0; k < 3; k++) {
        char args[1024], mine[600], theirs[600];
        snprintf(args, sizeof args, "render s.json --spp 2 --width 24 --height 16 --quiet -o r%d.exr --preview %s",
                 k, display[k]);
        cr_assert_eq(run(dir, args, err, sizeof err), 0, "%s", err);
        snprintf(args, sizeof args, "tonemap r%d.exr -o t%d.png %s", k, k, display[k]);
        cr_assert_eq(run(dir, args, err, sizeof err), 0, "%s", err);
        snprintf(mine, sizeof mine, "%s/t%d.png", dir, k);
        snprintf(theirs, sizeof theirs, "%s/r%d.png", dir, k);
        cr_expect(same_file(mine, theirs), "%s: not the PNG pt render wrote", display[k]);
    }
    /* Another curve is another picture (the options are used, not ignored). */
    char a[600], b[600];
    cr_assert_eq(run(dir, "tonemap r0.exr -o other.png --tonemap clamp", err, sizeof err), 0, "%s", err);
    snprintf(a, sizeof a, "%s/other.png", dir);
    snprintf(b, sizeof b, "%s/t0.png", dir);
    cr_expect(!same_file(a, b));
}

Test(tonemap_cmd, bad_use_is_one_line)
{
    const char *dir = test_temp_dir();
    char err[8192];
    test_write_file(dir, "x.exr", "not an exr");
    cr_expect_eq(run(dir, "tonemap x.exr", err, sizeof err), 1);
    cr_expect(strstr(err, "-o OUT.png"), "%s", err);
    cr_expect_eq(run(dir, "tonemap x.exr -o y.exr", err, sizeof err), 1);
    cr_expect(strstr(err, "PNG"), "%s", err);
    cr_expect_eq(run(dir, "tonemap x.exr -o y.png --spp 4", err, sizeof err), 1);
    cr_expect(strstr(err, "--spp"), "%s", err);
    cr_expect_eq(run(dir, "tonemap x.exr -o y.png", err, sizeof err), 1);
    cr_expect(strstr(err, "x.exr"), "names the file: %s", err);
    cr_expect_eq(run(dir, "tonemap missing.exr -o y.png", err, sizeof err), 1);
    cr_expect(strstr(err, "missing.exr"), "%s", err);
}

Test(tonemap_cmd, an_image_as_scene_names_pt_tonemap)
{
    const char *dir = test_temp_dir();
    char err[8192];
    const char *names[] = {"render.exr", "sky.hdr", "photo.PNG", "spider.jpg"};
    for (int k = 0; k < 4; k++) {
        test_write_file(dir, names[k], "{\"objects\": []}"); /* even valid JSON: the name decides */
        char args[256];
        snprintf(args, sizeof args, "render %s --quiet", names[k]);
        cr_expect_eq(run(dir, args, err, sizeof err), 1, "%s", names[k]);
        cr_expect(strstr(err, "that is an image") && strstr(err, "pt tonemap") && strstr(err, names[k]),
                  "%s", err);
    }
}

/* A fresh kernel cache: the first render announces its compile before the summary line; the second
 * takes the cache and says nothing; --quiet never says it. */
Test(tonemap_cmd, first_time_kernel_build_is_announced, .timeout = 600)
{
    const char *dir = test_temp_dir();
    char err[8192], args[1024];
    scene(dir);
    snprintf(args, sizeof args, "render s.json --spp 1 --width 8 --height 8 -o a.exr");
    char env_args[1200];
    snprintf(env_args, sizeof env_args, "%s", args);
    setenv("XDG_CACHE_HOME", dir, 1);
    cr_assert_eq(run(dir, env_args, err, sizeof err), 0, "%s", err);
    const char *notice = strstr(err, "compiling kernels for this scene's features");
    const char *summary = strstr(err, "triangles,");
    cr_expect(notice && summary && notice < summary, "no notice before the build: %s", err);
    cr_expect(strstr(err, "first time only") && strstr(err, dir), "%s", err);
    cr_assert_eq(run(dir, env_args, err, sizeof err), 0, "%s", err);
    cr_expect(!strstr(err, "compiling kernels"), "the cache had it: %s", err);
    snprintf(env_args, sizeof env_args, "%s --no-cache --quiet", args);
    cr_assert_eq(run(dir, env_args, err, sizeof err), 0, "%s", err);
    cr_expect(!strstr(err, "compiling kernels"), "--quiet: %s", err);
    unsetenv("XDG_CACHE_HOME");
}
