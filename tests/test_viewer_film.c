// SPDX-License-Identifier: MIT
/* 'pt view' end to end, the film: a scripted session (resize, drag, saves) renders what 'pt render'
 * renders for the pose and size it ends at, and the film (--screenshot FILE.exr, Ctrl+S) is
 * 'pt render' bit for bit. Same Xvfb and xdotool setup as test_viewer.c (viewer_session.c). */
#define _XOPEN_SOURCE 700 /* realpath */
#include <criterion/criterion.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <stb_image.h>

#include "support.h"
#include "io/image_io.h"
#include "viewer/camera_controls.h"
#include "viewer_session.h"

TestSuite(view, .init = start_xvfb, .fini = stop_xvfb, .timeout = 120);

/* A user session scripted with xdotool: shrink the window, print the camera, orbit by a drag,
 * wait for the target spp, print the camera again, save twice, quit. Each event is sent once the
 * viewer has said it read the one before (--events). The film follows the framebuffer: the
 * screenshot is 'pt render' of the orbited pose at the new size, and nothing moves between the
 * two saves (xdotool lets Ctrl go before S: a frame between the two used to fly backwards). */
Test(view, keys_drag_and_resize_in_a_real_window)
{
    require_display();
    const char *dir = test_temp_dir();
    char root[PATH_MAX];
    cr_assert(getcwd(root, sizeof root));
    ViewSession s;
    session_start(&s, dir, "view '%s/scenes/cornell-box' --width 200 --height 150 --spp 4 "
                  "--events --screenshot shot.png", root);
    size_t at = session_wait(&s, 0, "event: ready 200x150");
    session_find_window(&s);
    at = session_send(&s, at, "windowsize --sync %W 160 120", "event: film 160x120");
    at = session_send(&s, at, "key c", "\"camera\"");
    at = session_send(&s, at, "mousemove --window %W 80 60", "event: cursor 80 60");
    at = session_send(&s, at, "mousedown 1", "event: button 0 press");
    size_t orbited = at = session_send(&s, at, "mousemove_relative 40 0", "event: cursor 120 60");
    at = session_send(&s, at, "mouseup 1", "event: button 0 release");
    /* converged after the orbit: perhaps already before the release */
    at = session_wait(&s, orbited, "event: converged 4 spp");
    at = session_send(&s, at, "key c", "\"camera\"");
    at = session_send(&s, at, "key ctrl+s", "wrote out/cornell-box-view-1.png");
    at = session_send(&s, at, "key ctrl+s", "wrote out/cornell-box-view-2.png");
    int exit_code = session_quit(&s);
    char err[8192], path[PATH_MAX];
    slurp(s.err_path, err, sizeof err);
    cr_assert_eq(exit_code, 0, "pt view exit status %d, stderr: %s", exit_code, err);
    char *out = s.out;

    /* C before the drag prints the scene's pose; after a drag right the eye has orbited left. */
    char *first = strstr(out, "\"camera\""), *second = first ? strstr(first + 1, "\"camera\"") : NULL;
    cr_assert(first && second, "two cameras printed: %s", out);
    *strchr(first, '\n') = '\0', *strchr(second, '\n') = '\0';
    CameraDesc before = {0}, after = {0};
    Error e = {0};
    cr_assert(viewer_camera_parse(first, &before, &e) && viewer_camera_parse(second, &after, &e),
              "%s", e.message);
    cr_expect(before.eye[0] == 0.0f && before.eye[2] == 3.9f, "scene pose: %s", first);
    float orbit_radius = hypotf(after.eye[0], after.eye[2]);
    cr_expect(after.eye[0] < -0.3f && fabsf(orbit_radius - 3.9f) < 1e-3f, "orbited: %s", second);

    /* The resized, re-allocated film renders the orbited pose: 'pt render' of a scene with the
     * printed camera (exact: C prints floats that read back as the same floats). */
    snprintf(path, sizeof path, "%s/orbited.json", dir);
    FILE *f = fopen(path, "w");
    cr_assert(f, "cannot write %s", path);
    fprintf(f, "{%s, \"objects\": [{\"obj\": \"%s/scenes/cornell-box/CornellBox-Original.obj\"}]}\n",
            second, root);
    fclose(f);
    char render_args[PATH_MAX + 64];
    snprintf(render_args, sizeof render_args, "%s --width 160 --height 120 --spp 4", path);
    expect_screenshot_is_the_render(dir, "shot", 0, render_args);

    /* Ctrl+S twice: two numbered pairs, nothing overwritten, at the resized film's size. */
    for (int n = 1; n <= 2; n++) {
        snprintf(path, sizeof path, "%s/out/cornell-box-view-%d.exr", dir, n);
        cr_expect(access(path, F_OK) == 0, "%s missing; stdout: %s", path, out);
        snprintf(path, sizeof path, "out/cornell-box-view-%d.png", n);
        Png saved = load_png(dir, path);
        cr_expect(saved.width == 160 && saved.height == 120, "%s is %dx%d", path, saved.width,
                  saved.height);
        stbi_image_free(saved.rgb);
    }
    float *film[2];
    int width[2], height[2];
    for (int n = 0; n < 2; n++) {
        Error read_err = {0};
        snprintf(path, sizeof path, "%s/out/cornell-box-view-%d.exr", dir, n + 1);
        cr_assert(image_read_exr(path, &film[n], &width[n], &height[n], &read_err), "%s",
                  read_err.message);
    }
    cr_assert(width[0] == width[1] && height[0] == height[1]);
    size_t film_bytes = (size_t)width[0] * (size_t)height[0] * 3 * sizeof(float);
    cr_expect(memcmp(film[0], film[1], film_bytes) == 0, "the film changed between the two saves; stdout: %s", out);
    free(film[0]), free(film[1]);
}

