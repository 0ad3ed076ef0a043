/* SPDX-License-Identifier: MIT */
/* stop_signals.h: SIGINT, SIGTERM and SIGHUP end `pt render` without losing the image: the
 * handler only records the signal; the render stops after the window in flight, the image so far
 * is written (a write in progress finishes: its temporary file is renamed, never left behind),
 * and pt exits with 128 + the signal: 130 (SIGINT), 143 (SIGTERM), 129 (SIGHUP). Repeated
 * signals change nothing (sigaction without SA_RESETHAND: a second Ctrl-C does not kill). A
 * signal that pt was started ignoring (nohup) stays ignored.
 *
 * PT_TEST_RAISE=SIGNAL@POINT[:COUNT] (tests only) makes pt raise the signal itself the COUNT-th
 * time (default 1) it reaches a point it names: "render" (a window of samples done), "write" (a
 * file's temporary copy complete, not yet renamed), "unit" (a run of work units rendered, from
 * any device's thread) or "checkpoint" (a periodic checkpoint written), so that tests reach those
 * moments without timing. SIGNAL is INT, TERM, HUP (with or without SIG) or KILL: a crash, for
 * the checkpoint tests (PT_TEST_RAISE=SIGKILL@unit:5). */
#ifndef PT_STOP_SIGNALS_H
#define PT_STOP_SIGNALS_H

#include <stdbool.h>

#include "base/error.h"

/* Call first, before OpenCL starts (PoCL changes some dispositions): notes the signals pt was
 * started ignoring, reads and checks PT_TEST_RAISE (false with ERR_USAGE when malformed). */
bool stop_signals_configure(Error *err);
/* Installs the handlers (from here on, the signals stop the render instead of killing pt). */
void stop_signals_install(void);
/* The first signal received since stop_signals_install, 0 when none. Async-signal-safe. */
int stop_signal_received(void);
/* "SIGINT", "SIGTERM", "SIGHUP". */
const char *stop_signal_name(int signal_number);
/* 128 + the signal received, 0 when none. */
int stop_exit_status(void);
/* Raises PT_TEST_RAISE's signal when `point` is its point, reached for the COUNT-th time (once;
 * thread-safe). */
void stop_signals_test_point(const char *point);

#endif
