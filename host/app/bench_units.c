// SPDX-License-Identifier: MIT
/* pt bench's unit modes (app/bench.h): the render `pt render` does with --device all, a device
 * list or --unit-spp/--unit-rows (dist/render_units.h: a host thread per device taking runs of work
 * units from one scheduler, one host film), timed like the other modes. "units" is the session's
 * device alone through the scheduler, alternated with the "default" mode's plain render of the
 * same settings and the best of a few of each kept (a shared machine's load changes from one
 * render to the next): their ratio is the scheduler's cost on one device. "units-all" is every
 * device of the list; its devices' units, runs and Mpaths/s while busy go to the table and
 * FILE_units.csv. */
#include "app/bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dist/render_units.h"

static void run_units(Session *s, SessionDevice *extra, int num_extra, const UnitGrid *grid,
                      RenderSettings settings, RenderStats *stats, UnitRenderReport *report)
{
    UnitDevices devices = {.session = s, .extra = extra, .num_extra = num_extra};
    UnitRenderDesc desc = {.settings = settings, .grid = *grid}; /* no hooks: no progress */
    UnitFilm film;
    RenderStop stop;
    Error err = {0};
    if (!unit_film_init(&film, grid, &err) ||
        !render_units_run(&devices, &desc, &film, stats, &stop, report, &err))
        die("%s", err.message);
    if (stop != RENDER_COMPLETE)
        die("pt bench: the unit render stopped early");
    stats->spp_done = (int)grid->spp;
    unit_film_free(&film);
}

static void append_devices_csv(const char *csv, const Session *s, const char *mode,
                               const UnitRenderReport *report)
{
    char path[4096];
    bench_sibling_path(path, sizeof path, csv, "units");
    FILE *f = bench_open_csv(path, "mode,device_spec,device,scene,width,height,spp,units,runs,"
                                   "paths,busy_seconds,mpaths_per_s_busy\n");
    for (int i = 0; i < report->num_devices; i++) {
        const UnitDeviceReport *r = &report->device[i];
        fprintf(f, "%s,%s,\"%s\",\"%s\",%d,%d,%d,%u,%u,%llu,%.6f,%.3f\n", mode, r->spec, r->name,
                s->scene.desc.path, s->scene.desc.width, s->scene.desc.height, s->scene.desc.spp,
                r->units, r->runs, (unsigned long long)r->paths, r->busy_seconds,
                r->busy_seconds > 0 ? r->paths / r->busy_seconds * 1e-6 : 0.0);
    }
    fclose(f);
}

static void print_devices(const UnitRenderReport *report)
{
    for (int i = 0; i < report->num_devices; i++) {
        const UnitDeviceReport *r = &report->device[i];
        printf("  device %-5s %-40.40s %7u units %6u runs %10.2f Mpaths/s busy\n", r->spec,
               r->name, r->units, r->runs,
               r->busy_seconds > 0 ? r->paths / r->busy_seconds * 1e-6 : 0.0);
    }
}

void bench_units(Session *s, const Options *o, const DeviceSpecList *list, RenderSettings settings,
                 float *rgb)
{
    const SceneDesc *d = &s->scene.desc;
    UnitGrid grid;
    Error err = {0};
    if (!unit_grid_init(&grid, (uint32_t)d->width, (uint32_t)d->height, (uint32_t)settings.spp,
                        (uint32_t)o->unit_spp, (uint32_t)o->unit_rows, &err))
        die("%s", err.message);
    int num_extra = list->count > 1 ? list->count - 1 : 0;
    SessionDevice *extra = num_extra ? calloc((size_t)num_extra, sizeof *extra) : NULL;
    if (num_extra && !extra)
        die("out of memory for %d devices", num_extra);
    for (int i = 0; i < num_extra; i++)
        if (!session_device_open(&extra[i], &s->scene, list->spec[i + 1], o->no_cache, &err))
            die("%s", err.message);
    /* Warm-up on every device (compilation and first launches stay out of the figures). */
    RenderStats stats;
    UnitRenderReport report;
    UnitGrid warm;
    if (!unit_grid_init(&warm, grid.width, grid.height, 2 * (uint32_t)(1 + num_extra), 1,
                        grid.unit_rows, &err))
        die("%s", err.message);
    RenderSettings warm_settings = settings;
    warm_settings.spp = (int)warm.spp;
    run_units(s, extra, num_extra, &warm, warm_settings, &stats, &report);

    printf("unit modes: %u work units (%u tiles of %u rows x %u sample blocks of %u spp)\n",
           grid.count, grid.tiles, grid.unit_rows, grid.blocks, grid.unit_spp);
    RenderStats plain = {.seconds = 1e300}, best = {.seconds = 1e300};
    UnitRenderReport best_report = {0};
    for (int r = 0; r < UNIT_BENCH_REPEATS; r++) {
        RenderStats p = bench_render(s, settings, rgb);
        if (p.seconds < plain.seconds)
            plain = p;
        run_units(s, NULL, 0, &grid, settings, &stats, &report);
        if (stats.seconds < best.seconds)
            best = stats, best_report = report;
    }
    stats = best, report = best_report;
    bench_print_row("units", &stats);
    printf("  one device through the scheduler: %.1f%% of the default mode's Mpaths/s (%.3f vs "
           "%.3f, best of %d alternating renders each)\n",
           100.0 * plain.seconds / stats.seconds, stats.paths / stats.seconds * 1e-6,
           plain.paths / plain.seconds * 1e-6, UNIT_BENCH_REPEATS);
    print_devices(&report);
    if (o->csv) {
        bench_append_csv(o->csv, s, "units", &stats);
        append_devices_csv(o->csv, s, "units", &report);
    }
    if (num_extra) {
        run_units(s, extra, num_extra, &grid, settings, &stats, &report);
        bench_print_row("units-all", &stats);
        print_devices(&report);
        if (o->csv) {
            bench_append_csv(o->csv, s, "units-all", &stats);
            append_devices_csv(o->csv, s, "units-all", &report);
        }
    }
    for (int i = 0; i < num_extra; i++)
        session_device_close(&extra[i]);
    free(extra);
}
