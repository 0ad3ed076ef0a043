/* SPDX-License-Identifier: MIT */
/* render_units_internal.h (private to dist/render_units*.c): the state the unit render's main
 * thread and device threads share, and the steps that differ under MPI (render_units_ranks.c),
 * kept apart so that render_units.c reads as the render of one process. */
#ifndef PT_RENDER_UNITS_INTERNAL_H
#define PT_RENDER_UNITS_INTERNAL_H

#include <pthread.h>

#include "dist/render_ranks.h"
#include "dist/render_units.h"

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
    bool time_up;           /* the time limit has passed (the render stops once it holds samples) */
    uint64_t flush_request; /* workers with flushed below it move their film to the host's */
    int running;
    double merge_seconds;
    bool checkpoint_failed; /* warned once: later failures are silent */
};

/* The hooks (UnitRenderHooks), each a no-op when NULL. */
static inline int units_stop_requested(const Shared *sh)
{
    return sh->desc->hooks.stop_requested ? sh->desc->hooks.stop_requested() : 0;
}

static inline void units_test_point(const Shared *sh, const char *point)
{
    if (sh->desc->hooks.test_point)
        sh->desc->hooks.test_point(point);
}

/* Whether this process schedules the units: alone, or rank 0 of an MPI job. */
static inline bool units_is_root(const Shared *sh)
{
    return !sh->desc->ranks || rank_link_is_root(sh->desc->ranks);
}

/* render_units.c: whether every worker still running has served flush request `request`. */
bool units_workers_flushed(const Worker *workers, int n, uint64_t request);

/* render_units_ranks.c. A worker's next run (false: none left) and its finished run: from and to
 * the scheduler, or on ranks other than 0 through the main thread to rank 0. */
bool units_take_run(Worker *k, UnitRun *run);
void units_finish_run(Worker *k, UnitRun run);
/* The main thread, between its waits, with sh->lock held: rank 0 answers the other ranks; another
 * rank relays its threads' requests and sends its film when rank 0 asks for it (*asked: the
 * generation, until sent). */
bool units_serve_ranks(Shared *sh, Worker *workers, int n, uint64_t *asked, Error *err);
/* Rank 0: whether another rank has yet to send its last film (the main thread waits for it). */
bool units_ranks_pending(const Shared *sh);
/* After the device threads: another rank sends its film, report and counters to rank 0; rank 0
 * adds the other ranks' counters to stats. */
bool units_end_ranks(Shared *sh, const UnitRenderReport *report, RenderStats *stats, bool ok,
                     Error *err);

#endif
