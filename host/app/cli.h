/* SPDX-License-Identifier: MIT */
/* cli.h: the command line of shared/DESIGN.md, parsed into one options struct (zero = default). */
#ifndef PT_CLI_H
#define PT_CLI_H

#include <stdbool.h>

#include "base/error.h"
#include "app/options.h"
#include "render/session.h"
#include "render/wavefront.h"
#include "viewer/viewer.h"


/* Parses argv; returns false with ERR_USAGE naming the offending argument (or an option the
 * command does not take: app/cli_options.c lists who takes what). */
bool cli_parse(int argc, char **argv, Options *out, Error *err);
void cli_print_help(void);
/* The parts of the options that the render core and the viewer take. */
RenderDesc cli_render_desc(const Options *o);
/* The render settings the options ask for; the scene's part (spp, depth, material sorting) is
 * settled by session_settle_settings once the scene is open. */
RenderSettings cli_render_settings(const Options *o);
ViewerDesc cli_viewer_desc(const Options *o);

#endif
