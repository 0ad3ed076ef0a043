// SPDX-License-Identifier: MIT
/* render_ranks_relay.c: the other ranks' side of the link (dist/render_ranks.h): the main thread
 * relays its device threads' requests to rank 0 and their answers back, and sends the rank's
 * film. */
#include <limits.h>
#include <mpi.h>
#include <string.h>

#include "dist/render_ranks_wire.h"
#include "render/film.h"

void rank_link_ask(RankLink *l, int worker, uint32_t max_units)
{
    pthread_mutex_lock(&l->lock);
    l->slot[worker].state = SLOT_ASKING;
    l->slot[worker].max_units = max_units;
    pthread_mutex_unlock(&l->lock);
}

void rank_link_finished(RankLink *l, int worker, UnitRun run, uint64_t paths)
{
    pthread_mutex_lock(&l->lock);
    l->slot[worker].done = run;
    l->slot[worker].done_paths = paths;
    pthread_mutex_unlock(&l->lock);
}

bool rank_link_answer(RankLink *l, int worker, UnitRun *run)
{
    Slot *s = &l->slot[worker];
    pthread_mutex_lock(&l->lock);
    while (s->state != SLOT_ANSWERED)
        pthread_cond_wait(&l->answered, &l->lock);
    s->state = SLOT_IDLE;
    *run = s->answer;
    bool found = s->found;
    pthread_mutex_unlock(&l->lock);
    return found;
}

bool rank_link_pump(RankLink *l, uint64_t *flush_request, Error *err)
{
    TakeMsg out[DEVICE_LIST_MAX + 1];
    int n = 0;
    pthread_mutex_lock(&l->lock);
    for (uint32_t w = 0; w <= DEVICE_LIST_MAX; w++) {
        Slot *s = &l->slot[w];
        if (s->state != SLOT_ASKING)
            continue;
        out[n++] = (TakeMsg){w, s->max_units, s->done.first, s->done.count, s->done_paths};
        s->state = SLOT_SENT;
        s->done = (UnitRun){0, 0}, s->done_paths = 0;
    }
    pthread_mutex_unlock(&l->lock);
    for (int i = 0; i < n; i++)
        MPI_Send(&out[i], sizeof out[i], MPI_BYTE, 0, TAG_TAKE, MPI_COMM_WORLD);
    for (;;) {
        int flag = 0;
        MPI_Status status;
        MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
        if (!flag)
            return true;
        if (status.MPI_TAG == TAG_FLUSH) {
            uint64_t generation;
            MPI_Recv(&generation, 1, MPI_UINT64_T, 0, TAG_FLUSH, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
            if (generation > *flush_request)
                *flush_request = generation;
            continue;
        }
        RunMsg a = {.worker = UINT32_MAX};
        if (status.MPI_TAG == TAG_RUN)
            MPI_Recv(&a, sizeof a, MPI_BYTE, 0, TAG_RUN, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        pthread_mutex_lock(&l->lock);
        bool ok = a.worker <= DEVICE_LIST_MAX && l->slot[a.worker].state == SLOT_SENT &&
                  (!a.found || (a.count > 0 && a.first < l->grid.count &&
                                a.count <= l->grid.count - a.first));
        if (ok) {
            Slot *s = &l->slot[a.worker];
            s->state = SLOT_ANSWERED, s->found = a.found, s->answer = (UnitRun){a.first, a.count};
            pthread_cond_broadcast(&l->answered);
        }
        pthread_mutex_unlock(&l->lock);
        if (!ok) {
            error_set(err, ERR_MPI, NULL, 0, "an unexpected message from rank 0 (tag %d)",
                      status.MPI_TAG);
            return false;
        }
    }
}

bool rank_link_send_film(RankLink *l, UnitFilm *film, uint64_t generation,
                         const UnitRenderReport *final_report, const RenderStats *final_stats,
                         Error *err)
{
    const UnitGrid *g = &l->grid;
    size_t bitmap = unit_bitmap_bytes(g->count);
    FilmHeader *h = (FilmHeader *)l->message;
    memset(h, 0, sizeof *h);
    h->generation = generation;
    if (final_report) {
        h->final = 1;
        h->num_devices = (uint32_t)final_report->num_devices;
        memcpy(h->device, final_report->device, sizeof h->device);
        h->stats = *final_stats;
    }
    /* The film's lock is held throughout: a device thread ending now waits to add its units. */
    pthread_mutex_lock(&film->lock);
    uint32_t first_tile = UINT32_MAX, last_tile = 0;
    for (uint32_t u = 0; u < g->count; u++)
        if (unit_bitmap_get(film->done, u)) {
            uint32_t t = u / g->blocks;
            first_tile = t < first_tile ? t : first_tile;
            last_tile = t > last_tile ? t : last_tile;
        }
    if (first_tile != UINT32_MAX) {
        uint32_t first_row = first_tile * g->unit_rows, end_row = (last_tile + 1) * g->unit_rows;
        end_row = end_row < g->height ? end_row : g->height;
        h->first_pixel = first_row * g->width, h->num_pixels = (end_row - first_row) * g->width;
    }
    size_t words = (size_t)h->num_pixels * FILM_WORDS;
    if (words > INT_MAX) {
        pthread_mutex_unlock(&film->lock);
        error_set(err, ERR_TOO_LARGE, NULL, 0,
                  "%zu film words are more than one MPI message holds", words);
        return false;
    }
    memcpy(l->message + sizeof *h, film->done, bitmap);
    MPI_Send(l->message, (int)(sizeof *h + bitmap), MPI_BYTE, 0, TAG_FILM, MPI_COMM_WORLD);
    uint64_t *rows = film->sums + (size_t)h->first_pixel * FILM_WORDS;
    if (words)
        MPI_Send(rows, (int)words, MPI_UINT64_T, 0, TAG_SUMS, MPI_COMM_WORLD);
    /* What the film held is rank 0's now. */
    memset(rows, 0, words * sizeof *rows);
    memset(film->done, 0, bitmap);
    film->units_done = 0;
    pthread_mutex_unlock(&film->lock);
    return true;
}
