// SPDX-License-Identifier: MIT
/* render_units.c: the unit render (dist/render_units.h). The main thread starts one worker thread
 * per device, then only waits: for the workers (a run finished: progress), for the next checkpoint
 * and for the time limit. Workers take runs from the scheduler, render each into their device's
 * film as one block (wavefront_render_block), and move their film into the host's on request (a
 * checkpoint) and at the end. What changes under MPI is in render_units_ranks.c. */
#include "dist/render_units_internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "dist/checkpoint.h"
#include "render/film.h"

/* Moves the device's film into the host's: whole runs only, since a worker flushes between runs. */
static bool flush(Worker *k)
{
    Shared *sh = k->sh;
    const UnitGrid *g = &sh->desc->grid;
    bool any = false;
    for (size_t i = 0; i < unit_bitmap_bytes(g->count) && !any; i++)
        any = k->pending[i] != 0;
    if (!any)
        return true;
    double start = seconds_now();
    Film *film = wavefront_film(k->w);
    film_read_sums(film, k->sums);
    film_clear(film);
    bool ok = unit_film_merge(sh->film, k->sums, k->pending, &k->err);
    memset(k->pending, 0, unit_bitmap_bytes(g->count));
    pthread_mutex_lock(&sh->lock);
    sh->merge_seconds += seconds_now() - start;
    pthread_mutex_unlock(&sh->lock);
    return ok;
}

/* PT_TEST_HOLD_FIRST_RUN=1 (tests only: test_stop_matrix): with a time limit, device threads take
 * their first run only once the limit has passed, the order a loaded machine's slow thread start
 * gives by chance. */
static void hold_first_run(Shared *sh)
{
    const char *hold = getenv("PT_TEST_HOLD_FIRST_RUN");
    if (!hold || strcmp(hold, "1") != 0 || !(sh->desc->time_limit > 0))
        return;
    pthread_mutex_lock(&sh->lock);
    while (!sh->time_up && !sh->stop)
        pthread_cond_wait(&sh->changed, &sh->lock);
    pthread_mutex_unlock(&sh->lock);
}

static void *worker_main(void *arg)
{
    Worker *k = arg;
    Shared *sh = k->sh;
    const UnitGrid *g = &sh->desc->grid;
    hold_first_run(sh);
    for (;;) {
        pthread_mutex_lock(&sh->lock);
        bool stop = sh->stop || units_stop_requested(sh);
        uint64_t request = sh->flush_request;
        pthread_mutex_unlock(&sh->lock);
        if (request > k->flushed) {
            if (!flush(k))
                break;
            pthread_mutex_lock(&sh->lock);
            k->flushed = request;
            pthread_cond_broadcast(&sh->changed);
            pthread_mutex_unlock(&sh->lock);
        }
        UnitRun run;
        if (stop || !units_take_run(k, &run))
            break;
        double start = seconds_now();
        PixelBlock block = unit_run_block(g, run);
        wavefront_render_block(k->w, &block);
        for (uint32_t u = run.first; u < run.first + run.count; u++)
            unit_bitmap_set(k->pending, u);
        units_finish_run(k, run);
        pthread_mutex_lock(&sh->lock);
        k->report->units += run.count;
        k->report->runs++;
        k->report->paths += unit_run_paths(g, run);
        k->last_run_end = seconds_now();
        k->report->busy_seconds += k->last_run_end - start;
        pthread_cond_broadcast(&sh->changed);
        pthread_mutex_unlock(&sh->lock);
        units_test_point(sh, "unit");
    }
    bool ok = !error_is_set(&k->err) && flush(k);
    pthread_mutex_lock(&sh->lock);
    k->failed = !ok;
    if (!ok)
        sh->stop = true;
    k->finished = true;
    sh->running--;
    pthread_cond_broadcast(&sh->changed);
    pthread_mutex_unlock(&sh->lock);
    return NULL;
}

/* Waits on changed until it is signalled or `until` (seconds_now's clock) passes. */
static void wait_until(Shared *sh, double until)
{
    double left = until - seconds_now();
    if (left <= 0)
        return;
    if (left > 3600.0)
        left = 3600.0; /* "never": an hour at a time (a time_t holds no 1e300) */
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    double whole = (double)(time_t)left;
    ts.tv_sec += (time_t)left;
    ts.tv_nsec += (long)((left - whole) * 1e9);
    if (ts.tv_nsec >= 1000000000L)
        ts.tv_sec++, ts.tv_nsec -= 1000000000L;
    int rc = pthread_cond_timedwait(&sh->changed, &sh->lock, &ts);
    (void)rc; /* ETIMEDOUT or a signal of changed: the caller looks at the state either way */
}