/* The film at N spp is 'pt render' at N spp bit for bit (--screenshot FILE.exr writes the film),
 * with the settings options given to both (extra). 64x64 at 8 spp: each of the viewer's windows
 * (and pt render's single one) holds several samples per pixel, so only an exact,
 * order-independent film makes the two agree. */
static void expect_view_film_is_render(const char *extra)
{
    require_display();
    const char *dir = test_temp_dir();
    char root[PATH_MAX];
    cr_assert(getcwd(root, sizeof root));
    char size[256];
    snprintf(size, sizeof size, "--width 64 --height 64 --seed 3 %s", extra);
    char args[PATH_MAX + 512];
    snprintf(args, sizeof args, "'%s/scenes/cornell-box' %s --screenshot view.exr", root, size);
    ViewSession s;
    int exit_code = view_until_converged(&s, dir, 8, args);
    char err[8192];
    slurp(s.err_path, err, sizeof err);
    cr_assert_eq(exit_code, 0, "pt view %s: %s", extra, err);
    cr_assert(strstr(s.out, "wrote view.exr (8 spp)"), "stdout: %s", s.out);
    Run r = run_pt("render scenes/cornell-box %s --spp 8 -q -o %s/render.exr", size, dir);
    cr_assert_eq(r.exit_code, 0, "pt render %s: %s", extra, r.err);

    float *view, *render;
    int view_width, view_height, render_width, render_height;
    Error e = {0};
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/view.exr", dir);
    cr_assert(image_read_exr(path, &view, &view_width, &view_height, &e), "%s", e.message);
    snprintf(path, sizeof path, "%s/render.exr", dir);
    cr_assert(image_read_exr(path, &render, &render_width, &render_height, &e), "%s", e.message);
    cr_assert(view_width == 64 && view_height == 64 && render_width == 64 &&
              render_height == 64,
              "view %dx%d, render %dx%d", view_width, view_height, render_width, render_height);
    size_t n = (size_t)64 * 64 * 3, differ = 0, first = n;
    for (size_t i = 0; i < n; i++)
        if (memcmp(&view[i], &render[i], sizeof(float)) != 0)
            differ++, first = first < n ? first : i;
    cr_expect_eq(differ, 0, "%s: %zu of %zu values differ; the first, pixel %zu channel %zu: %.9g "
                 "in the viewer, %.9g in pt render", extra, differ, n, first / 3, first % 3,
                 first < n ? view[first] : 0.0f, first < n ? render[first] : 0.0f);
    free(view), free(render);
}

