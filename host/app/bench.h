/* SPDX-License-Identifier: MIT */
/* bench.h: `pt bench`: throughput of the wavefront on one scene and device (bench.c), and of the
 * unit render on one or several devices (bench_units.c). */
#ifndef PT_BENCH_H
#define PT_BENCH_H

#include <stddef.h>
#include <stdio.h>

#include "app/cli.h"
#include "render/session.h"
#include "render/wavefront.h"

int command_bench(const Options *o);

/* The unit modes: "units" (the session's device alone through the unit scheduler, alternated
 * with the default mode's plain render: the best of UNIT_BENCH_REPEATS of each) and, when list
 * holds several devices, "units-all" (the session's device is list->spec[0]; the others are opened
 * here). rgb: room for the film, for the plain renders. */
#define UNIT_BENCH_REPEATS 3
void bench_units(Session *s, const Options *o, const DeviceSpecList *list, RenderSettings settings,
                 float *rgb);

/* Shared by both: a plain render (wavefront_render); a CSV file opened to append (its header
 * written when it is new); a row of the table; a row of the --csv file; FILE.csv ->
 * FILE_<suffix>.csv. */
RenderStats bench_render(Session *s, RenderSettings settings, float *rgb);
FILE *bench_open_csv(const char *path, const char *header);
void bench_print_row(const char *label, const RenderStats *st);
void bench_append_csv(const char *path, const Session *s, const char *mode, const RenderStats *st);
void bench_sibling_path(char *out, size_t size, const char *csv, const char *suffix);

#endif
