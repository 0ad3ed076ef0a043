/* SPDX-License-Identifier: MIT */
/* bench.h: `pt bench`: throughput of the wavefront on one scene and device (bench.c), and of the
 * unit render on one or several devices (bench_units.c). */
#ifndef PT_BENCH_H
#define PT_BENCH_H

#include <stddef.h>

#include "app/cli.h"
#include "render/session.h"
#include "render/wavefront.h"

int command_bench(const Options *o);

/* The unit modes: "units" (the session's device alone through the unit scheduler; plain: the
 * default mode's stats, to compare) and, when list holds several devices, "units-all" (the
 * session's device is list->spec[0]; the others are opened here). */
void bench_units(Session *s, const Options *o, const DeviceSpecList *list, RenderSettings settings,
                 const RenderStats *plain);

/* Shared by both: a row of the table, a row of the --csv file, FILE.csv -> FILE_<suffix>.csv. */
void bench_print_row(const char *label, const RenderStats *st);
void bench_append_csv(const char *path, const Session *s, const char *mode, const RenderStats *st);
void bench_sibling_path(char *out, size_t size, const char *csv, const char *suffix);

#endif
