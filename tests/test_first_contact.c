// SPDX-License-Identifier: MIT
/* The first image's silent failures, named or fixed (issue 36): a closed room seen from outside
 * (black: a warning that no light reaches the camera), a file's camera looking away (a warning
 * naming --frame, before the render starts; --frame finds the model), a bare model whose only emitters are tiny labels
 * (Khronos ClearCoatTest's trait: lit by the default rig, not black), a scene of sky alone (it
 * renders the sky), and the beauty's coverage A (1 on geometry, 0 on the sky, the fraction of the
 * samples at an edge). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

#include "exr_inspect.h"
#include "support.h"

typedef struct {
    int exit_code;
    char err[8192];
    char exr[1024];
} Run;

static Run render(const char *dir, const char *scene, const char *flags)
{
    Run r = {0};
    char cmd[4096], err_path[1024];
    snprintf(r.exr, sizeof r.exr, "%s/out.exr", dir);
    snprintf(err_path, sizeof err_path, "%s/stderr.txt", dir);
    snprintf(cmd, sizeof cmd, "'%s' render '%s' --spp 4 --width 16 --height 16 --quiet -o '%s' %s 2>'%s' >/dev/null",
             test_pt_bin(), scene, r.exr, flags, err_path);
    int status = system(cmd);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    char *text = test_read_file(err_path, NULL);
    snprintf(r.err, sizeof r.err, "%s", text ? text : "");
    free(text);
    return r;
}

/* The mean of a channel of the written EXR. */
static double channel_mean(const char *exr, const char *name)
{
    ExrInspect f;
    exr_inspect_open(&f, exr);
    float *v = exr_inspect_channel(&f, name);
    double sum = 0.0;
    size_t n = (size_t)f.width * (size_t)f.height;
    for (size_t i = 0; i < n; i++)
        sum += v[i];
    free(v);
    exr_inspect_close(&f);
    return sum / (double)n;
}

/* A closed box 2 x 2 x 2 (outward quads) with a lamp inside: emitters the camera cannot see. */
static const char *closed_room(const char *dir)
{
    test_write_file(dir, "room.mtl", "newmtl lamp\nKd 0 0 0\nKe 10 10 10\n");
    return test_write_file(dir, "room.obj",
                           "mtllib room.mtl\nv -1 0 -1\nv 1 0 -1\nv 1 2 -1\nv -1 2 -1\nv -1 0 1\nv 1 0 1\n"
                           "v 1 2 1\nv -1 2 1\nf 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\n"
                           "f 2 6 7 3\nusemtl lamp\nv -0.5 1.9 0.5\nv 0.5 1.9 0.5\nv 0.5 1.9 -0.5\n"
                           "v -0.5 1.9 -0.5\nf 9 10 11 12\n");
}

Test(first_contact, closed_room_seen_from_outside_is_named, .timeout = 300)
{
    const char *dir = test_temp_dir();
    Run r = render(dir, closed_room(dir), "");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    cr_expect(channel_mean(r.exr, "G") == 0.0, "the room's outside is lit?");
    cr_expect(strstr(r.err, "no light reaches the camera") && strstr(r.err, "room.obj") &&
                  strstr(r.err, "--camera"), "stderr: %s", r.err);
    cr_expect_gt(channel_mean(r.exr, "A"), 0.2, "the camera sees the room");
}

Test(first_contact, camera_looking_away_is_named_and_frame_finds_the_model, .timeout = 300)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "quad.obj", "v -1 0 -1\nv 1 0 -1\nv 1 1 -1\nv -1 1 -1\nf 1 2 3 4\n");
    const char *scene = test_write_file(dir, "away.json",
                                        "{\"camera\": {\"eye\": [0, 0.5, 3], \"target\": [0, 0.5, 9]},"
                                        " \"objects\": [{\"obj\": \"quad.obj\"}], \"background\": [0.5, 0.5, 0.5]}");
    Run r = render(dir, scene, "--progress");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    const char *warning = strstr(r.err, "the camera sees no geometry"), *progress = strstr(r.err, "pt: progress:");
    cr_expect(warning && strstr(r.err, "--frame"), "stderr: %s", r.err);
    cr_expect(warning && progress && warning < progress, "said before the render: %s", r.err);
    cr_expect(channel_mean(r.exr, "A") == 0.0);
    r = render(dir, scene, "--frame");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    cr_expect(!strstr(r.err, "sees no geometry"), "stderr: %s", r.err);
    cr_expect_gt(channel_mean(r.exr, "A"), 0.2, "--frame: the quad is in view");
}

