// SPDX-License-Identifier: MIT
/* Work units (dist/work_units.h) and the unit film (dist/unit_film.h), on the host alone: the
 * grid covers every (pixel, sample) of a render exactly once however its units are grouped into
 * runs; its defaults and clamps; the scheduler hands every unit out exactly once to concurrent
 * takers, skips a resumed render's finished units, hands a requeued run out again and shortens its
 * runs towards the end; the film refuses a unit counted twice and reports the samples every pixel
 * holds. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "render/film.h"
#include "dist/unit_film.h"
#include "dist/work_units.h"

/* A small deterministic generator (the tests must not change from run to run). */
static uint32_t next_random(uint64_t *state)
{
    *state = *state * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(*state >> 33);
}

static uint32_t random_in(uint64_t *state, uint32_t lo, uint32_t hi) /* lo..hi inclusive */
{
    return lo + next_random(state) % (hi - lo + 1);
}

/* Adds one to covered[pixel * spp + sample] for every (pixel, sample) the run renders. */
static void cover_run(const UnitGrid *g, UnitRun run, uint8_t *covered)
{
    PixelBlock b = unit_run_block(g, run);
    cr_assert_leq((uint64_t)b.first_pixel + b.num_pixels, (uint64_t)g->width * g->height,
                  "run %u+%u: pixels past the film", run.first, run.count);
    cr_assert_leq(b.first_sample + b.num_samples, g->spp, "run %u+%u: samples past spp", run.first,
                  run.count);
    cr_assert_eq(b.first_pixel % g->width, 0, "a tile starts a row");
    cr_assert_eq(b.num_pixels % g->width, 0, "a tile holds whole rows");
    cr_assert_eq(unit_run_paths(g, run), (uint64_t)b.num_pixels * b.num_samples);
    for (uint32_t p = b.first_pixel; p < b.first_pixel + b.num_pixels; p++)
        for (uint32_t s = b.first_sample; s < b.first_sample + b.num_samples; s++)
            covered[(size_t)p * g->spp + s]++;
}

static void expect_covered_once(const UnitGrid *g, const uint8_t *covered, const char *what)
{
    size_t n = (size_t)g->width * g->height * g->spp, wrong = 0, first = 0;
    for (size_t i = 0; i < n; i++)
        if (covered[i] != 1 && wrong++ == 0)
            first = i;
    cr_assert_eq(wrong, 0,
                 "%s: %zu (pixel, sample) pairs not rendered exactly once, the first pixel %zu "
                 "sample %zu (%u times); grid %ux%u %u spp, units of %u spp x %u rows",
                 what, wrong, first / g->spp, first % g->spp, covered[first], g->width, g->height,
                 g->spp, g->unit_spp, g->unit_rows);
}

Test(work_units, runs_of_any_length_cover_every_pixel_sample_once)
{
    uint64_t rng = 20;
    for (int iter = 0; iter < 300; iter++) {
        uint32_t width = random_in(&rng, 1, 40), height = random_in(&rng, 1, 40);
        uint32_t spp = random_in(&rng, 1, 40);
        uint32_t unit_spp = random_in(&rng, 0, spp + 3), unit_rows = random_in(&rng, 0, height + 3);
        UnitGrid g;
        Error err = {0};
        cr_assert(unit_grid_init(&g, width, height, spp, unit_spp, unit_rows, &err), "%s",
                  err.message);
        cr_assert_eq(g.count, g.tiles * g.blocks);
        uint8_t *covered = calloc((size_t)width * height * spp, 1);
        cr_assert(covered);
        /* Runs of random length, never across a tile (as the scheduler hands them out). */
        for (uint32_t u = 0; u < g.count;) {
            uint32_t tile_end = (u / g.blocks + 1) * g.blocks;
            uint32_t count = random_in(&rng, 1, tile_end - u);
            cover_run(&g, (UnitRun){u, count}, covered);
            u += count;
        }
        expect_covered_once(&g, covered, "random runs");
        /* Single units, in reverse order: the same cover. */
        memset(covered, 0, (size_t)width * height * spp);
        for (uint32_t u = g.count; u-- > 0;)
            cover_run(&g, (UnitRun){u, 1}, covered);
        expect_covered_once(&g, covered, "single units");
        free(covered);
    }
}

