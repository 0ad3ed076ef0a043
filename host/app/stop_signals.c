// SPDX-License-Identifier: MIT
#include "app/stop_signals.h"

#include <signal.h>
#include <stdlib.h>
#include <string.h>

static volatile sig_atomic_t g_signal_received;

/* The signals pt was started ignoring, seen before any library could change them (PoCL resets
 * some while it starts). */
static bool g_ignored_at_start[3];

/* PT_TEST_RAISE, parsed. */
static int g_test_signal;
static const char *g_test_point;

static const struct {
    int number;
    const char *name;
} stop_signals[] = {{SIGINT, "SIGINT"}, {SIGTERM, "SIGTERM"}, {SIGHUP, "SIGHUP"}};
enum { STOP_SIGNAL_COUNT = sizeof stop_signals / sizeof stop_signals[0] };
_Static_assert(STOP_SIGNAL_COUNT == 3, "g_ignored_at_start has one entry per signal");

static const char *const test_points[] = {"render", "write"};

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
    for (int s = 0; at && s < STOP_SIGNAL_COUNT; s++) {
        const char *short_name = stop_signals[s].name + 3;
        if (strlen(short_name) != name_length || strncmp(name, short_name, name_length))
            continue;
        for (size_t p = 0; p < sizeof test_points / sizeof test_points[0]; p++) {
            if (!strcmp(at + 1, test_points[p])) {
                g_test_signal = stop_signals[s].number;
                g_test_point = test_points[p];
                return true;
            }
        }
    }
    error_set(err, ERR_USAGE, NULL, 0,
              "environment variable PT_TEST_RAISE=%s: expected SIGNAL@POINT with SIGNAL one of "
              "INT, TERM, HUP and POINT one of render, write", value);
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
    if (g_test_signal && !strcmp(point, g_test_point)) {
        int signal_number = g_test_signal;
        g_test_signal = 0;
        raise(signal_number);
    }
}
