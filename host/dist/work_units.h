/* SPDX-License-Identifier: MIT */
/* work_units.h: the canonical split of a render into work units, and the scheduler that hands them
 * out. A unit is a tile (a band of whole rows) times a block of samples per pixel; their sizes
 * follow from the render settings alone (film, spp, --unit-spp, --unit-rows), never from a device
 * or from timing. Every sample's value depends only on its pixel and sample index, and the film
 * sums are integers (render/film.h), so the film of any set of units is the same bits whichever
 * device renders which unit, in any order, in runs of any length. */
#ifndef PT_WORK_UNITS_H
#define PT_WORK_UNITS_H

#include <pthread.h>
#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "render/wavefront.h" /* PixelBlock: what a run renders */

/* Units are numbered tile-major: unit u is sample block u % blocks of tile u / blocks, so that
 * consecutive units of one tile are consecutive samples (a run, rendered as one block). */
typedef struct {
    uint32_t width, height, spp;
    uint32_t unit_spp;  /* samples per pixel of a unit (a tile's last block may hold fewer) */
    uint32_t unit_rows; /* rows of a tile (the last tile may hold fewer) */
    uint32_t tiles, blocks, count; /* count = tiles * blocks */
} UnitGrid;

/* Default tiles: whole rows, as many tiles as needed to keep each at or below this many pixels
 * (1280x960: 2 tiles of 480 rows; 3840x2160: 8 of 270), so that a render of few samples still
 * splits between devices; and one sample per unit. */
#define UNIT_TILE_MAX_PIXELS (1u << 20)
#define UNIT_DEFAULT_SPP 1u

/* unit_spp, unit_rows: 0 = the defaults above; larger than spp or the height: clamped. */
bool unit_grid_init(UnitGrid *g, uint32_t width, uint32_t height, uint32_t spp, uint32_t unit_spp,
                    uint32_t unit_rows, Error *err);

/* Units first .. first + count - 1, all of one tile. */
typedef struct {
    uint32_t first, count;
} UnitRun;


PixelBlock unit_run_block(const UnitGrid *g, UnitRun run);
uint64_t unit_run_paths(const UnitGrid *g, UnitRun run);
/* The units of one device window of window_samples samples (at least 1): a device's appetite. */
uint32_t unit_grid_units_per_window(const UnitGrid *g, uint64_t window_samples);

/* Hands out runs to any number of takers (threads of this process, or MPI ranks through rank 0):
 * dynamic, so a fast device takes more. Thread-safe. */
typedef struct {
    pthread_mutex_t lock;
    UnitGrid grid;
    uint8_t *state;     /* UNIT_TODO, UNIT_TAKEN or UNIT_DONE per unit */
    uint32_t cursor;    /* no UNIT_TODO unit before it */
    uint32_t todo;      /* units neither taken nor done */
    uint32_t unfinished; /* units not done */
    uint32_t takers;    /* devices sharing the units (sizes the runs near the end) */
} UnitScheduler;

enum { UNIT_TODO = 0, UNIT_TAKEN = 1, UNIT_DONE = 2 };

/* done: NULL, or a bitmap (bit u of byte u / 8) of units finished already (a resumed render):
 * they are never handed out. */
bool unit_scheduler_init(UnitScheduler *s, const UnitGrid *g, uint32_t takers, const uint8_t *done,
                         Error *err);
void unit_scheduler_free(UnitScheduler *s);
/* The next run of at most max_units units (guided: the units left over the takers, so that the
 * last runs are short and the devices finish together); false when none is left. */
bool unit_scheduler_take(UnitScheduler *s, uint32_t max_units, UnitRun *run);
/* Marks a run finished (its samples are in some film). */
void unit_scheduler_finish(UnitScheduler *s, UnitRun run);
/* Gives a taken run back (its taker failed before finishing it): it is handed out again. */
void unit_scheduler_requeue(UnitScheduler *s, UnitRun run);
uint32_t unit_scheduler_unfinished(UnitScheduler *s);

/* The bitmap of finished-unit sets: bytes for count units. */
static inline size_t unit_bitmap_bytes(uint32_t count) { return (count + 7u) / 8u; }
static inline bool unit_bitmap_get(const uint8_t *bits, uint32_t u) { return bits[u / 8] >> (u % 8) & 1u; }
static inline void unit_bitmap_set(uint8_t *bits, uint32_t u) { bits[u / 8] |= (uint8_t)(1u << (u % 8)); }

#endif