bool units_workers_flushed(const Worker *workers, int n, uint64_t request)
{
    for (int i = 0; i < n; i++)
        if (!workers[i].finished && workers[i].flushed < request)
            return false;
    return true;
}

/* ---- the main thread: waits, checkpoints, progress, the time limit ---- */

/* Whether the render holds samples to write: a run finished here or resumed from a checkpoint,
 * or this process has no worker of its own, or ranks take part (their units arrive with their
 * films). */
static bool units_hold_samples(const Shared *sh, const Worker *workers, int n)
{
    if (n == 0 || sh->desc->ranks || sh->film->units_done > 0)
        return true;
    for (int i = 0; i < n; i++)
        if (workers[i].report->units > 0)
            return true;
    return false;
}

typedef struct {
    double start, next_print, next_checkpoint, deadline; /* seconds_now's clock; 1e300: never */
    uint64_t pending_checkpoint; /* the flush request a checkpoint waits for, 0: none */
    uint64_t asked;              /* MPI, ranks other than 0: the film generation rank 0 asked for */
} Supervision;

static Supervision supervision_start(const UnitRenderDesc *d)
{
    double start = seconds_now();
    return (Supervision){
        .start = start,
        .next_print = d->hooks.progress ? start : 1e300,
        .next_checkpoint = d->checkpoint_seconds > 0 ? start + d->checkpoint_seconds : 1e300,
        .deadline = d->time_limit > 0 ? start + d->time_limit : 1e300,
    };
}

/* The next moment the main thread has something to do; under MPI it also polls the link. */
static double next_wake(const Shared *sh, const Supervision *v)
{
    double until = v->next_print < v->next_checkpoint ? v->next_print : v->next_checkpoint;
    if (sh->desc->ranks && until > seconds_now() + RANK_POLL_SECONDS)
        until = seconds_now() + RANK_POLL_SECONDS;
    return until < v->deadline ? until : v->deadline;
}

/* Writes the checkpoint. One that fails (a full disk) costs only what it would have saved: the
 * render goes on and its image is written; the first failure is one warning, later ones are
 * silent (a disk that stays full would say it at every interval). */
static void checkpoint_save(Shared *sh, UnitRenderReport *report)
{
    const UnitRenderDesc *d = sh->desc;
    Error err = {0};
    if (checkpoint_write(d->checkpoint_path, d->identity, sh->film, &err)) {
        report->checkpoints++;
    } else if (!sh->checkpoint_failed) {
        sh->checkpoint_failed = true;
        warn("checkpoint not written, the render goes on without it: %s", err.message);
    }
}

/* A due checkpoint first asks every worker (and every rank) to move its film into the host's, and
 * is written once all have. With sh->lock held. */
static void checkpoint_step(Shared *sh, const Worker *workers, int n, Supervision *v, double now,
                            UnitRenderReport *report)
{
    const UnitRenderDesc *d = sh->desc;
    RankLink *l = d->ranks;
    if (now >= v->next_checkpoint && !v->pending_checkpoint) {
        v->pending_checkpoint = ++sh->flush_request;
        v->next_checkpoint = 1e300;
        if (l) {
            pthread_mutex_unlock(&sh->lock);
            rank_link_request_flush(l, v->pending_checkpoint);
            pthread_mutex_lock(&sh->lock);
        }
    }
    if (!v->pending_checkpoint || !units_workers_flushed(workers, n, v->pending_checkpoint) ||
        (l && !rank_link_flushed(l, v->pending_checkpoint)))
        return;
    pthread_mutex_unlock(&sh->lock);
    checkpoint_save(sh, report);
    pthread_mutex_lock(&sh->lock);
    v->pending_checkpoint = 0;
    v->next_checkpoint = seconds_now() + d->checkpoint_seconds;
    pthread_mutex_unlock(&sh->lock);
    units_test_point(sh, "checkpoint");
    pthread_mutex_lock(&sh->lock);
}

/* With sh->lock held. Under MPI the other ranks' units reach the film at their end: their paths,
 * as they report them, count instead. */