Test(work_units, defaults_and_clamps)
{
    UnitGrid g;
    Error err = {0};
    cr_assert(unit_grid_init(&g, 1280, 960, 64, 0, 0, &err));
    cr_expect_eq(g.unit_spp, 1);
    cr_expect_eq(g.unit_rows, 480);
    cr_expect_eq(g.tiles, 2);
    cr_expect_eq(g.blocks, 64);
    cr_assert(unit_grid_init(&g, 3840, 2160, 4, 0, 0, &err));
    cr_expect_eq(g.tiles, 8);
    cr_expect_eq(g.unit_rows, 270);
    cr_assert(unit_grid_init(&g, 64, 48, 16, 0, 0, &err));
    cr_expect_eq(g.tiles, 1, "a small film is one tile");
    /* Default tiles hold at most 2^20 pixels, as few tiles as balanced rows allow. */
    uint64_t rng = 7;
    for (int i = 0; i < 200; i++) {
        uint32_t w = random_in(&rng, 1, 9000), h = random_in(&rng, 1, 9000);
        cr_assert(unit_grid_init(&g, w, h, 1, 0, 0, &err), "%s", err.message);
        cr_expect_leq((uint64_t)g.unit_rows * w, UNIT_TILE_MAX_PIXELS, "%ux%u: %u rows", w, h,
                      g.unit_rows);
        /* Balanced tiles (rows rounded up), and no fewer would fit. */
        cr_expect_eq(g.tiles, (h + g.unit_rows - 1) / g.unit_rows);
        if (g.tiles > 1) {
            uint32_t rows = (h + g.tiles - 2) / (g.tiles - 1);
            cr_expect_gt((uint64_t)rows * w, UNIT_TILE_MAX_PIXELS, "%ux%u: %u tiles", w, h,
                         g.tiles);
        }
    }
    /* Sizes above the render are clamped to it. */
    cr_assert(unit_grid_init(&g, 10, 5, 8, 100, 9, &err));
    cr_expect_eq(g.unit_spp, 8);
    cr_expect_eq(g.unit_rows, 5);
    cr_expect_eq(g.count, 1);
    /* Uneven sizes: the last tile and the last sample block hold the rest. */
    cr_assert(unit_grid_init(&g, 10, 5, 8, 3, 2, &err));
    cr_expect_eq(g.tiles, 3);
    cr_expect_eq(g.blocks, 3);
    PixelBlock last = unit_run_block(&g, (UnitRun){g.count - 1, 1});
    cr_expect_eq(last.first_pixel, 40);
    cr_expect_eq(last.num_pixels, 10);
    cr_expect_eq(last.first_sample, 6);
    cr_expect_eq(last.num_samples, 2);
    /* A device's appetite: at least one unit, at most a tile's blocks. */
    cr_expect_eq(unit_grid_units_per_window(&g, 0), 1);
    cr_expect_eq(unit_grid_units_per_window(&g, 1u << 30), g.blocks);
    cr_expect_eq(unit_grid_units_per_window(&g, 2 * 2 * 10 * 3), 2);
    /* An empty render and too many units are errors. */
    cr_expect_not(unit_grid_init(&g, 0, 5, 8, 0, 0, &err));
    cr_expect(strstr(err.message, "empty"), "%s", err.message);
    err = (Error){0};
    cr_expect_not(unit_grid_init(&g, 65536, 65536, 1u << 20, 1, 1, &err));
    cr_expect(strstr(err.message, "--unit-spp"), "%s", err.message);
}

/* Concurrent takers: each records its runs; every unit must be taken by exactly one. */
typedef struct {
    UnitScheduler *sched;
    pthread_barrier_t *start;
    uint32_t max_units;
    UnitRun runs[4096];
    uint32_t num_runs;
} Taker;

