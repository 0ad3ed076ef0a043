/* SPDX-License-Identifier: MIT */
/* tonemap_cmd.h: `pt tonemap IN.exr -o OUT.png [--tonemap OP] [--exposure EV] [--bloom S[,R]]`:
 * displays a render's EXR again (its linear beauty R, G, B) through the same bloom and display
 * curve as `pt render`'s PNG, so trying six curves costs six reads, not six renders. */
#ifndef PT_TONEMAP_CMD_H
#define PT_TONEMAP_CMD_H

#include "app/options.h"

/* Exit status 0, or dies with one line naming the file. */
int command_tonemap(const Options *o);

#endif