static void print_progress(Shared *sh, const Worker *workers, int n, Supervision *v, double now)
{
    const UnitRenderHooks *h = &sh->desc->hooks;
    const UnitGrid *g = &sh->desc->grid;
    RankLink *l = sh->desc->ranks;
    uint64_t total = (uint64_t)g->width * g->height * g->spp, done = 0;
    for (int i = 0; i < n; i++)
        done += workers[i].report->paths;
    uint32_t spp_done = l ? (uint32_t)((done + rank_link_paths(l)) / ((uint64_t)g->width * g->height))
                          : unit_film_spp_done(sh->film);
    done += l ? rank_link_paths(l) : 0;
    pthread_mutex_unlock(&sh->lock);
    h->progress(h->progress_context, (int)spp_done, (int)g->spp, done, total, now - v->start);
    pthread_mutex_lock(&sh->lock);
    v->next_print = now + h->progress_interval;
}

/* The main thread's loop, until every worker (and under MPI every rank) has ended. */
static bool supervise(Shared *sh, Worker *workers, int n, UnitRenderReport *report, RenderStop *stop,
                      Error *err)
{
    const UnitRenderHooks *h = &sh->desc->hooks;
    Supervision v = supervision_start(sh->desc);
    bool ok = true;
    pthread_mutex_lock(&sh->lock);
    while (ok && (sh->running > 0 || units_ranks_pending(sh))) {
        wait_until(sh, next_wake(sh, &v));
        ok = !sh->desc->ranks || units_serve_ranks(sh, workers, n, &v.asked, err);
        if (!ok)
            break;
        double now = seconds_now();
        if (now >= v.deadline) {
            /* Never due again: a deadline left in the past made next_wake return at once, and
             * the loop spun holding sh->lock, so that no worker could take it to end (with
             * progress lines, print_progress let go of the lock now and then). */
            v.deadline = 1e300;
            sh->time_up = true;
            pthread_cond_broadcast(&sh->changed);
        }
        /* Past the limit the render ends as soon as it holds samples: as the one-device loop
         * (app/render_loop.c) finishes its first pass, a limit shorter than the first run still
         * gives an image (it once gave none, when no unit had finished by then). Workers signal
         * `changed` after each run, which wakes this loop. */
        if (sh->time_up && units_hold_samples(sh, workers, n)) {
            if (!sh->stop)
                *stop = RENDER_STOPPED_BY_TIME_LIMIT;
            sh->stop = true;
        }
        checkpoint_step(sh, workers, n, &v, now, report);
        if (now >= v.next_print)
            print_progress(sh, workers, n, &v, now);
    }
    if (!ok)
        sh->stop = true;
    pthread_mutex_unlock(&sh->lock);
    if (h->progress_end)
        h->progress_end(h->progress_context);
    return ok;
}

/* ---- the phases of render_units_run ---- */

static bool shared_init(Shared *sh, int num_devices, Error *err)
{
    RankLink *l = sh->desc->ranks; /* MPI: rank 0's scheduler serves every rank's devices */
    uint32_t takers = l ? rank_link_devices(l) : (uint32_t)num_devices;
    if (!unit_scheduler_init(&sh->sched, &sh->desc->grid, takers, sh->film->done, err))
        return false;
    pthread_mutex_init(&sh->lock, NULL);
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC); /* wait_until's clock */
    pthread_cond_init(&sh->changed, &attr);
    pthread_condattr_destroy(&attr);
    return true;
}

static void shared_free(Shared *sh)
{
    unit_scheduler_free(&sh->sched);
    pthread_cond_destroy(&sh->changed);
    pthread_mutex_destroy(&sh->lock);
}

/* A worker per device, each with its wavefront, its pending bitmap and its pinned readback; *ok
 * false at the first that fails (the array is returned all the same, for workers_collect). */
static Worker *workers_create(const UnitDevices *devices, Shared *sh, int n,
                              UnitRenderReport *report, bool *ok, Error *err)
{
    const UnitGrid *g = &sh->desc->grid;
    Worker *workers = calloc((size_t)n, sizeof *workers);
    *ok = workers != NULL;
    if (!workers)
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for %d device threads", n);
    for (int i = 0; i < n && *ok; i++) {
        Worker *k = &workers[i];
        SessionDevice *extra = i == 0 ? NULL : &devices->extra[i - 1];
        Device *dev = extra ? &extra->dev : &devices->session->dev;
        const SceneBuffers *buffers = extra ? &extra->buffers : &devices->session->buffers;
        k->sh = sh, k->dev = dev, k->report = &report->device[i];
        k->index = i; /* MPI */
        snprintf(k->report->spec, sizeof k->report->spec, "%d:%d", dev->platform_index, dev->device_index);
        snprintf(k->report->name, sizeof k->report->name, "%s", dev->name);
        k->w = wavefront_create(dev, &devices->session->scene, buffers, &sh->desc->settings, err);
        k->pending = calloc(unit_bitmap_bytes(g->count), 1);
        if (k->w)
            k->sums = device_pinned_alloc(dev, "film_readback", sh->film->num_pixels * FILM_BYTES_PER_PIXEL,
                                          &k->sums_buffer, err);
        *ok = k->w && k->pending && k->sums;
        if (*ok)
            k->appetite = unit_grid_units_per_window(g, wavefront_stats(k->w)->config.window_size);
        else if (!error_is_set(err))
            error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for device %s's film",
                      k->report->spec);
    }
    return workers;
}

