// SPDX-License-Identifier: MIT
#include "app/render_cmd_units.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/render_loop.h"
#include "app/stop_signals.h"
#include "base/fs.h"
#include "dist/checkpoint.h"
#include "dist/mpi_link.h"
#include "dist/render_ranks.h"
#include "render/film.h"

bool render_cmd_wants_units(const Options *o)
{
    return mpi_link_size() > 1 || device_spec_is_list(o->device) || o->checkpoint_seconds > 0 ||
           o->resume || o->unit_spp || o->unit_rows;
}

bool render_cmd_units_devices(const Options *o, DeviceSpecList *list, Error *err)
{
    if (device_spec_is_list(o->device))
        return device_spec_list(o->device, list, err);
    memset(list, 0, sizeof *list);
    return true; /* the session's device alone */
}

/* What the unit render cannot do (yet): decisions per pixel over the whole film. */
static bool check_supported(const Options *o, const RenderSettings *s, Error *err)
{
    const char *what = mpi_link_size() > 1             ? "several MPI ranks"
                       : device_spec_is_list(o->device) ? "--device with several devices"
                       : o->checkpoint_seconds > 0      ? "--checkpoint"
                       : o->resume                      ? "--resume"
                                                        : "--unit-spp/--unit-rows";
    if (s->noise_threshold > 0.0f) {
        error_set(err, ERR_USAGE, NULL, 0,
                  "%s: adaptive sampling (--noise-threshold or the scene's render.noise_threshold) "
                  "decides over the whole film and runs on one device without work units: drop %s "
                  "(or the scene's noise_threshold)", what, what);
        return false;
    }
    if (s->moments) {
        error_set(err, ERR_USAGE, NULL, 0,
                  "%s: the variance layer (--aov variance) needs the film's second moments, which "
                  "only a one-device render without work units keeps", what);
        return false;
    }
    return true;
}

/* The unit render's hooks (dist/render_units.h): pt render's stop signals, test points and
 * progress lines, the same as its one-device loop's. */
static void print_progress(void *style, int spp_done, int spp, uint64_t done, uint64_t total,
                           double elapsed)
{
    render_loop_print_progress(*(const ProgressStyle *)style, spp_done, spp, done, total, elapsed);
}

static void end_progress(void *style)
{
    if (*(const ProgressStyle *)style == PROGRESS_TERMINAL)
        fputc('\n', stderr); /* below the line rewritten in place */
}

static UnitRenderHooks unit_hooks(ProgressStyle *style)
{
    bool shown = *style != PROGRESS_NONE;
    return (UnitRenderHooks){.stop_requested = stop_signal_received,
                             .stop_name = stop_signal_name,
                             .progress = shown ? print_progress : NULL,
                             .progress_end = end_progress,
                             .progress_context = style,
                             .progress_interval = render_loop_update_interval(*style),
                             .test_point = stop_signals_test_point};
}

/* The end of a unit render, on stderr: the units, each device's share and speed, the merge. */
static void print_report(const UnitRenderDesc *ud, const UnitRenderReport *report,
                         const char *checkpoint)
{
    fprintf(stderr, "pt: %u work units (%u tiles x %u sample blocks of %u spp)%s\n",
            ud->grid.count, ud->grid.tiles, ud->grid.blocks, ud->grid.unit_spp,
            report->units_resumed ? ", some from the checkpoint" : "");
    for (int i = 0; i < report->num_devices; i++) {
        const UnitDeviceReport *r = &report->device[i];
        fprintf(stderr, "pt: device %s %s: %u units in %u runs, %.2f Mpaths/s busy\n", r->spec,
                r->name, r->units, r->runs,
                r->busy_seconds > 0 ? r->paths / r->busy_seconds * 1e-6 : 0.0);
    }
    fprintf(stderr, "pt: device films merged into the host's in %.1f ms\n",
            report->merge_seconds * 1e3);
    if (ud->ranks)
        rank_link_print_report(ud->ranks, stderr);
    if (report->checkpoints)
        fprintf(stderr, "pt: %u checkpoints written to %s\n", report->checkpoints, checkpoint);
}

/* The list's devices after the first (the session's own); *num_extra: those opened, which the
 * caller closes whether *ok or not. */
