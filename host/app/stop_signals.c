// SPDX-License-Identifier: MIT
#include "app/stop_signals.h"

#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

static volatile sig_atomic_t g_signal_received;

/* The signals pt was started ignoring, seen before any library could change them (PoCL resets
 * some while it starts). */
static bool g_ignored_at_start[3];

/* PT_TEST_RAISE, parsed: the signal, its point and how many more times the point is reached
 * before it is raised (the point is reached from several worker threads at once: "unit"). */
static int g_test_signal;
static const char *g_test_point;
static atomic_long g_test_countdown;

static const struct {
    int number;
    const char *name;
} stop_signals[] = {{SIGINT, "SIGINT"}, {SIGTERM, "SIGTERM"}, {SIGHUP, "SIGHUP"}};
enum { STOP_SIGNAL_COUNT = sizeof stop_signals / sizeof stop_signals[0] };
_Static_assert(STOP_SIGNAL_COUNT == 3, "g_ignored_at_start has one entry per signal");

static const char *const test_points[] = {"render", "write", "unit", "checkpoint"};

/* Signals PT_TEST_RAISE may raise: the stop signals, and SIGKILL (a crash that nothing can
 * catch: the checkpoint tests). */
static int test_signal_number(const char *name, size_t length)
{
    for (int s = 0; s < STOP_SIGNAL_COUNT; s++) {
        const char *short_name = stop_signals[s].name + 3;
        if (strlen(short_name) == length && !strncmp(name, short_name, length))
            return stop_signals[s].number;
    }
    return length == 4 && !strncmp(name, "KILL", 4) ? SIGKILL : 0;
}

/* POINT or POINT:COUNT (COUNT from 1: the COUNT-th time the point is reached). */
static bool parse_test_point(const char *text)
{
    const char *colon = strchr(text, ':');
    size_t length = colon ? (size_t)(colon - text) : strlen(text);
    long count = 1;
    if (colon) {
        char *end;
        if (colon[1] < '0' || colon[1] > '9')
            return false;
        count = strtol(colon + 1, &end, 10);
        if (*end || count < 1 || count > 1000000000L)
            return false;
    }
    for (size_t p = 0; p < sizeof test_points / sizeof test_points[0]; p++) {
        if (strlen(test_points[p]) == length && !strncmp(text, test_points[p], length)) {
            g_test_point = test_points[p];
            atomic_store(&g_test_countdown, count);
            return true;
        }
    }
    return false;
}

static void on_stop_signal(int signal_number)
{
    if (!g_signal_received)
        g_signal_received = signal_number;
}

bool stop_signals_configure(Error *err)
{
    for (int s = 0; s < STOP_SIGNAL_COUNT; s++) {
        struct sigaction old;
        g_ignored_at_start[s] = sigaction(stop_signals[s].number, NULL, &old) == 0 &&
                                old.sa_handler == SIG_IGN;
    }
    const char *value = getenv("PT_TEST_RAISE");
    if (!value || !*value)
        return true;
    const char *at = strchr(value, '@'), *name = value;
    size_t name_length = at ? (size_t)(at - value) : 0;
    if (name_length > 3 && !strncmp(name, "SIG", 3)) /* SIGTERM or TERM */
        name += 3, name_length -= 3;
    int number = at ? test_signal_number(name, name_length) : 0;
    if (number && parse_test_point(at + 1)) {
        g_test_signal = number;
        return true;
    }
    error_set(err, ERR_USAGE, NULL, 0,
              "environment variable PT_TEST_RAISE=%s: expected SIGNAL@POINT or SIGNAL@POINT:COUNT "
              "with SIGNAL one of INT, TERM, HUP, KILL, POINT one of render, write, unit, "
              "checkpoint and COUNT a number from 1", value);
    return false;
}

void stop_signals_install(void)
{
    g_signal_received = 0;
    for (int s = 0; s < STOP_SIGNAL_COUNT; s++) {
        struct sigaction action;
        memset(&action, 0, sizeof action);
        /* Started ignoring it (nohup): keep ignoring it, whatever OpenCL's start did. */
        action.sa_handler = g_ignored_at_start[s] ? SIG_IGN : on_stop_signal;
        sigemptyset(&action.sa_mask);
        /* Restart interrupted system calls: the render and the file writes carry on, and the
         * render loop looks at the flag between windows. */
        action.sa_flags = SA_RESTART;
        sigaction(stop_signals[s].number, &action, NULL);
    }
    /* A file-size limit (ulimit -f) makes a write fail with EFBIG, which pt reports like a full
     * disk, rather than kill it. Also LLVM (inside PoCL) installs a crash handler for SIGXFSZ
     * that, when it runs, resets every handler to the default, pt's stop handlers with them: the
     * next SIGTERM then killed pt without its image. */
    signal(SIGXFSZ, SIG_IGN);
}

int stop_signal_received(void) { return g_signal_received; }

const char *stop_signal_name(int signal_number)
{
    for (int s = 0; s < STOP_SIGNAL_COUNT; s++)
        if (stop_signals[s].number == signal_number)
            return stop_signals[s].name;
    return "a signal";
}

int stop_exit_status(void) { return g_signal_received ? 128 + g_signal_received : 0; }

void stop_signals_test_point(const char *point)
{
    /* Exactly one caller sees the countdown go from 1 to 0, however many threads reach it. */
    if (g_test_signal && !strcmp(point, g_test_point) &&
        atomic_fetch_sub(&g_test_countdown, 1) == 1)
        raise(g_test_signal);
}