Test(view, film_at_n_spp_is_pt_render_bit_for_bit) { expect_view_film_is_render(""); }

/* --clamp and adaptive sampling reach the viewer's settings (pt view used to accept them and
 * render without them): its film is pt render's with the same options. */
Test(view, clamp_and_adaptive_sampling_apply_in_the_viewer)
{
    expect_view_film_is_render("--clamp 0.25");
    expect_view_film_is_render("--noise-threshold 0.3 --min-spp 2");
}

/* Reads dir/name (an EXR film) into *rgb; its size must be width x height. */
static float *read_film(const char *dir, const char *name, int width, int height)
{
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    float *rgb;
    int w, h;
    Error e = {0};
    cr_assert(image_read_exr(path, &rgb, &w, &h, &e), "%s", e.message);
    cr_assert(w == width && h == height, "%s is %dx%d", name, w, h);
    return rgb;
}

/* '.' and ',' turn the environment map by +15 and -15 degrees (the scene's environment.rotation):
 * seven '.' and one ',' end at 90, and the film after them is 'pt render' of the scene with
 * rotation 90 bit for bit (and not the scene's own rotation 0). */
Test(view, environment_rotation_keys_give_the_render_of_that_rotation)
{
    require_display();
    const char *dir = test_temp_dir();
    char root[PATH_MAX];
    cr_assert(getcwd(root, sizeof root));
    const char *size = "--width 48 --height 32 --spp 4 --seed 3";
    ViewSession s;
    session_start(&s, dir, "view '%s/scenes/venice/sphere.json' %s --events --screenshot view.exr",
                  root, size);
    size_t at = session_wait(&s, 0, "event: ready 48x32");
    session_find_window(&s);
    char expected[64];
    for (int step = 1; step <= 7; step++) {
        snprintf(expected, sizeof expected, "event: environment rotation %d", 15 * step);
        at = session_send(&s, at, "key period", expected);
    }
    at = session_send(&s, at, "key comma", "event: environment rotation 90");
    at = session_wait(&s, at, "event: converged 4 spp");
    int exit_code = session_quit(&s);
    char err[8192];
    slurp(s.err_path, err, sizeof err);
    cr_assert_eq(exit_code, 0, "pt view: %s", err);

    char scene[PATH_MAX];
    snprintf(scene, sizeof scene, "%s/rotated.json", dir);
    FILE *f = fopen(scene, "w");
    cr_assert(f, "cannot write %s", scene);
    fprintf(f, "{\"camera\": {\"eye\": [0, 0.6, 4.5], \"target\": [0, -0.2, 0], \"fov_y\": 40},\n"
               " \"render\": {\"max_depth\": 6},\n"
               " \"objects\": [{\"obj\": \"%s/scenes/venice/sphere.obj\"}],\n"
               " \"environment\": {\"file\": \"%s/scenes/venice/venice_sunset_1k.hdr\", \"rotation\": 90}}\n",
            root, root);
    fclose(f);
    Run r = run_pt("render %s %s -q -o %s/rotated.exr", scene, size, dir);
    cr_assert_eq(r.exit_code, 0, "pt render: %s", r.err);
    r = run_pt("render scenes/venice/sphere.json %s -q -o %s/unrotated.exr", size, dir);
    cr_assert_eq(r.exit_code, 0, "pt render: %s", r.err);
    float *view = read_film(dir, "view.exr", 48, 32), *rotated = read_film(dir, "rotated.exr", 48, 32);
    float *unrotated = read_film(dir, "unrotated.exr", 48, 32);
    size_t n = (size_t)48 * 32 * 3;
    cr_expect(memcmp(view, rotated, n * sizeof *view) == 0, "the film is not pt render at rotation 90");
    cr_expect(memcmp(view, unrotated, n * sizeof *view) != 0, "the film is still at rotation 0");
    free(view), free(rotated), free(unrotated);
}
