// SPDX-License-Identifier: MIT
/* Material sort (host/parallel/material_sort.c, cl/parallel/sort_materials.cl) against a serial stable counting sort:
 * the output list equals the reference entry for entry (so grouping, key order, misses last and
 * stability are all checked), entries past n are not written and the input list is left alone.
 * For list sizes around the tile (4096 entries with work-groups of 256), 1 to 20000 materials
 * (local and global key counts), misses mixed in, one key only, misses only, runs of one key as
 * coherent rays give, small work-groups (many tiles, a multi-level scan of the counts) and a reused
 * sorter. The active list is a random permutation of the slots: nothing may assume it ascends. */
#include <criterion/criterion.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "parallel/material_sort.h"
#include "support.h"
#include "xorshift.h"

#define SENTINEL 0xdeadbeefu

static const uint32_t sizes[] = {0, 1, 255, 256, 257, 4097, (1u << 20) + 3};
#define NUM_SIZES (sizeof sizes / sizeof sizes[0])
#define MAX_SIZE ((1u << 20) + 3)
static const uint32_t material_counts[] = {1, 2, 7, 300, 4096};
#define NUM_MATERIAL_COUNTS (sizeof material_counts / sizeof material_counts[0])

typedef enum { KEYS_RANDOM, KEYS_ONE, KEYS_ALL_MISS, KEYS_RUNS } KeyMode;

static uint64_t rng_state; /* the seed is in every failure message */

static uint32_t rng_next(void) { return xorshift_next(&rng_state); }

typedef struct {
    Device *dev;
    uint32_t capacity;
    cl_mem hit, material_ids, active_in, active_out;
    cl_float4 *host_hit;
    uint32_t *host_material_ids, *slot_keys, *active, *expected, *actual, *key_starts;
} Fixture;

/* Triangles per material in the generated scenes; triangle t has material t % num_materials. */
#define TRIANGLES_PER_MATERIAL 3
#define MAX_MATERIALS 20000

static Fixture fixture_open(uint32_t capacity)
{
    Fixture f = {.dev = test_device(), .capacity = capacity};
    Error err = {0};
    size_t slots = capacity + 1; /* room for the sentinel past n */
    size_t triangles = (size_t)MAX_MATERIALS * TRIANGLES_PER_MATERIAL;
    f.hit = device_buffer(f.dev, "hit", CL_MEM_READ_ONLY, slots * sizeof(cl_float4), NULL, &err);
    f.material_ids = device_buffer(f.dev, "material_ids", CL_MEM_READ_ONLY,
                                   triangles * sizeof(uint32_t), NULL, &err);
    f.active_in = device_buffer(f.dev, "active_in", CL_MEM_READ_ONLY, slots * sizeof(uint32_t),
                                NULL, &err);
    f.active_out = device_buffer(f.dev, "active_out", CL_MEM_READ_WRITE, slots * sizeof(uint32_t),
                                 NULL, &err);
    cr_assert(f.hit && f.material_ids && f.active_in && f.active_out, "%s", err.message);
    f.host_hit = malloc(slots * sizeof *f.host_hit);
    f.host_material_ids = malloc(triangles * sizeof(uint32_t));
    f.slot_keys = malloc(slots * sizeof(uint32_t));
    f.active = malloc(slots * sizeof(uint32_t));
    f.expected = malloc(slots * sizeof(uint32_t));
    f.actual = malloc(slots * sizeof(uint32_t));
    f.key_starts = malloc((MAX_MATERIALS + 2) * sizeof(uint32_t));
    cr_assert(f.host_hit && f.host_material_ids && f.slot_keys && f.active && f.expected &&
              f.actual && f.key_starts);
    return f;
}

static void fixture_close(Fixture *f)
{
    cl_mem buffers[] = {f->hit, f->material_ids, f->active_in, f->active_out};
    for (size_t i = 0; i < sizeof buffers / sizeof buffers[0]; i++)
        CL_CHECK(clReleaseMemObject(buffers[i]));
    free(f->host_hit), free(f->host_material_ids), free(f->slot_keys), free(f->active);
    free(f->expected), free(f->actual), free(f->key_starts);
    test_device_release(f->dev);
}

/* A hit for each of n slots: a miss (key num_materials) or a triangle, chosen by mode; the slot's
 * expected key goes to slot_keys. KEYS_ONE: every slot hits material num_materials / 2. KEYS_RUNS:
 * the material changes about every 50 slots and one slot in 10 misses. */
