// SPDX-License-Identifier: MIT
/* render_ranks.c: the messages between rank 0 and the other ranks of a unit render
 * (app/render_ranks.h). MPI errors are fatal (MPI_ERRORS_ARE_FATAL, the default): a failed call
 * ends the job through mpirun, so the return codes are not checked. */
#include "app/render_ranks.h"

#include <limits.h>
#include <mpi.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "app/mpi_link.h"
#include "base/clock.h"
#include "base/version.h"
#include "render/film.h"

enum { TAG_TAKE = 1, TAG_RUN, TAG_FLUSH, TAG_FILM, TAG_SUMS };

/* What a rank renders; rank 0 compares every other rank's with its own. */
typedef struct {
    uint64_t identity;
    uint32_t width, height, spp, unit_spp, unit_rows, count;
    uint32_t seed, max_depth, no_nee;
    float clamp_indirect;
    uint32_t num_devices;
    char version[32];
} Hello;

/* A device thread's request: a run of at most max_units, and the run it finished last. */
typedef struct {
    uint32_t worker, max_units, done_first, done_count;
    uint64_t done_paths;
} TakeMsg;

typedef struct {
    uint32_t worker, found, first, count;
} RunMsg;

/* A film message (TAG_FILM): this header, then the done bitmap; the sums of rows
 * first_pixel / width .. follow as TAG_SUMS when num_pixels > 0 (only the tiles it touches). */
typedef struct {
    uint64_t generation; /* the flush request it answers (0: none) */
    uint32_t final;      /* the rank's last message: with its devices and counters */
    uint32_t first_pixel, num_pixels;
    uint32_t num_devices;
    RenderStats stats;
    UnitDeviceReport device[DEVICE_LIST_MAX + 1];
} FilmHeader;

enum { SLOT_IDLE, SLOT_ASKING, SLOT_SENT, SLOT_ANSWERED };

/* A device thread of a rank other than 0, as its main thread relays it. */
typedef struct {
    int state;
    uint32_t max_units;
    UnitRun done, answer;
    uint64_t done_paths;
    bool found;
} Slot;

/* Rank 0's view of another rank. */
typedef struct {
    bool final;
    uint64_t flushed, paths;
    FilmHeader last; /* its final message: devices and counters */
} Peer;

struct RankLink {
    int rank, size;
    UnitGrid grid;
    uint32_t devices;
    int kill_rank; /* PT_TEST_KILL_RANK (-1: none) */
    uint32_t kill_units, units_done;
    uint8_t *message; /* a FilmHeader and a bitmap */
    /* rank 0 */
    Peer *peers;
    uint64_t *scratch; /* a film of zeros but for the rows being merged */
    uint64_t films, bytes, units_received;
    double merge_seconds;
    /* the others */
    pthread_mutex_t lock;
    pthread_cond_t answered;
    Slot slot[DEVICE_LIST_MAX + 1];
};

static Hello hello_of(const UnitGrid *g, const RenderSettings *s, uint64_t identity, int devices)
{
    Hello h = {.identity = identity, .width = g->width, .height = g->height, .spp = g->spp,
               .unit_spp = g->unit_spp, .unit_rows = g->unit_rows, .count = g->count,
               .seed = s->seed, .max_depth = (uint32_t)s->max_depth, .no_nee = s->no_nee,
               .clamp_indirect = s->clamp_indirect, .num_devices = (uint32_t)devices};
    snprintf(h.version, sizeof h.version, "%s", PT_VERSION);
    return h;
}

/* The first way b's render differs from a's, into out; false when they agree. */
static bool hello_differs(const Hello *a, const Hello *b, char *out, size_t size)
{
    if (strcmp(a->version, b->version))
        snprintf(out, size, "pt %s, not %s", b->version, a->version);
    else if (a->width != b->width || a->height != b->height)
        snprintf(out, size, "a %ux%u film, not %ux%u", b->width, b->height, a->width, a->height);
    else if (a->spp != b->spp)
        snprintf(out, size, "%u spp, not %u", b->spp, a->spp);
    else if (a->unit_spp != b->unit_spp || a->unit_rows != b->unit_rows || a->count != b->count)
        snprintf(out, size, "units of %u spp x %u rows, not %u x %u", b->unit_spp, b->unit_rows,
                 a->unit_spp, a->unit_rows);
    else if (a->seed != b->seed || a->max_depth != b->max_depth || a->no_nee != b->no_nee ||
             a->clamp_indirect != b->clamp_indirect)
        snprintf(out, size, "seed %u, max depth %u, no-nee %u, clamp %g; not %u, %u, %u, %g",
                 b->seed, b->max_depth, b->no_nee, b->clamp_indirect, a->seed, a->max_depth,
                 a->no_nee, a->clamp_indirect);
    else if (a->identity != b->identity)
        snprintf(out, size, "render identity %016llx, not %016llx (another scene or settings)",
                 (unsigned long long)b->identity, (unsigned long long)a->identity);
    else
        return false;
    return true;
}