static void *take_all(void *arg)
{
    Taker *t = arg;
    pthread_barrier_wait(t->start);
    UnitRun run;
    /* No Criterion assertion here (not the test's thread): the main thread checks the runs. */
    while (t->num_runs < 4096 && unit_scheduler_take(t->sched, t->max_units, &run)) {
        t->runs[t->num_runs++] = run;
        unit_scheduler_finish(t->sched, run);
    }
    return NULL;
}

/* Counts, per unit, the runs that held it; checks every run lies in one tile. */
static void count_runs(const UnitGrid *g, const UnitRun *runs, uint32_t n, uint32_t *taken)
{
    for (uint32_t r = 0; r < n; r++) {
        cr_assert_gt(runs[r].count, 0, "an empty run");
        cr_assert_leq(runs[r].first + runs[r].count, g->count);
        cr_assert_eq(runs[r].first / g->blocks, (runs[r].first + runs[r].count - 1) / g->blocks,
                     "run %u+%u crosses a tile", runs[r].first, runs[r].count);
        for (uint32_t u = runs[r].first; u < runs[r].first + runs[r].count; u++)
            taken[u]++;
    }
}

/* Every unit taken exactly once and finished; frees taken and the scheduler. */
static void expect_each_unit_once(UnitScheduler *s, uint32_t *taken, const char *what)
{
    for (uint32_t u = 0; u < s->grid.count; u++)
        cr_assert_eq(taken[u], 1, "%s: unit %u taken %u times", what, u, taken[u]);
    cr_expect_eq(unit_scheduler_unfinished(s), 0);
    free(taken);
    unit_scheduler_free(s);
}

Test(unit_scheduler, concurrent_takers_get_every_unit_once)
{
    enum { TAKERS = 4 };
    for (int round = 0; round < 20; round++) {
        UnitGrid g;
        Error err = {0};
        cr_assert(unit_grid_init(&g, 16, 40, 300, 1, 3 + round % 5, &err));
        UnitScheduler s;
        cr_assert(unit_scheduler_init(&s, &g, TAKERS, NULL, &err));
        cr_assert_eq(unit_scheduler_unfinished(&s), g.count);
        pthread_barrier_t start;
        pthread_barrier_init(&start, NULL, TAKERS);
        static Taker takers[TAKERS];
        pthread_t threads[TAKERS];
        for (int i = 0; i < TAKERS; i++) {
            takers[i] = (Taker){.sched = &s, .start = &start, .max_units = i == 0 ? 0 : 1u + i * 3};
            cr_assert_eq(pthread_create(&threads[i], NULL, take_all, &takers[i]), 0);
        }
        for (int i = 0; i < TAKERS; i++)
            pthread_join(threads[i], NULL);
        pthread_barrier_destroy(&start);
        uint32_t *taken = calloc(g.count, sizeof *taken);
        for (int i = 0; i < TAKERS; i++) {
            count_runs(&g, takers[i].runs, takers[i].num_runs, taken);
            for (uint32_t r = 0; r < takers[i].num_runs && takers[i].max_units; r++)
                cr_expect_leq(takers[i].runs[r].count, takers[i].max_units);
        }
        char what[32];
        snprintf(what, sizeof what, "round %d", round);
        expect_each_unit_once(&s, taken, what);
    }
}

Test(unit_scheduler, done_units_are_skipped)
{
    UnitGrid g;
    Error err = {0};
    cr_assert(unit_grid_init(&g, 8, 30, 50, 1, 4, &err));
    uint8_t *done = calloc(unit_bitmap_bytes(g.count), 1);
    uint64_t rng = 3;
    uint32_t num_done = 0;
    for (uint32_t u = 0; u < g.count; u++)
        if (next_random(&rng) % 3 == 0)
            unit_bitmap_set(done, u), num_done++;
    unit_bitmap_set(done, 0); /* the cursor starts on a done unit */
    num_done = 0;
    for (uint32_t u = 0; u < g.count; u++)
        num_done += unit_bitmap_get(done, u);
    UnitScheduler s;
    cr_assert(unit_scheduler_init(&s, &g, 2, done, &err));
    cr_expect_eq(unit_scheduler_unfinished(&s), g.count - num_done);
    uint32_t *taken = calloc(g.count, sizeof *taken);
    UnitRun run;
    while (unit_scheduler_take(&s, 0, &run)) {
        count_runs(&g, &run, 1, taken);
        unit_scheduler_finish(&s, run);
    }
    for (uint32_t u = 0; u < g.count; u++)
        cr_assert_eq(taken[u], unit_bitmap_get(done, u) ? 0u : 1u, "unit %u taken %u times", u,
                     taken[u]);
    cr_expect_eq(unit_scheduler_unfinished(&s), 0);
    free(taken);
    free(done);
    unit_scheduler_free(&s);
}