static void make_hits(Fixture *f, uint32_t n, uint32_t num_materials, KeyMode mode)
{
    uint32_t triangles = num_materials * TRIANGLES_PER_MATERIAL;
    for (uint32_t t = 0; t < triangles; t++)
        f->host_material_ids[t] = t % num_materials;
    uint32_t run_triangle = 0;
    for (uint32_t slot = 0; slot < n; slot++) {
        uint32_t triangle = rng_next() % triangles;
        if (mode == KEYS_ONE)
            triangle = num_materials / 2 + num_materials * (rng_next() % TRIANGLES_PER_MATERIAL);
        if (mode == KEYS_RUNS) {
            if (rng_next() % 50 == 0)
                run_triangle = rng_next() % triangles;
            triangle = run_triangle;
        }
        bool miss = mode == KEYS_ALL_MISS || (mode == KEYS_RANDOM && rng_next() % 4 == 0) ||
                    (mode == KEYS_RUNS && rng_next() % 10 == 0);
        uint32_t prim = miss ? HIT_NONE : triangle;
        f->host_hit[slot] = (cl_float4){{(float)(rng_next() % 1000), 0.25f, 0.5f, 0.0f}};
        memcpy(&f->host_hit[slot].s[3], &prim, sizeof prim);
        f->slot_keys[slot] = miss ? num_materials : f->host_material_ids[triangle];
    }
    device_write(f->dev, f->hit, 0, (size_t)n * sizeof(cl_float4), f->host_hit);
    device_write(f->dev, f->material_ids, 0, (size_t)triangles * sizeof(uint32_t),
                 f->host_material_ids);
}

/* active[0..n): a random permutation of the slots, or ascending (as compaction leaves it). */
static void make_active(Fixture *f, uint32_t n, bool ascending)
{
    for (uint32_t i = 0; i < n; i++)
        f->active[i] = i;
    for (uint32_t i = n; i > 1 && !ascending; i--) {
        uint32_t j = rng_next() % i, swap = f->active[i - 1];
        f->active[i - 1] = f->active[j], f->active[j] = swap;
    }
    device_write(f->dev, f->active_in, 0, (size_t)n * sizeof(uint32_t), f->active);
}

/* The serial stable counting sort of active[0..n) by slot key (keys 0..num_materials). */
static void reference_sort(Fixture *f, uint32_t n, uint32_t num_materials)
{
    uint32_t *starts = f->key_starts;
    memset(starts, 0, (num_materials + 2) * sizeof *starts);
    for (uint32_t i = 0; i < n; i++)
        starts[f->slot_keys[f->active[i]] + 1]++;
    for (uint32_t k = 0; k <= num_materials; k++)
        starts[k + 1] += starts[k];
    for (uint32_t i = 0; i < n; i++)
        f->expected[starts[f->slot_keys[f->active[i]]]++] = f->active[i];
}

/* Sorts fresh keys of size n on the device with sorter s and compares with the reference. */
static void check_sort(Fixture *f, MaterialSorter *s, uint32_t n, uint32_t num_materials,
                       KeyMode mode, uint64_t seed, bool ascending)
{
    rng_state = seed | 1;
    make_hits(f, n, num_materials, mode);
    make_active(f, n, ascending);
    reference_sort(f, n, num_materials);
    uint32_t sentinel = SENTINEL;
    CL_CHECK(clEnqueueFillBuffer(f->dev->queue, f->active_out, &sentinel, sizeof sentinel, 0,
                                 ((size_t)f->capacity + 1) * sizeof sentinel, 0, NULL, NULL));
    material_sorter_run(s, f->hit, f->material_ids, f->active_in, f->active_out, n);
#define CONTEXT_FORMAT "; n %u, %u materials, mode %d, seed %llu, group size %zu"
#define CONTEXT n, num_materials, (int)mode, (unsigned long long)seed, material_sorter_group_size(s)
    device_read(f->dev, f->active_out, 0, ((size_t)n + 1) * sizeof(uint32_t), f->actual);
    for (uint32_t i = 0; i < n; i++)
        if (f->actual[i] != f->expected[i])
            cr_assert_fail("out[%u] = %u (key %u), expected %u (key %u)" CONTEXT_FORMAT, i,
                           f->actual[i], f->actual[i] < n ? f->slot_keys[f->actual[i]] : 0u,
                           f->expected[i], f->slot_keys[f->expected[i]], CONTEXT);
    cr_assert_eq(f->actual[n], SENTINEL, "out[%u] written past n" CONTEXT_FORMAT, n, CONTEXT);
    device_read(f->dev, f->active_in, 0, (size_t)n * sizeof(uint32_t), f->actual);
    cr_assert(memcmp(f->actual, f->active, (size_t)n * sizeof(uint32_t)) == 0,
              "the input list changed" CONTEXT_FORMAT, CONTEXT);
#undef CONTEXT
#undef CONTEXT_FORMAT
}

static MaterialSorter *sorter_open(Fixture *f, uint32_t num_materials, size_t group_size)
{
    Error err = {0};
    MaterialSorter *s =
        material_sorter_create_sized(f->dev, f->capacity, num_materials, group_size, &err);
    cr_assert(s, "material_sorter_create: %s", err.message);
    return s;
}

/* Every size for each material count in counts, in one mode. */
static void check_all_sizes(const uint32_t *counts, size_t num_counts, KeyMode mode)
{
    Fixture f = fixture_open(MAX_SIZE);
    for (size_t m = 0; m < num_counts; m++) {
        MaterialSorter *s = sorter_open(&f, counts[m], 0);
        for (size_t i = 0; i < NUM_SIZES; i++)
            check_sort(&f, s, sizes[i], counts[m], mode, 100 * m + i, false);
        material_sorter_destroy(s);
    }
    fixture_close(&f);
}

