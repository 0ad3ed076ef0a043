// SPDX-License-Identifier: MIT
/* 'pt view' end to end: the real binary in a real window on a private Xvfb server (Mesa's
 * llvmpipe), driven by --frames/--screenshot/--camera and by xdotool. Screenshots are compared with
 * 'pt render' of the same scene, pose, size, spp and seed: equal up to 8-bit rounding, measured
 * against the difference between two seeds (the noise). Xvfb and xdotool are required, not
 * optional: 'make test' installs them (tools/install-deps.sh), so their absence fails the tests.
 * PT_BIN names the binary (default build/pt); tests run from the repository root. */
#define _XOPEN_SOURCE 700 /* realpath */
#include <criterion/criterion.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stb_image.h>

#include "support.h"
#include "viewer/camera_controls.h"

/* ---- A private X server per test ------------------------------------------------------------ */

static pid_t xvfb_pid;
static char display_name[32];
static char xvfb_failure[256];

/* Xvfb picks a free display number itself and writes it to a pipe (-displayfd): tests running in
 * parallel never share a server, so xdotool only ever sees this test's window. The server dies
 * with the test process (PR_SET_PDEATHSIG) even if the test crashes. */
static void start_xvfb(void)
{
    int fds[2];
    if (pipe(fds) != 0) {
        snprintf(xvfb_failure, sizeof xvfb_failure, "pipe: %s", strerror(errno));
        return;
    }
    xvfb_pid = fork();
    if (xvfb_pid == 0) {
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        close(fds[0]);
        char fd_text[16];
        snprintf(fd_text, sizeof fd_text, "%d", fds[1]);
        int devnull = open("/dev/null", O_WRONLY);
        dup2(devnull, STDOUT_FILENO), dup2(devnull, STDERR_FILENO);
        execlp("Xvfb", "Xvfb", "-displayfd", fd_text, "-screen", "0", "1024x768x24", "-nolisten",
               "tcp", (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    /* "NUMBER\n" once it listens; end of file if it could not start (not installed, say). */
    char text[16] = "";
    size_t length = 0;
    struct pollfd ready = {.fd = fds[0], .events = POLLIN};
    while (length < sizeof text - 1 && !strchr(text, '\n') && poll(&ready, 1, 20000) == 1) {
        ssize_t n = read(fds[0], text + length, sizeof text - 1 - length);
        if (n <= 0)
            break;
        length += (size_t)n, text[length] = '\0';
    }
    close(fds[0]);
    if (strchr(text, '\n'))
        snprintf(display_name, sizeof display_name, ":%d", atoi(text));
    else
        snprintf(xvfb_failure, sizeof xvfb_failure,
                 "Xvfb did not start (is it installed? 'make test' installs xvfb, xauth, "
                 "libgl1-mesa-dri and xdotool with tools/install-deps.sh)");
}

static void stop_xvfb(void)
{
    if (xvfb_pid > 0) {
        kill(xvfb_pid, SIGTERM);
        waitpid(xvfb_pid, NULL, 0);
    }
    xvfb_pid = 0;
}

static void require_display(void)
{
    cr_assert(display_name[0], "%s", xvfb_failure);
}

TestSuite(view, .init = start_xvfb, .fini = stop_xvfb, .timeout = 120);

/* ---- Running pt ----------------------------------------------------------------------------- */

typedef struct {
    int exit_code;
    char out[8192], err[8192];
} Run;

static const char *pt_bin(void)
{
    static char path[PATH_MAX];
    const char *bin = getenv("PT_BIN");
    cr_assert(realpath(bin ? bin : "build/pt", path), "pt binary %s not found (set PT_BIN)",
              bin ? bin : "build/pt");
    return path;
}

static void slurp(const char *path, char *out, size_t size)
{
    char *text = test_read_file(path, NULL);
    snprintf(out, size, "%s", text ? text : "");
    free(text);
}

/* Runs `pt ARGS` (printf-formatted) on this test's display, or with no display at all when the
 * suite started none. */
static Run run_pt(const char *format, ...) __attribute__((format(printf, 1, 2)));
static Run run_pt(const char *format, ...)
{
    static Run r;
    memset(&r, 0, sizeof r);
    char args[4096], out_path[64], err_path[64], cmd[8192];
    va_list ap;
    va_start(ap, format);
    vsnprintf(args, sizeof args, format, ap);
    va_end(ap);
    snprintf(out_path, sizeof out_path, "/tmp/pt-view-out-%d", (int)getpid());
    snprintf(err_path, sizeof err_path, "/tmp/pt-view-err-%d", (int)getpid());
    char display[64] = "env -u DISPLAY -u WAYLAND_DISPLAY";
    if (display_name[0])
        snprintf(display, sizeof display, "DISPLAY=%s", display_name);
    snprintf(cmd, sizeof cmd, "%s timeout 100 '%s' %s >%s 2>%s", display, pt_bin(), args, out_path,
             err_path);
    int status = system(cmd);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    slurp(out_path, r.out, sizeof r.out);
    slurp(err_path, r.err, sizeof r.err);
    unlink(out_path), unlink(err_path);
    return r;
}

static bool one_line(const char *text) { return strchr(text, '\n') == text + strlen(text) - 1; }

/* ---- Images --------------------------------------------------------------------------------- */

typedef struct {
    int width, height;
    unsigned char *rgb;
} Png;

static Png load_png(const char *dir, const char *name)
{
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    Png png = {0};
    int channels;
    png.rgb = stbi_load(path, &png.width, &png.height, &channels, 3);
    cr_assert(png.rgb, "cannot read %s", path);
    return png;
}

/* Mean squared difference of the 8-bit values. */
static double mean_squared_difference(Png a, Png b)
{
    cr_assert(a.width == b.width && a.height == b.height, "%dx%d vs %dx%d", a.width, a.height,
              b.width, b.height);
    double sum = 0.0;
    size_t n = (size_t)a.width * (size_t)a.height * 3;
    for (size_t i = 0; i < n; i++)
        sum += ((double)a.rgb[i] - b.rgb[i]) * ((double)a.rgb[i] - b.rgb[i]);
    return sum / (double)n;
}

/* The z-score of the mean of channel c of a - b, with the standard error taken from the pixel
 * differences (pixels are independent samples: the RNG is keyed on the pixel). */
static double mean_difference_z(Png a, Png b, int c)
{
    size_t n = (size_t)a.width * (size_t)a.height;
    double sum = 0.0, sum_squares = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = (double)a.rgb[3 * i + c] - b.rgb[3 * i + c];
        sum += d, sum_squares += d * d;
    }
    double mean = sum / (double)n, variance = (sum_squares / (double)n - mean * mean);
    return mean / sqrt(fmax(variance, 1e-12) / (double)n);
}

static void channel_means(Png p, double mean[3])
{
    mean[0] = mean[1] = mean[2] = 0.0;
    size_t n = (size_t)p.width * (size_t)p.height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            mean[c] += p.rgb[3 * i + c] / (double)n;
}

/* dir/NAME.png (a screenshot) against 'pt render RENDER_ARGS' at the screenshot's seed and at
 * another: with the same seed the two are the same estimate (the RNG is keyed on pixel and sample,
 * whatever the batches), so they may differ only by rounding, a small fraction of the two seeds'
 * difference; the screenshot's mean is within noise of the other seed's. Returns that noise. */
static double expect_screenshot_is_the_render(const char *dir, const char *name, unsigned seed,
                                              const char *render_args)
{
    Run r = run_pt("render %s --seed %u -q -o %s/%s-same.png", render_args, seed, dir, name);
    cr_assert_eq(r.exit_code, 0, "pt render: %s", r.err);
    r = run_pt("render %s --seed %u -q -o %s/%s-other.png", render_args, seed + 1, dir, name);
    cr_assert_eq(r.exit_code, 0, "pt render: %s", r.err);
    char file[256];
    snprintf(file, sizeof file, "%s.png", name);
    Png shot = load_png(dir, file);
    snprintf(file, sizeof file, "%s-same.png", name);
    Png same = load_png(dir, file);
    snprintf(file, sizeof file, "%s-other.png", name);
    Png other = load_png(dir, file);
    double to_same = mean_squared_difference(shot, same), noise = mean_squared_difference(same, other);
    cr_expect(noise > 10.0, "%s: two seeds differ by noise: %g", name, noise);
    cr_expect(to_same < 0.02 * noise, "%s vs the same-seed render: %g (noise between seeds %g)",
              name, to_same, noise);
    cr_log_info("%s: mean squared difference to the same seed %.3g, between seeds %.3g, z = %.2f "
                "%.2f %.2f", name, to_same, noise, mean_difference_z(shot, other, 0),
                mean_difference_z(shot, other, 1), mean_difference_z(shot, other, 2));
    for (int c = 0; c < 3; c++) {
        double z = mean_difference_z(shot, other, c);
        cr_expect(fabs(z) < 4.0, "%s: channel %d mean vs another seed's: z = %g", name, c, z);
    }
    stbi_image_free(shot.rgb), stbi_image_free(same.rgb), stbi_image_free(other.rgb);
    return noise;
}

/* The viewer's summary line at exit (host/viewer/stats.h). */
typedef struct {
    int frames, spp;
    double first_ms, mean_ms, median_ms, p95_ms, max_ms;
} Summary;

static Summary parse_summary(const char *err)
{
    Summary s = {.spp = -1};
    const char *line = strstr(err, "pt: view: "), *next;
    while (line && (next = strstr(line + 1, "pt: view: ")))
        line = next; /* the last: after "press H" */
    cr_assert(line && sscanf(line,
                             "pt: view: %d frames, %d spp; first frame %lf ms, then frame time "
                             "mean %lf ms, median %lf ms, p95 %lf ms, max %lf ms",
                             &s.frames, &s.spp, &s.first_ms, &s.mean_ms, &s.median_ms, &s.p95_ms,
                             &s.max_ms) == 7,
              "no summary line in: %s", err);
    return s;
}

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
    const char *common = "scenes/cornell-box --width 128 --height 96 --spp 8 --exposure 0.5";
    Run view = run_pt("view %s --seed 7 --frames 400 --screenshot %s/view.png", common, dir);
    cr_assert_eq(view.exit_code, 0, "pt view failed: %s", view.err);
    cr_assert_eq(parse_summary(view.err).spp, 8, "the viewer stops at the target spp: %s", view.err);
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
    Run r = run_pt("view scenes/cornell-box %s --frames 300 -q --camera '{%s}' --screenshot %s/posed.png",
                   size, pose, dir);
    cr_assert_eq(r.exit_code, 0, "pt view --camera: %s", r.err);
    char render_args[PATH_MAX + 64];
    snprintf(render_args, sizeof render_args, "%s %s", scene, size);
    double noise = expect_screenshot_is_the_render(dir, "posed", 0, render_args);

    Png posed = load_png(dir, "posed.png");
    double mean[3];
    channel_means(posed, mean);
    cr_expect(mean[0] > 2.0 * mean[1] && mean[0] > 2.0 * mean[2], "the left wall is red: %g %g %g",
              mean[0], mean[1], mean[2]);
    r = run_pt("render scenes/cornell-box %s -q -o %s/scene-pose.png", size, dir);
    cr_assert_eq(r.exit_code, 0, "pt render: %s", r.err);
    Png scene_pose = load_png(dir, "scene-pose.png");
    double moved = mean_squared_difference(posed, scene_pose);
    cr_log_info("posed vs the scene's pose: %.3g", moved);
    cr_expect(moved > 10.0 * noise, "the pose changed the view: %g vs noise %g", moved, noise);
    stbi_image_free(posed.rgb), stbi_image_free(scene_pose.rgb);

    Run bad = run_pt("view scenes/cornell-box --frames 1 --camera '{\"eye\": [0, 1]}'");
    cr_expect_eq(bad.exit_code, 1, "bad --camera: exit %d", bad.exit_code);
    cr_expect(strstr(bad.err, "'eye'") && one_line(bad.err), "one line naming the key: %s", bad.err);
}

/* --frames N runs exactly N frames on PoCL and the exit summary reports the frame times it
 * measured (the pacing itself is tested without a clock in test_viewer_pacing.c; frame times are
 * measurements for the notes, not thresholds for a test). */
Test(view, frames_run_and_frame_times_are_reported_on_pocl)
{
    require_display();
    Run r = run_pt("view scenes/cornell-box --device cpu --width 256 --height 256 --frames 40");
    cr_assert_eq(r.exit_code, 0, "%s", r.err);
    Summary s = parse_summary(r.err);
    cr_expect(s.frames == 40 && s.spp >= 1, "%d frames, %d spp", s.frames, s.spp);
    cr_expect(s.median_ms > 0.0 && s.p95_ms >= s.median_ms, "median %g ms, p95 %g ms", s.median_ms,
              s.p95_ms);
}

/* A user session scripted with xdotool: shrink the window, print the camera, orbit by a drag,
 * print it again, wait for the target spp, save twice, quit. The film follows the framebuffer:
 * the screenshot is 'pt render' of the orbited pose at the new size. */
Test(view, keys_drag_and_resize_in_a_real_window)
{
    require_display();
    cr_assert(system("command -v xdotool >/dev/null 2>&1") == 0,
              "xdotool not installed ('make test' installs it with tools/install-deps.sh)");
    const char *dir = test_temp_dir();
    char root[PATH_MAX], script[16384];
    cr_assert(getcwd(root, sizeof root));
    snprintf(script, sizeof script,
             "cd '%s'; export DISPLAY=%s; "
             "timeout 60 '%s' view '%s/scenes/cornell-box' --width 200 --height 150 --spp 4 "
             "--screenshot shot.png >stdout 2>stderr & pt=$!; "
             "session() { "
             "W=$(timeout 30 xdotool search --sync --name '^pt view.*spp') || return 3; "
             "xdotool windowfocus --sync $W && xdotool windowsize --sync $W 160 120 && sleep 0.5 && "
             "xdotool key c && sleep 0.3 && "
             "xdotool mousemove --window $W 80 60 && sleep 0.2 && xdotool mousedown 1 && sleep 0.2 && "
             "xdotool mousemove_relative 40 0 && sleep 0.2 && xdotool mouseup 1 && sleep 0.5 && "
             "xdotool key c && timeout 30 xdotool search --sync --name ' 4 spp [(]done[)]' >/dev/null && "
             "xdotool key ctrl+s && sleep 0.5 && xdotool key ctrl+s && sleep 0.5 && "
             "xdotool key Escape; }; "
             "session; r=$?; [ $r -eq 0 ] || kill $pt; wait $pt; echo $? >status; exit $r",
             dir, display_name, pt_bin(), root);
    int script_status = system(script);
    char path[PATH_MAX], status[64], out[8192], err[8192];
    snprintf(path, sizeof path, "%s/status", dir);
    slurp(path, status, sizeof status);
    snprintf(path, sizeof path, "%s/stdout", dir);
    slurp(path, out, sizeof out);
    snprintf(path, sizeof path, "%s/stderr", dir);
    slurp(path, err, sizeof err);
    cr_assert_eq(script_status, 0, "the xdotool script failed (%d); pt stdout: %s stderr: %s",
                 script_status, out, err);
    cr_assert_eq(atoi(status), 0, "pt view exit status %s, stderr: %s", status, err);

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
}
