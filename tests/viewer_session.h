/* SPDX-License-Identifier: MIT */
/* viewer_session.h: helpers of the 'pt view' end-to-end tests (tests/test_viewer*.c): the real
 * binary (PT_BIN, default build/pt) on a private Xvfb server, driven by xdotool. Tests run from the
 * repository root. Every helper fails the running test (cr_assert) when something it needs fails. */
#ifndef PT_TEST_VIEWER_SESSION_H
#define PT_TEST_VIEWER_SESSION_H

#include <limits.h>
#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>
#include <time.h>

/* ---- A private X server per test: the suite's .init and .fini ------------------------------- */

extern char display_name[32]; /* ":N" once start_xvfb succeeded, else empty */
void start_xvfb(void);
void stop_xvfb(void);
void require_display(void); /* fails the test with the reason when Xvfb did not start */

/* ---- Running pt ----------------------------------------------------------------------------- */

typedef struct {
    int exit_code;
    char out[8192], err[8192];
} Run;

/* Runs `pt ARGS` (printf-formatted) on this test's display, or with no display at all when the
 * suite started none. The result is static: valid until the next call. */
Run run_pt(const char *format, ...) __attribute__((format(printf, 1, 2)));
void slurp(const char *path, char *out, size_t size); /* a file's text, "" when unreadable */
bool one_line(const char *text);

/* ---- Images --------------------------------------------------------------------------------- */

typedef struct {
    int width, height;
    unsigned char *rgb;
} Png;

Png load_png(const char *dir, const char *name); /* free .rgb with stbi_image_free */
double mean_squared_difference(Png a, Png b);     /* of the 8-bit values */
void channel_means(Png p, double mean[3]);
/* Expects dir/NAME.png to be 'pt render RENDER_ARGS' at seed, up to 8-bit rounding; returns the
 * noise (the mean squared difference between two seeds). */
double expect_screenshot_is_the_render(const char *dir, const char *name, unsigned seed,
                                       const char *render_args);

/* The viewer's summary line at exit (host/viewer/stats.h). */
typedef struct {
    int frames, spp;
    double first_ms, mean_ms, median_ms, p95_ms, max_ms;
} Summary;

Summary parse_summary(const char *err);

/* ---- A scripted session: pt view --events, driven by xdotool -------------------------------- */

typedef struct {
    pid_t pid;
    int out_fd;          /* the viewer's stdout */
    char out[65536];     /* all of it so far */
    size_t length;
    char err_path[PATH_MAX], window[32];
    struct timespec start;
} ViewSession;

/* Starts `pt ARGS` (a shell word list, printf-formatted) in dir on this test's display. */
void session_start(ViewSession *s, const char *dir, const char *format, ...)
    __attribute__((format(printf, 3, 4)));
/* Waits for a whole line holding needle at or after offset from; returns the offset past it. */
size_t session_wait(ViewSession *s, size_t from, const char *needle);
void xdotool(ViewSession *s, const char *args); /* %W in args is the viewer's window */
/* xdotool ARGS, then session_wait for needle from offset from: one input and its acknowledgment. */
size_t session_send(ViewSession *s, size_t from, const char *args, const char *needle);
void session_find_window(ViewSession *s);       /* after 'event: ready' */
int session_quit(ViewSession *s);               /* Escape; the exit status */
/* pt view ARGS in dir until the film has spp samples per pixel; then Esc. Returns the exit status;
 * *session keeps the output. */
int view_until_converged(ViewSession *session, const char *dir, int spp, const char *args);

#endif