Test(material_sort, random_keys_with_misses)
{
    check_all_sizes(material_counts, NUM_MATERIAL_COUNTS, KEYS_RANDOM);
}

Test(material_sort, all_one_key) { check_all_sizes(material_counts, NUM_MATERIAL_COUNTS, KEYS_ONE); }

Test(material_sort, all_miss)
{
    const uint32_t counts[] = {1, 300, 4096};
    check_all_sizes(counts, 3, KEYS_ALL_MISS);
}

/* Ascending slots with long runs of one material, as coherent camera rays leave them: runs cross
 * the work items' chunks of 16 entries and the tiles. */
Test(material_sort, coherent_runs_in_ascending_list)
{
    Fixture f = fixture_open(MAX_SIZE);
    for (size_t m = 0; m < NUM_MATERIAL_COUNTS; m++) {
        MaterialSorter *s = sorter_open(&f, material_counts[m], 0);
        for (size_t i = 0; i < NUM_SIZES; i++)
            check_sort(&f, s, sizes[i], material_counts[m], KEYS_RUNS, 700 + 10 * m + i, true);
        material_sorter_destroy(s);
    }
    fixture_close(&f);
}

/* More keys than the local table takes: counts added with global atomics. */
Test(material_sort, many_materials_count_in_global_memory)
{
    Fixture f = fixture_open(MAX_SIZE);
    MaterialSorter *s = sorter_open(&f, MAX_MATERIALS, 0);
    cr_expect(!material_sorter_local_histogram(s), "20000 materials counted in local memory");
    const uint32_t some_sizes[] = {1, 257, 4097, 65537, MAX_SIZE};
    for (size_t i = 0; i < sizeof some_sizes / sizeof some_sizes[0]; i++) {
        check_sort(&f, s, some_sizes[i], MAX_MATERIALS, KEYS_RANDOM, 300 + i, false);
        check_sort(&f, s, some_sizes[i], MAX_MATERIALS, KEYS_RUNS, 400 + i, true);
    }
    material_sorter_destroy(s);
    fixture_close(&f);
}

/* Small work-groups: small tiles, so many of them, and counts that need several scan levels. */
Test(material_sort, any_power_of_two_group_size)
{
    const size_t group_sizes[] = {1, 2, 8, 32, 64, 128};
    const uint32_t small_sizes[] = {1, 15, 16, 17, 255, 4097, 20000};
    const uint32_t counts[] = {1, 7, 300};
    bool saw_multi_level = false;
    Fixture f = fixture_open(20000);
    for (size_t g = 0; g < sizeof group_sizes / sizeof group_sizes[0]; g++) {
        for (size_t m = 0; m < 3; m++) {
            MaterialSorter *s = sorter_open(&f, counts[m], group_sizes[g]);
            size_t actual = material_sorter_group_size(s);
            cr_assert(actual > 0 && (actual & (actual - 1)) == 0 && actual <= group_sizes[g],
                      "group size %zu for a request of %zu", actual, group_sizes[g]);
            for (size_t i = 0; i < sizeof small_sizes / sizeof small_sizes[0]; i++) {
                saw_multi_level |= material_sorter_launches(s, small_sizes[i]) > 3;
                check_sort(&f, s, small_sizes[i], counts[m], KEYS_RANDOM, 31 * g + 7 * m + i,
                           false);
            }
            material_sorter_destroy(s);
        }
    }
    cr_expect(saw_multi_level, "no case needed more than one scan launch");
    fixture_close(&f);
}

/* One sorter, many calls of different sizes in a row, larger and smaller than before. */
Test(material_sort, reused_sorter_with_changing_n)
{
    Fixture f = fixture_open(MAX_SIZE);
    MaterialSorter *s = sorter_open(&f, 7, 0);
    const uint32_t order[] = {MAX_SIZE, 3, 0, 65537, 1, 4096, 257, 0, 4097, 100000};
    for (size_t i = 0; i < sizeof order / sizeof order[0]; i++)
        check_sort(&f, s, order[i], 7, i % 2 ? KEYS_RANDOM : KEYS_RUNS, 500 + i, i % 3 == 0);
    material_sorter_destroy(s);
    fixture_close(&f);
}

/* The profile hook adds device time and leaves the result alone. */
Test(material_sort, profile_adds_device_time)
{
    Fixture f = fixture_open(4097);
    MaterialSorter *s = sorter_open(&f, 300, 0);
    double ms = 0.0;
    material_sorter_set_profile(s, &ms);
    check_sort(&f, s, 4097, 300, KEYS_RANDOM, 42, false);
    cr_expect(ms > 0.0, "profiled time %g ms", ms);
    material_sorter_destroy(s);
    fixture_close(&f);
}

Test(material_sort, too_many_materials_is_an_error)
{
    Device *dev = test_device();
    Error err = {0};
    MaterialSorter *s = material_sorter_create(dev, 1024, MATERIAL_SORT_MAX_MATERIALS + 1, &err);
    cr_expect_null(s);
    cr_expect_eq(err.code, ERR_TOO_LARGE);
    test_device_release(dev);
}
