// SPDX-License-Identifier: MIT
/* render_ranks_root.c: rank 0's side of the link (dist/render_ranks.h): it answers the other
 * ranks' requests from its scheduler and adds their films to its own. */
#include <mpi.h>
#include <stdlib.h>
#include <string.h>

#include "dist/render_ranks_wire.h"
#include "base/clock.h"
#include "render/film.h"

static bool receive_film(RankLink *l, int from, UnitFilm *film, Error *err)
{
    double start = seconds_now();
    size_t bitmap = unit_bitmap_bytes(l->grid.count), expected = sizeof(FilmHeader) + bitmap;
    MPI_Status status;
    MPI_Recv(l->message, (int)expected, MPI_BYTE, from, TAG_FILM, MPI_COMM_WORLD, &status);
    int got = 0;
    MPI_Get_count(&status, MPI_BYTE, &got);
    FilmHeader *h = (FilmHeader *)l->message;
    if ((size_t)got != expected || h->num_pixels > film->num_pixels ||
        h->first_pixel > film->num_pixels - h->num_pixels || h->num_devices > DEVICE_LIST_MAX + 1) {
        error_set(err, ERR_MPI, NULL, 0, "rank %d sent a malformed film (%d bytes)", from, got);
        return false;
    }
    uint64_t *rows = l->scratch + (size_t)h->first_pixel * FILM_WORDS;
    size_t words = (size_t)h->num_pixels * FILM_WORDS;
    if (words)
        MPI_Recv(rows, (int)words, MPI_UINT64_T, from, TAG_SUMS, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    const uint8_t *done = l->message + sizeof *h;
    Error merge = {0};
    bool ok = unit_film_merge(film, l->scratch, done, &merge);
    memset(rows, 0, words * sizeof *rows);
    if (!ok) {
        error_set(err, ERR_MPI, NULL, 0, "rank %d's film: %s", from, merge.message);
        return false;
    }
    for (size_t i = 0; i < bitmap; i++)
        l->units_received += (uint64_t)__builtin_popcount(done[i]);
    l->films++;
    l->bytes += expected + words * sizeof *rows;
    l->merge_seconds += seconds_now() - start;
    Peer *p = &l->peers[from];
    if (h->generation > p->flushed)
        p->flushed = h->generation;
    if (h->final)
        p->final = true, p->last = *h;
    return true;
}

static bool answer_take(RankLink *l, int from, UnitScheduler *sched, bool stop, Error *err)
{
    TakeMsg m;
    MPI_Recv(&m, sizeof m, MPI_BYTE, from, TAG_TAKE, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (m.worker > DEVICE_LIST_MAX || m.done_first > l->grid.count ||
        m.done_count > l->grid.count - m.done_first) {
        error_set(err, ERR_MPI, NULL, 0, "rank %d sent a malformed request", from);
        return false;
    }
    if (m.done_count) {
        unit_scheduler_finish(sched, (UnitRun){m.done_first, m.done_count});
        l->peers[from].paths += m.done_paths;
    }
    RunMsg a = {.worker = m.worker};
    UnitRun run;
    if (!stop && unit_scheduler_take(sched, m.max_units, &run))
        a.found = 1, a.first = run.first, a.count = run.count;
    MPI_Send(&a, sizeof a, MPI_BYTE, from, TAG_RUN, MPI_COMM_WORLD);
    return true;
}

bool rank_link_serve(RankLink *l, UnitScheduler *sched, UnitFilm *film, bool stop, Error *err)
{
    for (;;) {
        int flag = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
        if (!flag)
            return true;
        int from = status.MPI_SOURCE;
        bool ok = status.MPI_TAG == TAG_TAKE ? answer_take(l, from, sched, stop, err)
                  : status.MPI_TAG == TAG_FILM ? receive_film(l, from, film, err)
                                               : false;
        if (!ok && !error_is_set(err))
            error_set(err, ERR_MPI, NULL, 0, "rank %d sent an unexpected message (tag %d)", from,
                      status.MPI_TAG);
        if (!ok)
            return false;
    }
}

void rank_link_request_flush(RankLink *l, uint64_t generation)
{
    for (int r = 1; r < l->size; r++)
        if (!l->peers[r].final)
            MPI_Send(&generation, 1, MPI_UINT64_T, r, TAG_FLUSH, MPI_COMM_WORLD);
}

bool rank_link_flushed(const RankLink *l, uint64_t generation)
{
    for (int r = 1; r < l->size; r++)
        if (!l->peers[r].final && l->peers[r].flushed < generation)
            return false;
    return true;
}

bool rank_link_all_final(const RankLink *l) { return rank_link_flushed(l, UINT64_MAX); }

void rank_link_missing(const RankLink *l, char *out, size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    for (int r = 1; r < l->size && used < size; r++)
        if (!l->peers[r].final)
            used += (size_t)snprintf(out + used, size - used, "%s%d", used ? ", " : "", r);
}

uint64_t rank_link_paths(const RankLink *l)
{
    uint64_t paths = 0;
    for (int r = 1; r < l->size; r++)
        paths += l->peers[r].paths;
    return paths;
}

void rank_link_add_stats(const RankLink *l, RenderStats *stats)
{
    for (int r = 1; r < l->size; r++)
        render_stats_add(stats, &l->peers[r].last.stats);
}

void rank_link_print_report(const RankLink *l, FILE *out)
{
    for (int r = 1; r < l->size; r++)
        for (uint32_t i = 0; i < l->peers[r].last.num_devices; i++) {
            const UnitDeviceReport *d = &l->peers[r].last.device[i];
            fprintf(out, "pt: rank %d device %s %s: %u units in %u runs, %.2f Mpaths/s busy\n", r,
                    d->spec, d->name, d->units, d->runs,
                    d->busy_seconds > 0 ? d->paths / d->busy_seconds * 1e-6 : 0.0);
        }
    fprintf(out,
            "pt: films of %d other ranks at rank 0: %llu messages, %llu bytes (%.0f per unit), "
            "merged in %.2f ms\n", l->size - 1, (unsigned long long)l->films,
            (unsigned long long)l->bytes,
            l->units_received ? (double)l->bytes / (double)l->units_received : 0.0,
            l->merge_seconds * 1e3);
}