Test(unit_scheduler, requeued_runs_are_handed_out_again)
{
    UnitGrid g;
    Error err = {0};
    cr_assert(unit_grid_init(&g, 4, 12, 40, 1, 3, &err));
    UnitScheduler s;
    cr_assert(unit_scheduler_init(&s, &g, 3, NULL, &err));
    UnitRun a, b, c;
    cr_assert(unit_scheduler_take(&s, 5, &a));
    cr_assert(unit_scheduler_take(&s, 5, &b));
    cr_assert(unit_scheduler_take(&s, 5, &c));
    unit_scheduler_finish(&s, a);
    unit_scheduler_finish(&s, c);
    unit_scheduler_requeue(&s, b); /* its taker failed */
    unit_scheduler_requeue(&s, a); /* finished already: stays finished */
    cr_expect_eq(unit_scheduler_unfinished(&s), g.count - a.count - c.count);
    uint32_t *taken = calloc(g.count, sizeof *taken);
    count_runs(&g, &a, 1, taken);
    count_runs(&g, &c, 1, taken);
    UnitRun run;
    cr_assert(unit_scheduler_take(&s, 0, &run));
    cr_expect_eq(run.first, b.first, "the requeued run comes first: %u, not %u", run.first,
                 b.first);
    do {
        count_runs(&g, &run, 1, taken);
        unit_scheduler_finish(&s, run);
    } while (unit_scheduler_take(&s, 0, &run));
    expect_each_unit_once(&s, taken, "after a requeue");
}

Test(unit_scheduler, guided_runs_shrink_towards_the_end)
{
    UnitGrid g;
    Error err = {0};
    cr_assert(unit_grid_init(&g, 4, 4, 1000, 1, 0, &err)); /* one tile of 1000 units */
    UnitScheduler s;
    cr_assert(unit_scheduler_init(&s, &g, 2, NULL, &err));
    UnitRun run, prev = {0, UINT32_MAX};
    uint32_t runs = 0, total = 0;
    while (unit_scheduler_take(&s, 0, &run)) {
        cr_expect_leq(run.count, prev.count, "run %u: %u units after %u", runs, run.count,
                      prev.count);
        if (runs == 0)
            cr_expect_geq(run.count, g.count / 8, "the first run is long: %u units", run.count);
        total += run.count, runs++, prev = run;
        unit_scheduler_finish(&s, run);
    }
    cr_expect_eq(total, g.count);
    cr_expect_eq(prev.count, 1, "the last run is one unit");
    cr_expect_lt(runs, g.count / 10, "guided: far fewer runs (%u) than units", runs);
    unit_scheduler_free(&s);
}

/* Every sum word of a film of `pixels` pixels = value. */
static void fill_sums(uint64_t *sums, size_t pixels, uint64_t value)
{
    for (size_t i = 0; i < pixels * FILM_WORDS; i++)
        sums[i] = value;
}

