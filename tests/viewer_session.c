// SPDX-License-Identifier: MIT
/* viewer_session.c: what the 'pt view' tests (test_viewer*.c) share: a private Xvfb server per
 * test, running pt and reading what it printed, comparing screenshots with 'pt render', and a
 * scripted session that sends each xdotool input once the viewer has acknowledged the last
 * (--events). */
#define _XOPEN_SOURCE 700 /* realpath */
#include "viewer_session.h"

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

/* ---- A private X server per test ------------------------------------------------------------ */

static pid_t xvfb_pid;
char display_name[32];
static char xvfb_failure[256];

/* Xvfb picks a free display number itself and writes it to a pipe (-displayfd): tests running in
 * parallel never share a server, so xdotool only ever sees this test's window. The server dies
 * with the test process (PR_SET_PDEATHSIG) even if the test crashes. */
void start_xvfb(void)
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

void stop_xvfb(void)
{
    if (xvfb_pid > 0) {
        kill(xvfb_pid, SIGTERM);
        waitpid(xvfb_pid, NULL, 0);
    }
    xvfb_pid = 0;
}

void require_display(void)
{
    cr_assert(display_name[0], "%s", xvfb_failure);
}

/* ---- Running pt ----------------------------------------------------------------------------- */

void slurp(const char *path, char *out, size_t size)
{
    char *text = test_read_file(path, NULL);
    snprintf(out, size, "%s", text ? text : "");
    free(text);
}

/* Runs `pt ARGS` (printf-formatted) on this test's display, or with no display at all when the
 * suite started none. */
Run run_pt(const char *format, ...)
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
    snprintf(cmd, sizeof cmd, "%s timeout 100 '%s' %s >%s 2>%s", display, test_pt_bin(), args, out_path,
             err_path);
    int status = system(cmd);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    slurp(out_path, r.out, sizeof r.out);
    slurp(err_path, r.err, sizeof r.err);
    unlink(out_path), unlink(err_path);
    return r;
}

bool one_line(const char *text) { return strchr(text, '\n') == text + strlen(text) - 1; }

/* ---- Images --------------------------------------------------------------------------------- */

Png load_png(const char *dir, const char *name)
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
double mean_squared_difference(Png a, Png b)
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

void channel_means(Png p, double mean[3])
{
    mean[0] = mean[1] = mean[2] = 0.0;
    size_t n = (size_t)p.width * (size_t)p.height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            mean[c] += p.rgb[3 * i + c] / (double)n;
}

/* dir/NAME.png (a screenshot) against 'pt render RENDER_ARGS' at the screenshot's seed and at
 * another: with the same seed the two are the same estimate (the RNG is keyed on pixel and sample,
 * whatever the windows), so they may differ only by rounding, a small fraction of the two seeds'
 * difference; the screenshot's mean is within noise of the other seed's. Returns that noise. */
double expect_screenshot_is_the_render(const char *dir, const char *name, unsigned seed,
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

Summary parse_summary(const char *err)
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

static double session_seconds(const ViewSession *s)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)(now.tv_sec - s->start.tv_sec) + 1e-9 * (double)(now.tv_nsec - s->start.tv_nsec);
}

/* Starts `pt ARGS` (a shell word list) in dir on this test's display. */
void session_start(ViewSession *s, const char *dir, const char *format, ...)
{
    cr_assert(system("command -v xdotool >/dev/null 2>&1") == 0,
              "xdotool not installed ('make test' installs it with tools/install-deps.sh)");
    memset(s, 0, sizeof *s);
    char args[4096], cmd[8192];
    va_list ap;
    va_start(ap, format);
    vsnprintf(args, sizeof args, format, ap);
    va_end(ap);
    snprintf(cmd, sizeof cmd, "exec '%s' %s", test_pt_bin(), args);
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
size_t session_wait(ViewSession *s, size_t from, const char *needle)
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
void xdotool(ViewSession *s, const char *args)
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

size_t session_send(ViewSession *s, size_t from, const char *args, const char *needle)
{
    xdotool(s, args);
    return session_wait(s, from, needle);
}

/* After 'event: ready': the window exists (it is created before the line is printed). */
void session_find_window(ViewSession *s)
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
int session_quit(ViewSession *s)
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
int view_until_converged(ViewSession *session, const char *dir, int spp, const char *args)
{
    session_start(session, dir, "view %s --spp %d --events", args, spp);
    session_wait(session, 0, "event: ready");
    session_find_window(session);
    char converged[64];
    snprintf(converged, sizeof converged, "event: converged %d spp", spp);
    session_wait(session, 0, converged);
    return session_quit(session);
}
