// SPDX-License-Identifier: MIT
/* 'pt view' end to end: the real binary in a real window on a private Xvfb server (Mesa's
 * llvmpipe), driven by xdotool, each input sent once the viewer has acknowledged the last
 * (--events). Screenshots are compared with 'pt render' of the same scene, pose, size, spp and
 * seed: equal up to 8-bit rounding, measured against the difference between two seeds (the
 * noise); the film itself (--screenshot FILE.exr) is compared bit for bit. Xvfb and xdotool are
 * required, not optional: 'make test' installs them (tools/install-deps.sh), so their absence fails the tests.
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
#include <time.h>
#include <unistd.h>

#include <stb_image.h>

#include "support.h"
#include "io/image_io.h"
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

/* ---- A scripted session: pt view --events, driven by xdotool -------------------------------- */

/* The viewer runs with --events and the test reads its stdout: each xdotool command is sent only
 * once the viewer has printed that it read the previous event, and images are taken only after
 * 'event: converged N spp'. Nothing waits for a time: how many frames run between events, however
 * loaded the machine, changes nothing. The deadline only ends a session that hangs. */
#define SESSION_DEADLINE_S 100.0

typedef struct {
    pid_t pid;
    int out_fd;          /* the viewer's stdout */
    char out[65536];     /* all of it so far */
    size_t length;
    char err_path[PATH_MAX], window[32];
    struct timespec start;
} ViewSession;

static double session_seconds(const ViewSession *s)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)(now.tv_sec - s->start.tv_sec) + 1e-9 * (double)(now.tv_nsec - s->start.tv_nsec);
}

/* Starts `pt ARGS` (a shell word list) in dir on this test's display. */
static void session_start(ViewSession *s, const char *dir, const char *format, ...)
    __attribute__((format(printf, 3, 4)));
static void session_start(ViewSession *s, const char *dir, const char *format, ...)
{
    cr_assert(system("command -v xdotool >/dev/null 2>&1") == 0,
              "xdotool not installed ('make test' installs it with tools/install-deps.sh)");
    memset(s, 0, sizeof *s);
    char args[4096], cmd[8192];
    va_list ap;
    va_start(ap, format);
    vsnprintf(args, sizeof args, format, ap);
    va_end(ap);
    snprintf(cmd, sizeof cmd, "exec '%s' %s", pt_bin(), args);
    snprintf(s->err_path, sizeof s->err_path, "%s/stderr", dir);
    clock_gettime(CLOCK_MONOTONIC, &s->start);
    int fds[2];
    cr_assert(pipe(fds) == 0, "pipe: %s", strerror(errno));
    s->pid = fork();
    cr_assert(s->pid >= 0, "fork: %s", strerror(errno));
    if (s->pid == 0) {
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        int err = open(s->err_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (chdir(dir) != 0 || err < 0)
            _exit(127);
        dup2(fds[1], STDOUT_FILENO), dup2(err, STDERR_FILENO);
        close(fds[0]), close(fds[1]), close(err);
        setenv("DISPLAY", display_name, 1);
        execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
        _exit(127);
    }
    close(fds[1]);
    s->out_fd = fds[0];
}

/* Reads what the viewer printed; false at end of file. Fails the test past the deadline. */
static bool session_read(ViewSession *s)
{
    char err[4096];
    struct pollfd ready = {.fd = s->out_fd, .events = POLLIN};
    while (poll(&ready, 1, 1000) == 0) {
        if (session_seconds(s) > SESSION_DEADLINE_S) {
            kill(s->pid, SIGKILL);
            slurp(s->err_path, err, sizeof err);
            cr_assert_fail("pt view hung; stdout: %s stderr: %s", s->out, err);
        }
    }
    cr_assert(s->length < sizeof s->out - 1, "pt view printed too much: %s", s->out);
    ssize_t n = read(s->out_fd, s->out + s->length, sizeof s->out - 1 - s->length);
    if (n <= 0)
        return false;
    s->length += (size_t)n, s->out[s->length] = '\0';
    return true;
}

/* Waits for a whole line holding needle that starts at or after offset from; returns the offset
 * just past it (where to look for what the viewer did next). */
static size_t session_wait(ViewSession *s, size_t from, const char *needle)
{
    for (;;) {
        for (char *line = s->out + from, *end; (end = strchr(line, '\n')); line = end + 1) {
            *end = '\0';
            bool found = strstr(line, needle) != NULL;
            *end = '\n';
            if (found)
                return (size_t)(end + 1 - s->out);
        }
        if (!session_read(s)) {
            char err[4096];
            slurp(s->err_path, err, sizeof err);
            cr_assert_fail("pt view ended before printing '%s'; stdout: %s stderr: %s", needle,
                           s->out, err);
        }
    }
}

/* Runs `xdotool ARGS` on this test's display; %W in args is the viewer's window. */
static void xdotool(ViewSession *s, const char *args)
{
    char expanded[512], cmd[1024];
    const char *w = strstr(args, "%W");
    if (w)
        snprintf(expanded, sizeof expanded, "%.*s%s%s", (int)(w - args), args, s->window, w + 2);
    else
        snprintf(expanded, sizeof expanded, "%s", args);
    snprintf(cmd, sizeof cmd, "DISPLAY=%s xdotool %s", display_name, expanded);
    cr_assert(system(cmd) == 0, "%s failed; pt stdout so far: %s", cmd, s->out);
}

/* After 'event: ready': the window exists (it is created before the line is printed). */
static void session_find_window(ViewSession *s)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "DISPLAY=%s xdotool search --name '^pt view'", display_name);
    FILE *search = popen(cmd, "r");
    cr_assert(search, "popen %s", cmd);
    bool found = fgets(s->window, sizeof s->window, search) != NULL;
    pclose(search);
    cr_assert(found && atoi(s->window) > 0, "no 'pt view' window on %s", display_name);
    s->window[strcspn(s->window, "\n")] = '\0';
    xdotool(s, "windowfocus --sync %W");
}

