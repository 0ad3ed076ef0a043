/* SPDX-License-Identifier: MIT */
/* viewer.h: 'pt view', the interactive window: progressive rendering of the scene with camera
 * controls (keys: viewer_input.h). */
#ifndef PT_VIEWER_H
#define PT_VIEWER_H

#include "cli.h"

/* Runs the window until Esc, closing it, or o->frames frames; returns the exit status. Without a
 * display it ends with one line pointing to 'pt render' and status 1. */
int command_view(const Options *o);

#endif
