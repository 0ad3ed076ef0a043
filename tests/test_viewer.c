// SPDX-License-Identifier: MIT
/* 'pt view' end to end: the real binary in a real window on a private Xvfb server (Mesa's
 * llvmpipe), driven by xdotool, each input sent once the viewer has acknowledged the last
 * (--events; helpers in viewer_session.c). Screenshots are compared with 'pt render' of the same
 * scene, pose, size, spp and seed: equal up to 8-bit rounding, measured against the difference
 * between two seeds (the noise). The film itself is compared bit for bit in test_viewer_film.c.
 * Xvfb and xdotool are required, not optional: 'make test' installs them
 * (tools/install-deps.sh), so their absence fails the tests. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <stb_image.h>

#include "io/image_io.h"
#include "support.h"
#include "viewer_session.h"

TestSuite(view, .init = start_xvfb, .fini = stop_xvfb, .timeout = 120);

/* ---- Tests ---------------------------------------------------------------------------------- */
/* ---- Tests ---------------------------------------------------------------------------------- */

Test(view_headless, no_display_points_to_pt_render)
{
    Run r = run_pt("view scenes/cornell-box"); /* this suite starts no X server */
    cr_expect_eq(r.exit_code, 1, "exit %d, stderr: %s", r.exit_code, r.err);
    cr_expect(strncmp(r.err, "pt: ", 4) == 0 && one_line(r.err), "one line: %s", r.err);
    cr_expect(strstr(r.err, "display") && strstr(r.err, "pt render"), "says why and what to use: %s",
              r.err);
}

/* The window at the target spp shows what 'pt render' writes (exposure and sRGB in the shader). */
Test(view, screenshot_matches_pt_render_at_the_same_spp_and_seed)
{
    require_display();
    const char *dir = test_temp_dir();
    char root[PATH_MAX], args[PATH_MAX + 128];
    cr_assert(getcwd(root, sizeof root));
    const char *common = "scenes/cornell-box --width 128 --height 96 --spp 8 --exposure 0.5";
    snprintf(args, sizeof args, "'%s/scenes/cornell-box' --width 128 --height 96 --exposure 0.5 "
             "--seed 7 --screenshot view.png", root);
    ViewSession view;
    int exit_code = view_until_converged(&view, dir, 8, args);
    char err[8192];
    slurp(view.err_path, err, sizeof err);
    cr_assert_eq(exit_code, 0, "pt view failed: %s", err);
    cr_assert_eq(parse_summary(err).spp, 8, "the viewer stops at the target spp: %s", err);
    Png shot = load_png(dir, "view.png");
    cr_expect(shot.width == 128 && shot.height == 96, "screenshot %dx%d", shot.width, shot.height);
    stbi_image_free(shot.rgb);
    expect_screenshot_is_the_render(dir, "view", 7, common);
}

/* --camera: the view is 'pt render' of a scene whose camera is that pose, and not the scene's own
 * view. The pose looks from the middle of the box at the left wall, which fills the view red. */