/* Starts a thread per worker; returns how many started (all, unless one fails: then the started
 * ones are told to stop). */
static int workers_start(Worker *workers, int n, Shared *sh, Error *err)
{
    for (int i = 0; i < n; i++) {
        sh->running++;
        if (pthread_create(&workers[i].thread, NULL, worker_main, &workers[i]) != 0) {
            sh->running--;
            error_set(err, ERR_SYSTEM, NULL, 0, "cannot start a thread for device %s: %s",
                      workers[i].report->spec, strerror(errno));
            pthread_mutex_lock(&sh->lock);
            sh->stop = true;
            pthread_mutex_unlock(&sh->lock);
            return i;
        }
    }
    return n;
}

/* After the threads have ended: a failed worker's error, every device's counters into stats, and
 * the wavefronts freed. Returns when the last run was rendered (start when none was). */
static double workers_collect(Worker *workers, int n, double start, RenderStats *stats, bool *ok,
                              Error *err)
{
    double end = start;
    for (int i = 0; i < n && workers; i++) {
        Worker *k = &workers[i];
        if (k->last_run_end > end)
            end = k->last_run_end;
        if (k->failed && *ok) {
            *err = k->err;
            *ok = false;
        }
        if (k->w) {
            wavefront_read_counters(k->w);
            const RenderStats *s = wavefront_stats(k->w);
            render_stats_add(stats, s);
            if (i == 0)
                stats->config.pool_size = s->config.pool_size,
                stats->config.window_size = s->config.window_size;
            wavefront_destroy(k->w);
        }
        free(k->pending);
        device_pinned_free(k->dev, k->sums_buffer, k->sums);
    }
    free(workers);
    return end;
}

/* Why the render ended, and the checkpoint a stopped render leaves for --resume. */
static bool render_end(Shared *sh, bool ok, RenderStats *stats, RenderStop *stop,
                       UnitRenderReport *report)
{
    const UnitRenderDesc *d = sh->desc;
    stats->spp_done = (int)unit_film_spp_done(sh->film);
    if (ok && units_is_root(sh) && *stop == RENDER_COMPLETE && !unit_film_complete(sh->film))
        *stop = RENDER_STOPPED_BY_SIGNAL;
    if (ok && d->checkpoint_path && *stop != RENDER_COMPLETE)
        checkpoint_save(sh, report);
    return ok;
}

bool render_units_run(const UnitDevices *devices, const UnitRenderDesc *desc, UnitFilm *film,
                      RenderStats *stats, RenderStop *stop, UnitRenderReport *report, Error *err)
{
    memset(report, 0, sizeof *report);
    memset(stats, 0, sizeof *stats);
    *stop = RENDER_COMPLETE;
    int n = 1 + devices->num_extra;
    report->units_resumed = film->units_done;
    Shared sh = {.desc = desc, .film = film, .running = 0};
    if (!shared_init(&sh, n, err))
        return false;
    bool ok;
    Worker *workers = workers_create(devices, &sh, n, report, &ok, err);
    report->num_devices = n;
    double start = seconds_now();
    int started = ok ? workers_start(workers, n, &sh, err) : 0;
    ok = ok && started == n;
    if (started > 0 && !supervise(&sh, workers, started, report, stop, err))
        ok = false;
    for (int i = 0; i < started; i++)
        pthread_join(workers[i].thread, NULL);
    /* Rendering time, as the one-device render's: to the last run rendered; moving the films into
     * the host's is report->merge_seconds (the one-device render reads its film after its loop
     * too). */
    stats->seconds = workers_collect(workers, n, start, stats, &ok, err) - start;
    report->merge_seconds = sh.merge_seconds;
    ok = units_end_ranks(&sh, report, stats, ok, err);
    ok = render_end(&sh, ok, stats, stop, report);
    shared_free(&sh);
    return ok;
}
