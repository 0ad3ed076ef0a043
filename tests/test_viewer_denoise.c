// SPDX-License-Identifier: MIT
/* 'pt view' with the denoised view (Ctrl+D, issue 35): the key turns it on, the film is denoised
 * on a thread of its own once it has samples (and again when it stops gaining them), the title says
 * "denoised", and what the window shows is the denoised image: the screenshot at 8 spp is far
 * closer to 'pt render --denoise' at the same seed than to the noisy render. Needs OIDN as
 * tools/install-oidn.sh installs it. */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <stb_image.h>

#include "support.h"
#include "viewer_session.h"

TestSuite(view_denoise, .init = start_xvfb, .fini = stop_xvfb, .timeout = 300);

Test(view_denoise, ctrl_d_shows_the_denoised_film)
{
    require_display();
    const char *dir = test_temp_dir();
    char root[PATH_MAX];
    cr_assert(getcwd(root, sizeof root));
    const char *common = "--width 96 --height 96 --spp 8 --seed 7 --denoise-device cpu";
    ViewSession s;
    session_start(&s, dir, "view '%s/scenes/cornell-box' %s --events --screenshot shot.png", root,
                  common);
    size_t at = session_wait(&s, 0, "event: ready");
    session_find_window(&s);
    at = session_send(&s, at, "key ctrl+d", "denoised view on");
    at = session_wait(&s, at, "event: denoised 8 spp");
    at = session_wait(&s, at, "event: title denoised (8 spp)");
    cr_assert_eq(session_quit(&s), 0);

    Run r = run_pt("render scenes/cornell-box %s -q -o %s/denoised.png --denoise", common, dir);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    r = run_pt("render scenes/cornell-box %s -q -o %s/noisy.png", common, dir);
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    Png shot = load_png(dir, "shot.png"), denoised = load_png(dir, "denoised.png"),
        noisy = load_png(dir, "noisy.png");
    double to_denoised = mean_squared_difference(shot, denoised);
    double to_noisy = mean_squared_difference(shot, noisy);
    cr_log_info("screenshot vs pt render --denoise: %.3g, vs the noisy render: %.3g\n",
                to_denoised, to_noisy);
    /* The viewer's guides (4 spp) and OIDN's balanced quality differ a little from pt render's
     * (8 spp, high quality); the noise they remove is far larger. */
    cr_expect(to_denoised < 0.25 * to_noisy, "screenshot vs denoised %.3g, vs noisy %.3g",
              to_denoised, to_noisy);
    stbi_image_free(shot.rgb), stbi_image_free(denoised.rgb), stbi_image_free(noisy.rgb);
}