Test(unit_film, merge_refuses_a_unit_twice_and_keeps_the_film)
{
    UnitGrid g;
    Error err = {0};
    cr_assert(unit_grid_init(&g, 3, 4, 8, 2, 2, &err)); /* 2 tiles x 4 blocks */
    UnitFilm f;
    cr_assert(unit_film_init(&f, &g, &err));
    size_t pixels = f.num_pixels, bytes = unit_bitmap_bytes(g.count);
    uint64_t *sums = malloc(pixels * FILM_BYTES_PER_PIXEL);
    uint8_t *done = calloc(bytes, 1);
    fill_sums(sums, pixels, 5);
    unit_bitmap_set(done, 0), unit_bitmap_set(done, 2);
    cr_assert(unit_film_merge(&f, sums, done, &err), "%s", err.message);
    cr_expect_eq(f.units_done, 2);
    uint64_t *before_sums = malloc(pixels * FILM_BYTES_PER_PIXEL);
    uint8_t *before_done = malloc(bytes);
    memcpy(before_sums, f.sums, pixels * FILM_BYTES_PER_PIXEL);
    memcpy(before_done, f.done, bytes);
    /* Units 3 (new) and 2 (already in): refused, nothing added. */
    memset(done, 0, bytes);
    unit_bitmap_set(done, 3), unit_bitmap_set(done, 2);
    fill_sums(sums, pixels, 7);
    cr_expect_not(unit_film_merge(&f, sums, done, &err));
    cr_expect(strstr(err.message, "unit 2"), "the error names the unit: %s", err.message);
    cr_expect_eq(f.units_done, 2);
    cr_expect_eq(memcmp(f.sums, before_sums, pixels * FILM_BYTES_PER_PIXEL), 0, "sums changed");
    cr_expect_eq(memcmp(f.done, before_done, bytes), 0, "done units changed");
    /* Unit 3 alone goes in: the sums add. */
    memset(done, 0, bytes);
    unit_bitmap_set(done, 3);
    err = (Error){0};
    cr_assert(unit_film_merge(&f, sums, done, &err), "%s", err.message);
    cr_expect_eq(f.units_done, 3);
    cr_expect_eq(f.sums[0], 12);
    cr_expect_eq(f.sums[pixels * FILM_WORDS - 1], 12);
    unit_film_clear(&f);
    cr_expect_eq(f.units_done, 0);
    cr_expect_eq(f.sums[0], 0);
    cr_expect(unit_film_merge(&f, sums, done, &err), "a cleared film takes unit 3 again");
    free(sums), free(done), free(before_sums), free(before_done);
    unit_film_free(&f);
}

static void add_units(UnitFilm *f, const uint32_t *units, size_t n)
{
    uint8_t *done = calloc(unit_bitmap_bytes(f->grid.count), 1);
    uint64_t *sums = calloc(f->num_pixels, FILM_BYTES_PER_PIXEL);
    for (size_t i = 0; i < n; i++)
        unit_bitmap_set(done, units[i]);
    Error err = {0};
    cr_assert(unit_film_merge(f, sums, done, &err), "%s", err.message);
    free(done), free(sums);
}

Test(unit_film, spp_done_is_the_fewest_of_any_tile)
{
    UnitGrid g;
    Error err = {0};
    /* 2 tiles x 4 sample blocks of 3, 3, 3 and 1 samples. */
    cr_assert(unit_grid_init(&g, 4, 4, 10, 3, 2, &err));
    cr_assert_eq(g.tiles, 2);
    cr_assert_eq(g.blocks, 4);
    UnitFilm f;
    cr_assert(unit_film_init(&f, &g, &err));
    cr_expect_eq(unit_film_spp_done(&f), 0);
    add_units(&f, (uint32_t[]){0, 1, 3}, 3); /* tile 0: 3 + 3 + 1 */
    cr_expect_eq(unit_film_spp_done(&f), 0, "tile 1 has nothing");
    add_units(&f, (uint32_t[]){4}, 1); /* tile 1: 3 */
    cr_expect_eq(unit_film_spp_done(&f), 3);
    add_units(&f, (uint32_t[]){5, 6, 7}, 3); /* tile 1: 10 */
    cr_expect_eq(unit_film_spp_done(&f), 7);
    cr_expect_not(unit_film_complete(&f));
    add_units(&f, (uint32_t[]){2}, 1);
    cr_expect_eq(unit_film_spp_done(&f), 10);
    cr_expect(unit_film_complete(&f));
    unit_film_free(&f);
}
