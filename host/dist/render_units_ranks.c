// SPDX-License-Identifier: MIT
/* render_units_ranks.c: the unit render's steps under MPI (dist/render_ranks.h), in one place so
 * that render_units.c stays the render of one process: on ranks other than 0, runs come from rank
 * 0 through the main thread, and the film goes back to it. Every function does the one-process
 * thing when desc->ranks is NULL. */
#include "dist/render_units_internal.h"

bool units_take_run(Worker *k, UnitRun *run)
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

void units_finish_run(Worker *k, UnitRun run)
{
    RankLink *l = k->sh->desc->ranks;
    if (l && !rank_link_is_root(l))
        rank_link_finished(l, k->index, run, unit_run_paths(&k->sh->desc->grid, run));
    else
        unit_scheduler_finish(&k->sh->sched, run);
    if (l)
        rank_link_test_kill(l, run.count, false);
}

/* Rank 0: answers the other ranks; a stop signal before every rank has sent its film fails the
 * render rather than write an image that lacks their units. */
static bool serve_as_root(Shared *sh, RankLink *l, Error *err)
{
    int sig = units_stop_requested(sh);
    bool stop = sh->stop || sig;
    pthread_mutex_unlock(&sh->lock);
    bool ok = rank_link_serve(l, &sh->sched, sh->film, stop, err);
    pthread_mutex_lock(&sh->lock);
    if (ok && sig && !rank_link_all_final(l)) {
        /* mpirun sends SIGTERM to every rank when one dies: this image would lack its units. */
        char missing[256];
        rank_link_missing(l, missing, sizeof missing);
        const char *name = sh->desc->hooks.stop_name ? sh->desc->hooks.stop_name(sig) : "a signal";
        error_set(err, ERR_MPI, NULL, 0,
                  "rank 0: stopped by %s before rank(s) %s sent their film (a rank that dies "
                  "makes mpirun stop the others): no image is written", name, missing);
        ok = false;
    }
    return ok;
}

bool units_serve_ranks(Shared *sh, Worker *workers, int n, uint64_t *asked, Error *err)
{
    RankLink *l = sh->desc->ranks;
    if (rank_link_is_root(l))
        return serve_as_root(sh, l, err);
    uint64_t request = sh->flush_request;
    pthread_mutex_unlock(&sh->lock);
    bool ok = rank_link_pump(l, &request, err);
    pthread_mutex_lock(&sh->lock);
    if (request > sh->flush_request) {
        sh->flush_request = *asked = request;
        pthread_cond_broadcast(&sh->changed);
    }
    if (ok && *asked && units_workers_flushed(workers, n, *asked)) {
        uint64_t generation = *asked;
        *asked = 0;
        pthread_mutex_unlock(&sh->lock);
        ok = rank_link_send_film(l, sh->film, generation, NULL, NULL, err);
        pthread_mutex_lock(&sh->lock);
    }
    return ok;
}

bool units_ranks_pending(const Shared *sh)
{
    RankLink *l = sh->desc->ranks;
    return l && rank_link_is_root(l) && !rank_link_all_final(l);
}

bool units_end_ranks(Shared *sh, const UnitRenderReport *report, RenderStats *stats, bool ok,
                     Error *err)
{
    RankLink *l = sh->desc->ranks;
    if (l && !rank_link_is_root(l) && ok) { /* this rank's film and report go to rank 0 */
        rank_link_test_kill(l, 0, true);
        ok = rank_link_send_film(l, sh->film, 0, report, stats, err);
    }
    if (l && rank_link_is_root(l))
        rank_link_add_stats(l, stats);
    return ok;
}