Test(view, camera_option_gives_the_render_of_that_pose)
{
    require_display();
    const char *dir = test_temp_dir();
    char root[PATH_MAX], scene[PATH_MAX];
    cr_assert(getcwd(root, sizeof root));
    const char *pose = "\"eye\": [0, 1, 0.5], \"target\": [-1, 1, 0.3], \"up\": [0, 1, 0], "
                       "\"fov_y\": 39.3";
    snprintf(scene, sizeof scene, "%s/posed.json", dir);
    FILE *f = fopen(scene, "w");
    cr_assert(f, "cannot write %s", scene);
    fprintf(f, "{\"camera\": {%s}, \"objects\": [{\"obj\": \"%s/scenes/cornell-box/"
               "CornellBox-Original.obj\"}]}\n", pose, root);
    fclose(f);

    const char *size = "--width 64 --height 64 --spp 4";
    char args[PATH_MAX + 512];
    snprintf(args, sizeof args, "'%s/scenes/cornell-box' --width 64 --height 64 -q --camera '{%s}' "
             "--screenshot posed.png", root, pose);
    ViewSession view;
    int exit_code = view_until_converged(&view, dir, 4, args);
    char err[8192];
    slurp(view.err_path, err, sizeof err);
    cr_assert_eq(exit_code, 0, "pt view --camera: %s", err);
    char render_args[PATH_MAX + 64];
    snprintf(render_args, sizeof render_args, "%s %s", scene, size);
    double noise = expect_screenshot_is_the_render(dir, "posed", 0, render_args);

    Png posed = load_png(dir, "posed.png");
    double mean[3];
    channel_means(posed, mean);
    cr_expect(mean[0] > 2.0 * mean[1] && mean[0] > 2.0 * mean[2], "the left wall is red: %g %g %g",
              mean[0], mean[1], mean[2]);
    Run r = run_pt("render scenes/cornell-box %s -q -o %s/scene-pose.png", size, dir);
    cr_assert_eq(r.exit_code, 0, "pt render: %s", r.err);
    Png scene_pose = load_png(dir, "scene-pose.png");
    double moved = mean_squared_difference(posed, scene_pose);
    cr_log_info("posed vs the scene's pose: %.3g", moved);
    cr_expect(moved > 10.0 * noise, "the pose changed the view: %g vs noise %g", moved, noise);
    stbi_image_free(posed.rgb), stbi_image_free(scene_pose.rgb);

    Run bad = run_pt("view scenes/cornell-box --quiet --frames 1 --camera '{\"eye\": [0, 1]}'");
    cr_expect_eq(bad.exit_code, 1, "bad --camera: exit %d", bad.exit_code);
    cr_expect(strstr(bad.err, "camera.eye") && one_line(bad.err), "one line naming the key: %s", bad.err);
}

/* --frames N runs exactly N frames on PoCL and the exit summary reports the frame times it
 * measured (the pacing itself is tested without a clock in test_viewer_pacing.c; frame times are
 * measurements for the notes, not thresholds for a test). How many spp 40 frames reach depends on
 * the machine's speed and load (a busy machine measured 0 at 256x256), so it is not asserted. */
Test(view, frames_run_and_frame_times_are_reported_on_pocl)
{
    require_display();
    Run r = run_pt("view scenes/cornell-box --device cpu --width 256 --height 256 --frames 40");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    Summary s = parse_summary(r.err);
    cr_expect(s.frames == 40 && s.spp >= 0, "%d frames, %d spp", s.frames, s.spp);
    cr_expect(s.median_ms > 0.0 && s.p95_ms >= s.median_ms, "median %g ms, p95 %g ms", s.median_ms,
              s.p95_ms);
}

/* --frames 1 --screenshot on a film larger than one frame's samples (the first guess on a CPU is
 * 2^14 paths a frame; 256 x 256 is 4 times that): the viewer goes on until every pixel has a whole
 * sample, so the saved film has 1 spp or more and no band still black (issue 36: a bottom third). */
Test(view, frames_with_a_screenshot_wait_for_a_whole_sample)
{
    require_display();
    const char *dir = test_temp_dir();
    char shot[600];
    snprintf(shot, sizeof shot, "%s/shot.exr", dir);
    Run r = run_pt("view scenes/cornell-box --device cpu --width 256 --height 256 --frames 1 "
                   "--screenshot '%s'", shot);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    int spp = -1;
    const char *wrote = strstr(r.out, "wrote ");
    cr_assert(wrote && sscanf(strstr(wrote, "(") ? strstr(wrote, "(") : "", "(%d spp)", &spp) == 1, "%s", r.out);
    cr_expect_geq(spp, 1, "saved with %d spp: %s", spp, r.out);
    float *rgb;
    int w, h;
    Error err = {0};
    cr_assert(image_read_exr(shot, &rgb, &w, &h, &err), "%s", err.message);
    double bottom = 0.0;
    for (int y = h - h / 4; y < h; y++)
        for (int x = 0; x < w * 3; x++)
            bottom += rgb[(size_t)y * w * 3 + x];
    free(rgb);
    cr_expect_gt(bottom, 0.0, "the bottom quarter is black");
}