static bool parse_kill(RankLink *l, Error *err)
{
    l->kill_rank = -1;
    const char *spec = getenv("PT_TEST_KILL_RANK");
    if (!spec || !*spec)
        return true;
    char tail;
    if (sscanf(spec, "%d@%u%c", &l->kill_rank, &l->kill_units, &tail) != 2 || l->kill_rank < 0) {
        error_set(err, ERR_USAGE, NULL, 0, "PT_TEST_KILL_RANK=%s: expected RANK@UNITS, e.g. 1@2",
                  spec);
        return false;
    }
    return true;
}

RankLink *rank_link_open(const UnitGrid *g, const RenderSettings *s, uint64_t identity,
                         int num_devices, Error *err)
{
    int rank = mpi_link_rank(), size = mpi_link_size();
    Hello mine = hello_of(g, s, identity, num_devices);
    Hello *all = rank == 0 ? calloc((size_t)size, sizeof *all) : NULL;
    if (rank == 0 && !all)
        die("out of memory for %d ranks", size); /* ends the job: the others wait in the gather */
    MPI_Gather(&mine, sizeof mine, MPI_BYTE, all, sizeof mine, MPI_BYTE, 0, MPI_COMM_WORLD);
    char verdict[768] = "";
    uint32_t devices = 0;
    for (int r = 0; r < size && rank == 0; r++) {
        char what[400];
        if (!verdict[0] && hello_differs(&all[0], &all[r], what, sizeof what))
            snprintf(verdict, sizeof verdict,
                     "rank %d renders another image than rank 0 (%s): every rank must get the same "
                     "scene, options and pt build", r, what);
        devices += all[r].num_devices;
    }
    free(all);
    MPI_Bcast(verdict, sizeof verdict, MPI_CHAR, 0, MPI_COMM_WORLD);
    if (verdict[0]) {
        error_set(err, ERR_USAGE, NULL, 0, "%s", verdict);
        return NULL;
    }
    RankLink *l = calloc(1, sizeof *l);
    size_t message = sizeof(FilmHeader) + unit_bitmap_bytes(g->count);
    if (l) {
        l->rank = rank, l->size = size, l->grid = *g, l->devices = devices;
        l->message = calloc(message, 1);
        l->peers = rank == 0 ? calloc((size_t)size, sizeof *l->peers) : NULL;
        l->scratch = rank == 0 ? calloc((size_t)g->width * g->height * FILM_WORDS, 8) : NULL;
    }
    if (!l || !l->message || (rank == 0 && (!l->peers || !l->scratch)))
        die("out of memory for the film messages of rank %d", rank);
    pthread_mutex_init(&l->lock, NULL);
    pthread_cond_init(&l->answered, NULL);
    if (!parse_kill(l, err)) {
        rank_link_close(l);
        return NULL;
    }
    return l;
}

void rank_link_close(RankLink *l)
{
    if (!l)
        return;
    pthread_mutex_destroy(&l->lock);
    pthread_cond_destroy(&l->answered);
    free(l->message);
    free(l->peers);
    free(l->scratch);
    free(l);
}

bool rank_link_is_root(const RankLink *l) { return l->rank == 0; }
uint32_t rank_link_devices(const RankLink *l) { return l->devices; }

void rank_link_test_kill(RankLink *l, uint32_t units_finished, bool at_end)
{
    pthread_mutex_lock(&l->lock);
    l->units_done += units_finished;
    bool kill = l->kill_rank == l->rank && (at_end || l->units_done >= l->kill_units);
    uint32_t done = l->units_done;
    pthread_mutex_unlock(&l->lock);
    if (kill) {
        fprintf(stderr, "pt: rank %d: PT_TEST_KILL_RANK: SIGKILL after %u units\n", l->rank, done);
        raise(SIGKILL);
    }
}

/* ---- rank 0 ---- */

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
        error_set(err, ERR_USAGE, NULL, 0, "rank %d sent a malformed film (%d bytes)", from, got);
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
        error_set(err, ERR_USAGE, NULL, 0, "rank %d's film: %s", from, merge.message);
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
        error_set(err, ERR_USAGE, NULL, 0, "rank %d sent a malformed request", from);
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
            error_set(err, ERR_USAGE, NULL, 0, "rank %d sent an unexpected message (tag %d)", from,
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
    for (int r = 1; r < l->size; r++) {
        const RenderStats *s = &l->peers[r].last.stats;
        stats->paths += s->paths;
        stats->extension_rays += s->extension_rays;
        stats->shadow_rays += s->shadow_rays;
        stats->nonfinite += s->nonfinite;
        stats->batches += s->batches;
        for (int st = 0; st < STAGE_COUNT; st++) {
            stats->stage_ms[st] += s->stage_ms[st];
            stats->stage_launches[st] += s->stage_launches[st];
        }
    }
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

/* ---- the other ranks ---- */

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
            error_set(err, ERR_USAGE, NULL, 0, "an unexpected message from rank 0 (tag %d)",
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
