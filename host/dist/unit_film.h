/* SPDX-License-Identifier: MIT */
/* unit_film.h: the host's film of a render split into work units: the exact film sums
 * (render/film.h) of the units finished so far and which units those are. The two always agree:
 * sums and units are added together, under one lock, so the film can be saved (a checkpoint) or
 * sent (an MPI rank's share) at any moment and hold whole units only. */
#ifndef PT_UNIT_FILM_H
#define PT_UNIT_FILM_H

#include <pthread.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dist/work_units.h"

typedef struct {
    pthread_mutex_t lock;
    UnitGrid grid;
    size_t num_pixels;
    uint64_t *sums;      /* FILM_WORDS per pixel */
    uint8_t *done;       /* bitmap of the finished units (unit_bitmap_*) */
    uint32_t units_done;
} UnitFilm;

bool unit_film_init(UnitFilm *f, const UnitGrid *g, Error *err);
void unit_film_free(UnitFilm *f);
/* Adds the film sums of the units in done (a bitmap) to f. A unit already in f is an error that
 * names it (a unit counted twice would be a wrong image): false, f unchanged. */
bool unit_film_merge(UnitFilm *f, const uint64_t *sums, const uint8_t *done, Error *err);
/* Empties f (no units, zero sums): after its content has been sent on. */
void unit_film_clear(UnitFilm *f);
/* Samples every pixel holds: the fewest of any tile (its finished sample blocks). */
uint32_t unit_film_spp_done(UnitFilm *f);
/* Whether every unit is finished. */
bool unit_film_complete(UnitFilm *f);

#endif
