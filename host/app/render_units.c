// SPDX-License-Identifier: MIT
/* render_units.c: the unit render (app/render_units.h). The main thread starts one worker thread
 * per device, then only waits: for the workers (a run finished: progress), for the next checkpoint
 * and for the time limit. Workers take runs from the scheduler, render each into their device's
 * film as one block (wavefront_render_block), and move their film into the host's on request (a
 * checkpoint) and at the end. */
#include "app/render_units.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/render_ranks.h"
#include "app/stop_signals.h"
#include "base/clock.h"
#include "dist/checkpoint.h"
#include "render/film.h"

typedef struct Shared Shared;

typedef struct {
    Shared *sh;
    int index; /* MPI: its slot in the link to rank 0 */
    Device *dev;
    Wavefront *w;
    uint32_t appetite;   /* the most units a run may hold: about one window of the device */
    uint8_t *pending;    /* units in the device's film, not yet in the host's */
    uint64_t *sums;      /* the device film, read back (pinned: device_pinned_alloc) */
    cl_mem sums_buffer;
    uint64_t flushed;    /* the last flush request served */
    double last_run_end; /* seconds_now() when its last run was rendered */
    bool finished;
    bool failed;
    Error err;
    UnitDeviceReport *report;
    pthread_t thread;
} Worker;

struct Shared {
    pthread_mutex_t lock;
    pthread_cond_t changed; /* a run finished, a flush was served, a worker ended */
    const UnitRenderDesc *desc;
    UnitScheduler sched;
    UnitFilm *film;
    bool stop;              /* take no new runs (a signal, the time limit, a failure) */
    uint64_t flush_request; /* workers with flushed below it move their film to the host's */
    int running;
    double merge_seconds;
};

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

/* ---- MPI (app/render_ranks.h): on ranks other than 0, runs come from rank 0 ---- */

static bool take_run(Worker *k, UnitRun *run)
{
    Shared *sh = k->sh;
    RankLink *l = sh->desc->ranks;
    if (!l || rank_link_is_root(l))
        return unit_scheduler_take(&sh->sched, k->appetite, run);
    rank_link_ask(l, k->index, k->appetite);
    pthread_mutex_lock(&sh->lock);
    pthread_cond_broadcast(&sh->changed); /* the main thread sends the request */
    pthread_mutex_unlock(&sh->lock);
    return rank_link_answer(l, k->index, run);
}

static void finish_run(Worker *k, UnitRun run)
{
    RankLink *l = k->sh->desc->ranks;
    if (l && !rank_link_is_root(l))
        rank_link_finished(l, k->index, run, unit_run_paths(&k->sh->desc->grid, run));
    else
        unit_scheduler_finish(&k->sh->sched, run);
    if (l)
        rank_link_test_kill(l, run.count, false);
}

/* ---- end of MPI ---- */

