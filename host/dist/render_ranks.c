// SPDX-License-Identifier: MIT
/* render_ranks.c: the link's opening (every rank checks that all render the same image), its
 * end, and the test point PT_TEST_KILL_RANK (dist/render_ranks.h). MPI errors are fatal
 * (MPI_ERRORS_ARE_FATAL, the default): a failed call ends the job through mpirun, so the return
 * codes of MPI calls are not checked in render_ranks*.c. */
#include "dist/render_ranks.h"

#include <mpi.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>

#include "dist/mpi_link.h"
#include "dist/render_ranks_wire.h"
#include "base/version.h"
#include "render/film.h"

/* What a rank renders; rank 0 compares every other rank's with its own. */
/* What a rank renders; rank 0 compares every other rank's with its own. */
typedef struct {
    uint64_t identity;
    uint32_t width, height, spp, unit_spp, unit_rows, count;
    uint32_t seed, max_depth, no_nee, sampler;
    float clamp_indirect;
    uint32_t num_devices;
    char version[32];
} Hello;

static Hello hello_of(const UnitGrid *g, const RenderSettings *s, uint64_t identity, int devices)
{
    Hello h = {.identity = identity, .width = g->width, .height = g->height, .spp = g->spp,
               .unit_spp = g->unit_spp, .unit_rows = g->unit_rows, .count = g->count,
               .seed = s->seed, .max_depth = (uint32_t)s->max_depth, .no_nee = s->no_nee,
               .sampler = (uint32_t)s->sampler,
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
    else if (a->sampler != b->sampler)
        snprintf(out, size, "sampler %u, not %u", b->sampler, a->sampler);
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
        error_set(err, ERR_SETTINGS, NULL, 0, "PT_TEST_KILL_RANK=%s: expected RANK@UNITS, e.g. 1@2",
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
        error_set(err, ERR_MPI, NULL, 0, "%s", verdict);
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