static SessionDevice *open_extra_devices(const Options *o, Session *session,
                                         const DeviceSpecList *list, bool quiet, int *num_extra,
                                         bool *ok, Error *err)
{
    SessionDevice *extra = list->count > 1 ? calloc((size_t)list->count - 1, sizeof *extra) : NULL;
    *ok = list->count <= 1 || extra;
    if (!*ok)
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for %d devices", list->count);
    for (int i = 1; i < list->count && *ok; i++) {
        *ok = session_device_open(&extra[i - 1], &session->scene, list->spec[i], o->no_cache, err);
        if (*ok) {
            (*num_extra)++;
            if (!quiet)
                fprintf(stderr, "pt: device %s %s (%s, driver %s)\n", list->spec[i],
                        extra[i - 1].dev.name, extra[i - 1].dev.platform_name,
                        extra[i - 1].dev.driver_version);
        }
    }
    return extra;
}

bool render_cmd_units_run(const Options *o, Session *session, const DeviceSpecList *list,
                          const RenderSettings *settings, const char *checkpoint_base,
                          RenderImages *images, RenderStats *stats, RenderStop *stop, Error *err)
{
    if (!check_supported(o, settings, err))
        return false;
    /* MPI: rank 0 alone reports, keeps the checkpoint and watches the time; the others render. */
    bool mpi = mpi_link_size() > 1, root = mpi_link_rank() == 0, quiet = o->quiet || !root;
    const SceneDesc *desc = &session->scene.desc;
    ProgressStyle progress = render_loop_progress_style(quiet, o->progress, isatty(STDERR_FILENO));
    UnitRenderDesc ud = {.settings = *settings,
                         .hooks = unit_hooks(&progress),
                         .time_limit = root ? o->time_limit : 0.0,
                         .checkpoint_seconds = root ? o->checkpoint_seconds : 0.0,
                         .resume = o->resume && root,
                         .report_devices = !quiet};
    if (!unit_grid_init(&ud.grid, (uint32_t)desc->width, (uint32_t)desc->height,
                        (uint32_t)settings->spp, (uint32_t)o->unit_spp, (uint32_t)o->unit_rows, err))
        return false;
    char checkpoint[1200];
    if (mpi) /* every rank's, compared by rank_link_open */
        ud.identity = render_identity(&session->scene, settings, &ud.grid);
    if (root && (o->checkpoint_seconds > 0 || o->resume)) {
        checkpoint_path(checkpoint_base, checkpoint, sizeof checkpoint);
        ud.checkpoint_path = checkpoint;
        ud.identity = render_identity(&session->scene, settings, &ud.grid);
        fs_remove_stale_temps(checkpoint); /* a checkpoint write SIGKILLed earlier */
        /* Never overwrite a checkpoint the user did not ask to continue. */
        if (!o->resume && fs_exists(checkpoint)) {
            error_set(err, ERR_OUTPUT, checkpoint, 0,
                      "%s exists: continue it with --resume, or remove it to start over", checkpoint);
            return false;
        }
    }
    UnitFilm film;
    if (!unit_film_init(&film, &ud.grid, err))
        return false;
    if (ud.resume && !checkpoint_read(checkpoint, ud.identity, &film, err)) {
        unit_film_free(&film);
        return false;
    }
    if (ud.resume && !quiet)
        fprintf(stderr, "pt: resuming %s: %u of %u work units done\n", checkpoint, film.units_done,
                ud.grid.count);

    int num_extra = 0;
    bool ok;
    SessionDevice *extra = open_extra_devices(o, session, list, quiet, &num_extra, &ok, err);
    UnitRenderReport report;
    UnitDevices devices = {.session = session, .extra = extra, .num_extra = num_extra};
    if (ok && mpi) {
        ud.ranks = rank_link_open(&ud.grid, settings, ud.identity.scene, 1 + num_extra, err);
        if (!ud.ranks)
            mpi_link_finalize(); /* every rank refuses: none is left waiting, no abort needed */
        ok = ud.ranks != NULL;
    }
    if (ok)
        ok = render_units_run(&devices, &ud, &film, stats, stop, &report, err);
    if (ok && root) {
        film_sums_to_rgb(film.sums, film.num_pixels, images->rgb);
        if (images->layer[AOV_LAYER_SPP])
            for (size_t i = 0; i < film.num_pixels; i++)
                images->layer[AOV_LAYER_SPP][i] = (float)film.sums[FILM_WORDS * i + 3];
        if (!quiet)
            print_report(&ud, &report, checkpoint);
    }
    rank_link_close(ud.ranks);
    for (int i = 0; i < num_extra; i++)
        session_device_close(&extra[i]);
    free(extra);
    unit_film_free(&film);
    return ok;
}

void render_cmd_units_remove_checkpoint(const Options *o, const char *checkpoint_base)
{
    if (o->checkpoint_seconds <= 0 && !o->resume)
        return;
    char checkpoint[1200];
    checkpoint_path(checkpoint_base, checkpoint, sizeof checkpoint);
    unlink(checkpoint);
}