static void *worker_main(void *arg)
{
    Worker *k = arg;
    Shared *sh = k->sh;
    const UnitGrid *g = &sh->desc->grid;
    for (;;) {
        pthread_mutex_lock(&sh->lock);
        bool stop = sh->stop || stop_signal_received();
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
        if (stop || !take_run(k, &run))
            break;
        double start = seconds_now();
        PixelBlock block = unit_run_block(g, run);
        wavefront_render_block(k->w, &block);
        for (uint32_t u = run.first; u < run.first + run.count; u++)
            unit_bitmap_set(k->pending, u);
        finish_run(k, run);
        pthread_mutex_lock(&sh->lock);
        k->report->units += run.count;
        k->report->runs++;
        k->report->paths += unit_run_paths(g, run);
        k->last_run_end = seconds_now();
        k->report->busy_seconds += k->last_run_end - start;
        pthread_cond_broadcast(&sh->changed);
        pthread_mutex_unlock(&sh->lock);
        stop_signals_test_point("unit");
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

static bool all_flushed(const Worker *workers, int n, uint64_t request)
{
    for (int i = 0; i < n; i++)
        if (!workers[i].finished && workers[i].flushed < request)
            return false;
    return true;
}

/* MPI (app/render_ranks.h): the main thread, between its waits: rank 0 answers the other ranks;
 * another rank relays its threads' requests, and sends its film when rank 0 asks for it
 * (*asked: the generation, until sent). Called and returns with sh->lock held. */
static bool serve_ranks(Shared *sh, Worker *workers, int n, uint64_t *asked, Error *err)
{
    RankLink *l = sh->desc->ranks;
    bool ok;
    if (rank_link_is_root(l)) {
        int sig = stop_signal_received();
        bool stop = sh->stop || sig;
        pthread_mutex_unlock(&sh->lock);
        ok = rank_link_serve(l, &sh->sched, sh->film, stop, err);
        pthread_mutex_lock(&sh->lock);
        if (ok && sig && !rank_link_all_final(l)) {
            /* mpirun sends SIGTERM to every rank when one dies: this image would lack its units. */
            char missing[256];
            rank_link_missing(l, missing, sizeof missing);
            error_set(err, ERR_USAGE, NULL, 0,
                      "rank 0: stopped by %s before rank(s) %s sent their film (a rank that dies "
                      "makes mpirun stop the others): no image is written", stop_signal_name(sig),
                      missing);
            ok = false;
        }
        return ok;
    }
    uint64_t request = sh->flush_request;
    pthread_mutex_unlock(&sh->lock);
    ok = rank_link_pump(l, &request, err);
    pthread_mutex_lock(&sh->lock);
    if (request > sh->flush_request) {
        sh->flush_request = *asked = request;
        pthread_cond_broadcast(&sh->changed);
    }
    if (ok && *asked && all_flushed(workers, n, *asked)) {
        uint64_t generation = *asked;
        *asked = 0;
        pthread_mutex_unlock(&sh->lock);
        ok = rank_link_send_film(l, sh->film, generation, NULL, NULL, err);
        pthread_mutex_lock(&sh->lock);
    }
    return ok;
}

/* The main thread's loop: progress, checkpoints, the time limit, until every worker has ended. */
static bool supervise(Shared *sh, Worker *workers, int n, UnitRenderReport *report, RenderStop *stop,
                      Error *err)
{
    const UnitRenderDesc *d = sh->desc;
    const UnitGrid *g = &d->grid;
    double start = seconds_now(), interval = render_loop_update_interval(d->progress);
    double next_print = d->progress == PROGRESS_NONE ? 1e300 : start;
    double next_checkpoint = d->checkpoint_seconds > 0 ? start + d->checkpoint_seconds : 1e300;
    double deadline = d->time_limit > 0 ? start + d->time_limit : 1e300;
    uint64_t total = (uint64_t)g->width * g->height * g->spp, pending_checkpoint = 0;
    bool ok = true;
    RankLink *l = d->ranks;          /* MPI */
    bool root = !l || rank_link_is_root(l);
    uint64_t asked = 0;
    pthread_mutex_lock(&sh->lock);
    while (sh->running > 0 || (l && root && !rank_link_all_final(l))) {
        double until = next_print < next_checkpoint ? next_print : next_checkpoint;
        if (l && until > seconds_now() + RANK_POLL_SECONDS)
            until = seconds_now() + RANK_POLL_SECONDS;
        wait_until(sh, until < deadline ? until : deadline);
        if (l && !serve_ranks(sh, workers, n, &asked, err)) {
            ok = false;
            sh->stop = true;
            break;
        }
        double now = seconds_now();
        if (now >= deadline && !sh->stop) {
            sh->stop = true;
            *stop = RENDER_STOPPED_BY_TIME_LIMIT;
        }
        if (now >= next_checkpoint && !pending_checkpoint) {
            pending_checkpoint = ++sh->flush_request;
            next_checkpoint = 1e300;
            if (l) {
                pthread_mutex_unlock(&sh->lock);
                rank_link_request_flush(l, pending_checkpoint);
                pthread_mutex_lock(&sh->lock);
            }
        }
        if (pending_checkpoint && all_flushed(workers, n, pending_checkpoint) &&
            (!l || rank_link_flushed(l, pending_checkpoint))) {
            pthread_mutex_unlock(&sh->lock);
            ok = checkpoint_write(d->checkpoint_path, d->identity, sh->film, err);
            pthread_mutex_lock(&sh->lock);
            if (!ok) {
                sh->stop = true;
                break;
            }
            report->checkpoints++;
            pending_checkpoint = 0;
            next_checkpoint = seconds_now() + d->checkpoint_seconds;
            pthread_mutex_unlock(&sh->lock);
            stop_signals_test_point("checkpoint");
            pthread_mutex_lock(&sh->lock);
        }
        if (now >= next_print) {
            uint64_t done = 0;
            for (int i = 0; i < n; i++)
                done += workers[i].report->paths;
            /* Under MPI the other ranks' units reach the film at their end: count their paths. */
            uint32_t spp_done =
                l ? (uint32_t)((done + rank_link_paths(l)) / ((uint64_t)g->width * g->height))
                  : unit_film_spp_done(sh->film);
            done += l ? rank_link_paths(l) : 0;
            pthread_mutex_unlock(&sh->lock);
            render_loop_print_progress(d->progress, (int)spp_done, (int)g->spp, done, total,
                                       now - start);
            pthread_mutex_lock(&sh->lock);
            next_print = now + interval;
        }
    }
    pthread_mutex_unlock(&sh->lock);
    if (d->progress == PROGRESS_TERMINAL)
        fputc('\n', stderr);
    return ok;
}

bool render_units_run(const UnitDevices *devices, const UnitRenderDesc *desc, UnitFilm *film,
                      RenderStats *stats, RenderStop *stop, UnitRenderReport *report, Error *err)
{
    memset(report, 0, sizeof *report);
    memset(stats, 0, sizeof *stats);
    *stop = RENDER_COMPLETE;
    const UnitGrid *g = &desc->grid;
    int n = 1 + devices->num_extra;
    report->units_resumed = film->units_done;
    Shared sh = {.desc = desc, .film = film, .running = 0};
    RankLink *l = desc->ranks; /* MPI: rank 0's scheduler serves every rank's devices */
    bool root = !l || rank_link_is_root(l);
    if (!unit_scheduler_init(&sh.sched, g, l ? rank_link_devices(l) : (uint32_t)n, film->done, err))
        return false;
    pthread_mutex_init(&sh.lock, NULL);
    pthread_condattr_t attr;
    pthread_condattr_init(&attr);
    pthread_condattr_setclock(&attr, CLOCK_MONOTONIC);
    pthread_cond_init(&sh.changed, &attr);
    pthread_condattr_destroy(&attr);

    Worker *workers = calloc((size_t)n, sizeof *workers);
    bool ok = workers != NULL;
    const Scene *scene = &devices->session->scene;
    for (int i = 0; i < n && ok; i++) {
        Worker *k = &workers[i];
        Device *dev = i == 0 ? &devices->session->dev : &devices->extra[i - 1].dev;
        const SceneBuffers *buffers = i == 0 ? &devices->session->buffers : &devices->extra[i - 1].buffers;
        k->sh = &sh, k->dev = dev, k->report = &report->device[i];
        k->index = i; /* MPI */
        snprintf(k->report->spec, sizeof k->report->spec, "%d:%d", dev->platform_index, dev->device_index);
        snprintf(k->report->name, sizeof k->report->name, "%s", dev->name);
        k->w = wavefront_create(dev, scene, buffers, &desc->settings, err);
        k->pending = calloc(unit_bitmap_bytes(g->count), 1);
        if (k->w)
            k->sums = device_pinned_alloc(dev, "film_readback", film->num_pixels * FILM_BYTES_PER_PIXEL,
                                          &k->sums_buffer, err);
        ok = k->w && k->pending && k->sums;
        if (ok)
            k->appetite = unit_grid_units_per_window(g, wavefront_stats(k->w)->config.window_size);
        else if (!error_is_set(err))
            error_set(err, ERR_USAGE, NULL, 0, "out of memory for device %s's film", k->report->spec);
    }
    report->num_devices = n;
    double start = seconds_now();
    int started = 0;
    for (int i = 0; i < n && ok; i++) {
        sh.running++;
        if (pthread_create(&workers[i].thread, NULL, worker_main, &workers[i]) != 0) {
            sh.running--;
            error_set(err, ERR_USAGE, NULL, 0, "cannot start a thread for device %s: %s",
                      workers[i].report->spec, strerror(errno));
            pthread_mutex_lock(&sh.lock);
            sh.stop = true;
            pthread_mutex_unlock(&sh.lock);
            ok = false;
            break;
        }
        started++;
    }
    if (started > 0 && !supervise(&sh, workers, started, report, stop, err))
        ok = false;
    for (int i = 0; i < started; i++)
        pthread_join(workers[i].thread, NULL);
    /* Rendering time, as render_loop's: to the last run rendered; moving the films into the
     * host's is report->merge_seconds (the one-device render reads its film after its loop too). */
    double end = start;
    for (int i = 0; i < n && workers; i++) {
        Worker *k = &workers[i];
        if (k->last_run_end > end)
            end = k->last_run_end;
        if (k->failed && ok) {
            *err = k->err;
            ok = false;
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
    stats->seconds = end - start;
    report->merge_seconds = sh.merge_seconds;
    if (l && !root && ok) { /* MPI: this rank's film and report go to rank 0 */
        rank_link_test_kill(l, 0, true);
        ok = rank_link_send_film(l, film, 0, report, stats, err);
    }
    if (l && root)
        rank_link_add_stats(l, stats);
    stats->spp_done = (int)unit_film_spp_done(film);
    if (ok && root && *stop == RENDER_COMPLETE && !unit_film_complete(film))
        *stop = RENDER_STOPPED_BY_SIGNAL;
    /* A stopped render keeps what it has for --resume. */
    if (ok && desc->checkpoint_path && *stop != RENDER_COMPLETE &&
        checkpoint_write(desc->checkpoint_path, desc->identity, film, err))
        report->checkpoints++;
    else if (ok && desc->checkpoint_path && *stop != RENDER_COMPLETE)
        ok = false;
    unit_scheduler_free(&sh.sched);
    pthread_cond_destroy(&sh.changed);
    pthread_mutex_destroy(&sh.lock);
    return ok;
}