/* Escape, then the exit status once the viewer has written what it writes at exit. */
static int session_quit(ViewSession *s)
{
    xdotool(s, "key Escape");
    while (session_read(s)) {
    }
    close(s->out_fd);
    int status;
    cr_assert(waitpid(s->pid, &status, 0) == s->pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* pt view ARGS in dir until the film has spp samples per pixel; then Esc. Returns the exit
 * status; *session keeps the output. */
static int view_until_converged(ViewSession *session, const char *dir, int spp, const char *args)
{
    session_start(session, dir, "view %s --spp %d --events", args, spp);
    session_wait(session, 0, "event: ready");
    session_find_window(session);
    char converged[64];
    snprintf(converged, sizeof converged, "event: converged %d spp", spp);
    session_wait(session, 0, converged);
    return session_quit(session);
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

    Run bad = run_pt("view scenes/cornell-box --frames 1 --camera '{\"eye\": [0, 1]}'");
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
    xdotool(&s, "windowsize --sync %W 160 120");
    at = session_wait(&s, at, "event: film 160x120");
    xdotool(&s, "key c");
    at = session_wait(&s, at, "\"camera\"");
    xdotool(&s, "mousemove --window %W 80 60");
    at = session_wait(&s, at, "event: cursor 80 60");
    xdotool(&s, "mousedown 1");
    at = session_wait(&s, at, "event: button 0 press");
    xdotool(&s, "mousemove_relative 40 0");
    size_t orbited = at = session_wait(&s, at, "event: cursor 120 60");
    xdotool(&s, "mouseup 1");
    at = session_wait(&s, at, "event: button 0 release");
    /* converged after the orbit: perhaps already before the release */
    at = session_wait(&s, orbited, "event: converged 4 spp");
    xdotool(&s, "key c");
    at = session_wait(&s, at, "\"camera\"");
    xdotool(&s, "key ctrl+s");
    at = session_wait(&s, at, "wrote out/cornell-box-view-1.png");
    xdotool(&s, "key ctrl+s");
    at = session_wait(&s, at, "wrote out/cornell-box-view-2.png");
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

/* The film at N spp is 'pt render' at N spp bit for bit (--screenshot FILE.exr writes the film).
 * 512x512 keeps both at one sample per pixel per window (the viewer's windows are at most 16384
 * samples here, pt render's 4 x 65536 on a CPU), so the film sums samples in the same order in
 * both: this holds whatever the viewer's windows once the film sums exactly (integer sums). */
Test(view, film_at_n_spp_is_pt_render_bit_for_bit)
{
    require_display();
    const char *dir = test_temp_dir();
    char root[PATH_MAX];
    cr_assert(getcwd(root, sizeof root));
    /* 64x64 at 8 spp: each of the viewer's windows (and pt render's single one) holds several
     * samples per pixel, so only an exact, order-independent film makes the two agree. */
    const char *size = "--width 64 --height 64 --seed 3";
    char args[PATH_MAX + 256];
    snprintf(args, sizeof args, "'%s/scenes/cornell-box' %s --screenshot view.exr", root, size);
    ViewSession s;
    int exit_code = view_until_converged(&s, dir, 8, args);
    char err[8192];
    slurp(s.err_path, err, sizeof err);
    cr_assert_eq(exit_code, 0, "pt view: %s", err);
    cr_assert(strstr(s.out, "wrote view.exr (8 spp)"), "stdout: %s", s.out);
    Run r = run_pt("render scenes/cornell-box %s --spp 8 -q -o %s/render.exr", size, dir);
    cr_assert_eq(r.exit_code, 0, "pt render: %s", r.err);

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
    cr_expect_eq(differ, 0, "%zu of %zu values differ; the first, pixel %zu channel %zu: %.9g in "
                 "the viewer, %.9g in pt render", differ, n, first / 3, first % 3,
                 first < n ? view[first] : 0.0f, first < n ? render[first] : 0.0f);
    free(view), free(render);
}
