/* SPDX-License-Identifier: MIT */
/* render_cmd.h: `pt render`: one image of a scene to EXR and/or PNG. */
#ifndef PT_RENDER_CMD_H
#define PT_RENDER_CMD_H

#include "app/cli.h"

/* Returns the exit status: 0, or 128 + the signal that stopped the render; bad input dies with
 * one line. */
int command_render(const Options *o);

#endif
