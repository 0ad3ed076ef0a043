// SPDX-License-Identifier: MIT
#include "dist/unit_film.h"

#include <stdlib.h>
#include <string.h>

#include "render/film.h"

bool unit_film_init(UnitFilm *f, const UnitGrid *g, Error *err)
{
    memset(f, 0, sizeof *f);
    f->grid = *g;
    f->num_pixels = (size_t)g->width * g->height;
    f->sums = calloc(f->num_pixels * FILM_WORDS, sizeof *f->sums);
    f->done = calloc(unit_bitmap_bytes(g->count), 1);
    if (!f->sums || !f->done) {
        free(f->sums);
        free(f->done);
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for a %ux%u film", g->width, g->height);
        return false;
    }
    pthread_mutex_init(&f->lock, NULL);
    return true;
}

void unit_film_free(UnitFilm *f)
{
    if (f->sums)
        pthread_mutex_destroy(&f->lock);
    free(f->sums);
    free(f->done);
    memset(f, 0, sizeof *f);
}

bool unit_film_merge(UnitFilm *f, const uint64_t *sums, const uint8_t *done, Error *err)
{
    pthread_mutex_lock(&f->lock);
    uint32_t added = 0;
    for (uint32_t u = 0; u < f->grid.count; u++) {
        if (!unit_bitmap_get(done, u))
            continue;
        if (unit_bitmap_get(f->done, u)) {
            pthread_mutex_unlock(&f->lock);
            error_set(err, ERR_MPI, NULL, 0,
                      "work unit %u (tile %u, samples from %u) was rendered twice: refusing to "
                      "count it twice", u, u / f->grid.blocks, u % f->grid.blocks * f->grid.unit_spp);
            return false;
        }
        added++;
    }
    for (size_t i = 0; i < unit_bitmap_bytes(f->grid.count); i++)
        f->done[i] |= done[i];
    film_sums_add(f->sums, sums, f->num_pixels);
    f->units_done += added;
    pthread_mutex_unlock(&f->lock);
    return true;
}

void unit_film_clear(UnitFilm *f)
{
    pthread_mutex_lock(&f->lock);
    memset(f->sums, 0, f->num_pixels * FILM_WORDS * sizeof *f->sums);
    memset(f->done, 0, unit_bitmap_bytes(f->grid.count));
    f->units_done = 0;
    pthread_mutex_unlock(&f->lock);
}

uint32_t unit_film_spp_done(UnitFilm *f)
{
    pthread_mutex_lock(&f->lock);
    uint32_t fewest = f->grid.spp;
    for (uint32_t t = 0; t < f->grid.tiles; t++) {
        uint32_t samples = 0;
        for (uint32_t b = 0; b < f->grid.blocks; b++)
            if (unit_bitmap_get(f->done, t * f->grid.blocks + b))
                samples += unit_run_block(&f->grid, (UnitRun){t * f->grid.blocks + b, 1}).num_samples;
        if (samples < fewest)
            fewest = samples;
    }
    pthread_mutex_unlock(&f->lock);
    return fewest;
}

bool unit_film_complete(UnitFilm *f)
{
    pthread_mutex_lock(&f->lock);
    bool complete = f->units_done == f->grid.count;
    pthread_mutex_unlock(&f->lock);
    return complete;
}
