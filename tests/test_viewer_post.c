// SPDX-License-Identifier: MIT
/* 'pt view' with --tonemap and --bloom shows what 'pt render' writes with them: the viewer's
 * shader runs io/display_curve.h's text (the PNG writer's curves) and the viewer blooms its film
 * with render/bloom.h before showing it. Same scheme as test_viewer.c: the screenshot at the
 * target spp against 'pt render' at the same seed, measured against the noise between seeds. */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <unistd.h>

#include <stb_image.h>

#include "support.h"
#include "viewer_session.h"

TestSuite(view_post, .init = start_xvfb, .fini = stop_xvfb, .timeout = 180);

static void expect_view_is_render(const char *name, const char *post)
{
    require_display();
    const char *dir = test_temp_dir();
    char root[PATH_MAX], args[PATH_MAX + 256], common[256];
    cr_assert(getcwd(root, sizeof root));
    snprintf(common, sizeof common, "scenes/cornell-box --width 128 --height 96 --spp 8 %s", post);
    snprintf(args, sizeof args, "'%s/scenes/cornell-box' --width 128 --height 96 %s --seed 7 "
             "--screenshot %s.png", root, post, name);
    ViewSession view;
    int exit_code = view_until_converged(&view, dir, 8, args);
    char err[8192];
    slurp(view.err_path, err, sizeof err);
    cr_assert_eq(exit_code, 0, "pt view failed: %s", err);
    expect_screenshot_is_the_render(dir, name, 7, common);
}

Test(view_post, aces_and_exposure_match_pt_render)
{
    expect_view_is_render("aces", "--tonemap aces --exposure 1");
}

Test(view_post, bloom_matches_pt_render)
{
    expect_view_is_render("bloom", "--tonemap clamp --bloom 1,12");
}