/* Khronos ClearCoatTest's trait: a model whose only emitters are small labels rendered black
 * (mean 6 of 255); under the default rig it reads. */
Test(first_contact, tiny_emitters_keep_the_default_rig, .timeout = 300)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "label.mtl", "newmtl label\nKd 0 0 0\nKe 2 2 2\n");
    const char *obj = test_write_file(dir, "labelled.obj",
                                      "mtllib label.mtl\nv -1 0 0\nv 1 0 0\nv 1 1 0\nv -1 1 0\nv -1 0 -1\n"
                                      "v -1 1 -1\nf 1 2 3 4\nf 1 4 6 5\nusemtl label\nv -0.1 0.5 0.01\n"
                                      "v 0 0.5 0.01\nv 0 0.55 0.01\nf 7 8 9\n");
    Run r = render(dir, obj, "");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    cr_expect_gt(channel_mean(r.exr, "G"), 0.1, "black under its labels alone");
    cr_expect(strstr(r.err, "too weak to light it"), "stderr: %s", r.err);
    r = render(dir, obj, "--no-default-light");
    cr_expect_lt(channel_mean(r.exr, "G"), 0.02, "--no-default-light: the labels alone");
}

Test(first_contact, sky_alone_renders_the_sky, .timeout = 300)
{
    const char *dir = test_temp_dir();
    Run r = render(dir, test_write_file(dir, "sky.json", "{\"background\": [0.25, 0.5, 0.75]}"), "");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    cr_expect(fabs(channel_mean(r.exr, "R") - 0.25) < 1e-3 && fabs(channel_mean(r.exr, "B") - 0.75) < 1e-3);
    cr_expect(channel_mean(r.exr, "A") == 0.0);
    cr_expect(!strstr(r.err, "warning"), "stderr: %s", r.err);
    r = render(dir, test_write_file(dir, "sky2.json", "{\"background\": [0.25, 0.5, 0.75], \"objects\": []}"), "");
    cr_expect_eq(r.exit_code, 0, "%s", r.err);
    /* Without a sky, no objects is still an error naming the key. */
    r = render(dir, test_write_file(dir, "none.json", "{\"film\": {\"width\": 8}}"), "");
    cr_expect_neq(r.exit_code, 0);
    cr_expect(strstr(r.err, "objects"), "stderr: %s", r.err);
}

/* A quad covering exactly the left half of a 90-degree view: A is 1 on the left half, 0 on the
 * right (the edge falls between two columns). */
Test(first_contact, alpha_is_the_coverage, .timeout = 300)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "half.obj", "v -5 -5 0\nv 0 -5 0\nv 0 5 0\nv -5 5 0\nf 1 2 3 4\n");
    const char *scene = test_write_file(dir, "half.json",
                                        "{\"camera\": {\"eye\": [0, 0, 1], \"target\": [0, 0, 0], \"fov_y\": 90},"
                                        " \"objects\": [{\"obj\": \"half.obj\"}], \"background\": [1, 1, 1]}");
    Run r = render(dir, scene, "--spp 16");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    ExrInspect f;
    exr_inspect_open(&f, r.exr);
    float *a = exr_inspect_channel(&f, "A");
    for (int y = 0; y < f.height; y++)
        for (int x = 0; x < f.width; x++) {
            float expected = x < f.width / 2 ? 1.0f : 0.0f;
            cr_expect(a[y * f.width + x] == expected, "A(%d, %d) = %g, not %g", x, y, a[y * f.width + x], expected);
        }
    free(a);
    exr_inspect_close(&f);
}
