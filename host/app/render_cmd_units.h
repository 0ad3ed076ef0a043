/* SPDX-License-Identifier: MIT */
/* render_cmd_units.h: the part of `pt render` that renders through work units
 * (dist/render_units.h): when it is taken, what it refuses, the extra devices, the checkpoint beside
 * the output, and the image from the host's film. */
#ifndef PT_RENDER_CMD_UNITS_H
#define PT_RENDER_CMD_UNITS_H

#include <stdbool.h>

#include "app/cli.h"
#include "app/render_output.h"
#include "dist/render_units.h"

/* Whether the command line asks for the unit render: several devices, checkpoints, a unit size. */
bool render_cmd_wants_units(const Options *o);

/* Before the session: the first device of a list (the session's own) into *first_spec. */
bool render_cmd_units_devices(const Options *o, DeviceSpecList *list, Error *err);

/* Renders through units on the session's device and the rest of list; checkpoint_base names the
 * output the checkpoint sits beside (OUTPUT.ptckpt). images->rgb (and the spp layer) get the
 * film. */
bool render_cmd_units_run(const Options *o, Session *session, const DeviceSpecList *list,
                          const RenderSettings *settings, const char *checkpoint_base,
                          RenderImages *images, RenderStats *stats, RenderStop *stop, Error *err);
/* Once the image of a complete render is written (not before: a crash in between would lose both):
 * removes its checkpoint, if it has one. */
void render_cmd_units_remove_checkpoint(const Options *o, const char *checkpoint_base);

#endif
