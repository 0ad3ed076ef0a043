/* SPDX-License-Identifier: MIT */
/* render_ranks.h: a unit render (dist/render_units.h) spread over the ranks of an MPI job
 * (dist/mpi_link.h). Every rank loads the scene and renders on its own devices; rank 0 owns the
 * scheduler and hands runs of units to the other ranks' device threads as they ask (so a faster
 * node takes more), and those ranks send back the film of their finished units: when rank 0 asks
 * (a checkpoint) and at their end. Rank 0 adds them to its film (unit_film_merge: a unit counted
 * twice is an error) and writes the image, which is the same bits as one process's.
 *
 * Only each rank's main thread calls MPI (MPI_THREAD_FUNNELED): on rank 0 it answers the
 * requests between its own waits, on the other ranks it relays the device threads' requests.
 * Both poll (MPI_Iprobe) every RANK_POLL_SECONDS instead of blocking in MPI, which would spin.
 *
 * A rank that dies cannot be replaced: OpenMPI without ULFM ends the whole job, so its units are
 * not re-queued; --checkpoint is the recovery.
 *
 * PT_TEST_KILL_RANK=R@N (tests only): rank R kills itself (SIGKILL) once it has finished N units,
 * or, having finished fewer, before it sends its last film: a rank dying mid-run, without
 * timing. */
#ifndef PT_RENDER_RANKS_H
#define PT_RENDER_RANKS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "dist/render_units.h"

#define RANK_POLL_SECONDS 0.001

typedef struct RankLink RankLink;

/* Every rank (collective): checks that all ranks render the same image (render identity, unit
 * grid, settings, pt version) and learns how many devices they have. NULL on every rank, with a
 * message naming the first rank that differs, when they do not. */
RankLink *rank_link_open(const UnitGrid *g, const RenderSettings *s, uint64_t identity,
                         int num_devices, Error *err);
void rank_link_close(RankLink *l);
bool rank_link_is_root(const RankLink *l);
/* The devices of every rank: the scheduler's takers. */
uint32_t rank_link_devices(const RankLink *l);
/* PT_TEST_KILL_RANK: called with the units this rank has finished so far (at_end: before its
 * last film). */
void rank_link_test_kill(RankLink *l, uint32_t units_done, bool at_end);

/* Rank 0's main thread. Answers what has arrived: runs from sched (none once stop is set),
 * finished runs, films (merged into film). False on a bad message. */
bool rank_link_serve(RankLink *l, UnitScheduler *sched, UnitFilm *film, bool stop, Error *err);
/* Asks every rank still rendering for its film (a checkpoint's generation). */
void rank_link_request_flush(RankLink *l, uint64_t generation);
/* Whether every rank has sent its film for generation, or its last. */
bool rank_link_flushed(const RankLink *l, uint64_t generation);
/* Whether every other rank has sent its last film. */
bool rank_link_all_final(const RankLink *l);
/* The ranks that have not, as "1, 3" (for a message). */
void rank_link_missing(const RankLink *l, char *out, size_t size);
/* Camera paths the other ranks have reported finished (progress). */
uint64_t rank_link_paths(const RankLink *l);
/* After the render: the other ranks' counters added to stats. */
void rank_link_add_stats(const RankLink *l, RenderStats *stats);
/* The other ranks' devices (one line each) and the cost of their films at rank 0. */
void rank_link_print_report(const RankLink *l, FILE *out);

/* The other ranks. A device thread asks for a run of at most max_units units and reports the
 * last run it finished (paths: its camera paths) with its next request. */
void rank_link_ask(RankLink *l, int worker, uint32_t max_units);
void rank_link_finished(RankLink *l, int worker, UnitRun run, uint64_t paths);
/* Waits for rank 0's answer to the thread's request: false when there is no run left. */
bool rank_link_answer(RankLink *l, int worker, UnitRun *run);
/* The main thread: sends the requests, hands the answers over, and raises *flush_request to the
 * newest generation rank 0 asked for. False when MPI fails. */
bool rank_link_pump(RankLink *l, uint64_t *flush_request, Error *err);
/* Sends film's units to rank 0 and empties film; final (the last message, after the render):
 * with this rank's device report and counters. */
bool rank_link_send_film(RankLink *l, UnitFilm *film, uint64_t generation,
                         const UnitRenderReport *final_report, const RenderStats *final_stats,
                         Error *err);

#endif
