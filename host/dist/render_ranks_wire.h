/* SPDX-License-Identifier: MIT */
/* render_ranks_wire.h (private to dist/render_ranks*.c): the messages between rank 0 and the other
 * ranks, as the same build sends and reads them (MPI_BYTE: every rank runs the same pt, which
 * rank_link_open checks), and the link's state. */
#ifndef PT_RENDER_RANKS_WIRE_H
#define PT_RENDER_RANKS_WIRE_H

#include <pthread.h>

#include "dist/render_ranks.h"

enum { TAG_TAKE = 1, TAG_RUN, TAG_FLUSH, TAG_FILM, TAG_SUMS };

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

#endif
