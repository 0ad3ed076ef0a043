// SPDX-License-Identifier: MIT
#include "dist/work_units.h"

#include <stdlib.h>
#include <string.h>

bool unit_grid_init(UnitGrid *g, uint32_t width, uint32_t height, uint32_t spp, uint32_t unit_spp,
                    uint32_t unit_rows, Error *err)
{
    memset(g, 0, sizeof *g);
    if (width == 0 || height == 0 || spp == 0) {
        error_set(err, ERR_SETTINGS, NULL, 0, "work units: an empty render (%ux%u, %u spp)", width,
                  height, spp);
        return false;
    }
    if (unit_rows == 0) {
        uint64_t pixels = (uint64_t)width * height;
        uint64_t tiles = (pixels + UNIT_TILE_MAX_PIXELS - 1) / UNIT_TILE_MAX_PIXELS;
        unit_rows = (uint32_t)((height + tiles - 1) / tiles);
        /* Rounding the rows up can overfill a tile (6174x5940: 35 tiles of 170 rows hold
         * 1049580 pixels): add tiles until each fits (a row wider than the limit stays one). */
        while ((uint64_t)unit_rows * width > UNIT_TILE_MAX_PIXELS && unit_rows > 1)
            tiles++, unit_rows = (uint32_t)((height + tiles - 1) / tiles);
    }
    if (unit_spp == 0)
        unit_spp = UNIT_DEFAULT_SPP;
    g->width = width, g->height = height, g->spp = spp;
    g->unit_rows = unit_rows < height ? unit_rows : height;
    g->unit_spp = unit_spp < spp ? unit_spp : spp;
    g->tiles = (height + g->unit_rows - 1) / g->unit_rows;
    g->blocks = (spp + g->unit_spp - 1) / g->unit_spp;
    uint64_t count = (uint64_t)g->tiles * g->blocks;
    if (count > UINT32_MAX / 2) {
        error_set(err, ERR_SETTINGS, NULL, 0,
                  "work units: %llu units (%u tiles x %u sample blocks) are too many: raise "
                  "--unit-spp or --unit-rows", (unsigned long long)count, g->tiles, g->blocks);
        return false;
    }
    g->count = (uint32_t)count;
    return true;
}

PixelBlock unit_run_block(const UnitGrid *g, UnitRun run)
{
    uint32_t tile = run.first / g->blocks, block = run.first % g->blocks;
    uint32_t row = tile * g->unit_rows;
    uint32_t rows = g->height - row < g->unit_rows ? g->height - row : g->unit_rows;
    uint32_t first_sample = block * g->unit_spp;
    uint32_t end_sample = (block + run.count) * g->unit_spp;
    if (end_sample > g->spp)
        end_sample = g->spp;
    return (PixelBlock){.first_pixel = row * g->width,
                        .num_pixels = rows * g->width,
                        .first_sample = first_sample,
                        .num_samples = end_sample - first_sample};
}

uint64_t unit_run_paths(const UnitGrid *g, UnitRun run)
{
    PixelBlock b = unit_run_block(g, run);
    return (uint64_t)b.num_pixels * b.num_samples;
}

uint32_t unit_grid_units_per_window(const UnitGrid *g, uint64_t window_samples)
{
    uint64_t unit = (uint64_t)g->unit_rows * g->width * g->unit_spp;
    uint64_t n = window_samples / unit;
    return n < 1 ? 1 : n > g->blocks ? g->blocks : (uint32_t)n;
}

bool unit_scheduler_init(UnitScheduler *s, const UnitGrid *g, uint32_t takers, const uint8_t *done,
                         Error *err)
{
    memset(s, 0, sizeof *s);
    s->grid = *g;
    s->takers = takers ? takers : 1;
    s->state = calloc(g->count, 1);
    if (!s->state) {
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for %u work units", g->count);
        return false;
    }
    for (uint32_t u = 0; u < g->count; u++)
        if (done && unit_bitmap_get(done, u))
            s->state[u] = UNIT_DONE;
        else
            s->todo++;
    s->unfinished = s->todo;
    pthread_mutex_init(&s->lock, NULL);
    return true;
}

void unit_scheduler_free(UnitScheduler *s)
{
    if (s->state)
        pthread_mutex_destroy(&s->lock);
    free(s->state);
    memset(s, 0, sizeof *s);
}

bool unit_scheduler_take(UnitScheduler *s, uint32_t max_units, UnitRun *run)
{
    pthread_mutex_lock(&s->lock);
    while (s->cursor < s->grid.count && s->state[s->cursor] != UNIT_TODO)
        s->cursor++;
    bool found = s->cursor < s->grid.count;
    if (found) {
        /* Guided self-scheduling: an even share of what is left, so that early runs are long
         * (few requests, full devices) and the last ones short (the devices finish together); a
         * lone taker takes whole windows to the end. */
        uint32_t n = (s->todo + s->takers - 1) / s->takers;
        if (max_units && n > max_units)
            n = max_units;
        uint32_t first = s->cursor, tile_end = (first / s->grid.blocks + 1) * s->grid.blocks;
        uint32_t count = 0;
        while (count < n && first + count < tile_end && s->state[first + count] == UNIT_TODO)
            s->state[first + count++] = UNIT_TAKEN;
        s->todo -= count;
        *run = (UnitRun){first, count};
    }
    pthread_mutex_unlock(&s->lock);
    return found;
}

void unit_scheduler_finish(UnitScheduler *s, UnitRun run)
{
    pthread_mutex_lock(&s->lock);
    for (uint32_t u = run.first; u < run.first + run.count; u++)
        if (s->state[u] == UNIT_TAKEN) {
            s->state[u] = UNIT_DONE;
            s->unfinished--;
        }
    pthread_mutex_unlock(&s->lock);
}

void unit_scheduler_requeue(UnitScheduler *s, UnitRun run)
{
    pthread_mutex_lock(&s->lock);
    for (uint32_t u = run.first; u < run.first + run.count; u++)
        if (s->state[u] == UNIT_TAKEN) {
            s->state[u] = UNIT_TODO;
            s->todo++;
        }
    if (run.first < s->cursor)
        s->cursor = run.first;
    pthread_mutex_unlock(&s->lock);
}

uint32_t unit_scheduler_unfinished(UnitScheduler *s)
{
    pthread_mutex_lock(&s->lock);
    uint32_t n = s->unfinished;
    pthread_mutex_unlock(&s->lock);
    return n;
}
