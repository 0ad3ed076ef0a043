// SPDX-License-Identifier: MIT
/* Stream compaction (host/parallel/compact.c, cl/parallel/scan.cl) against a serial reference: the count is exact,
 * the indices are the alive slots in increasing order, nothing past the count is written, and this
 * holds for sizes around every tile boundary, all densities, flag values other than 1, work-group
 * sizes from 1 up (small groups force several scan levels), and a reused compactor. */
#include <criterion/criterion.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "parallel/compact.h"
#include "support.h"

#define SENTINEL 0xdeadbeefu

/* 8191..8193: around the flag tile of the default work-group size (32 x 256). */
static const uint32_t sizes[] = {0, 1, 2, 255, 256, 257, 1023, 1024, 1025, 4097, 8191, 8192, 8193,
                                 65537, (1u << 20) + 3};
#define NUM_SIZES (sizeof sizes / sizeof sizes[0])
#define MAX_SIZE ((1u << 20) + 3)

static uint64_t rng_state;

static uint32_t rng_next(void)
{
    /* xorshift64*: reproducible across runs (the seed is in every failure message). */
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (uint32_t)((rng_state * 0x2545f4914f6cdd1dull) >> 32);
}

/* Alive with probability density; alive flags take arbitrary nonzero values (1, 2, 0x80000000,
 * 0xffffffff, random) because the contract is "nonzero = alive". */
static void random_flags(uint32_t *flags, uint32_t n, double density, uint64_t seed)
{
    rng_state = seed | 1;
    const uint32_t threshold = (uint32_t)(density * 4294967295.0);
    for (uint32_t i = 0; i < n; i++) {
        bool alive = density >= 1.0 || (density > 0.0 && rng_next() < threshold);
        uint32_t value = 0;
        if (alive) {
            const uint32_t choices[] = {1u, 2u, 0x80000000u, 0xffffffffu, rng_next() | 1u};
            value = choices[rng_next() % 5];
        }
        flags[i] = value;
    }
}

static uint32_t reference_compact(const uint32_t *flags, uint32_t n, uint32_t *indices)
{
    uint32_t count = 0;
    for (uint32_t i = 0; i < n; i++)
        if (flags[i] != 0)
            indices[count++] = i;
    return count;
}

typedef struct {
    Device *dev;
    Compactor *compactor;
    cl_mem flags, indices;
    uint32_t *host_flags, *expected, *actual;
    uint32_t capacity;
} Fixture;

static Fixture fixture_open(uint32_t capacity, size_t group_size)
{
    Fixture f = {.dev = test_device(), .capacity = capacity};
    Error err = {0};
    f.compactor = compactor_create_sized(f.dev, capacity, group_size, &err);
    cr_assert(f.compactor, "compactor_create: %s", err.message);
    f.flags = device_buffer(f.dev, "flags", CL_MEM_READ_ONLY, capacity * sizeof(uint32_t), NULL, &err);
    f.indices = device_buffer(f.dev, "indices", CL_MEM_READ_WRITE, capacity * sizeof(uint32_t), NULL,
                              &err);
    cr_assert(f.flags && f.indices, "%s", err.message);
    size_t bytes = (capacity + 1) * sizeof(uint32_t);
    f.host_flags = malloc(bytes), f.expected = malloc(bytes), f.actual = malloc(bytes);
    cr_assert(f.host_flags && f.expected && f.actual);
    return f;
}

static void fixture_close(Fixture *f)
{
    compactor_destroy(f->compactor);
    CL_CHECK(clReleaseMemObject(f->flags));
    CL_CHECK(clReleaseMemObject(f->indices));
    free(f->host_flags), free(f->expected), free(f->actual);
    test_device_release(f->dev);
}

/* Compacts fresh random flags of size n on the device and compares with the reference, then the
 * free list (compactor_enqueue_free) likewise. The index buffer is filled with a sentinel first,
 * so a write past the count is caught too. */
static void check_compaction(Fixture *f, uint32_t n, double density, uint64_t seed)
{
    random_flags(f->host_flags, n, density, seed);
    device_write(f->dev, f->flags, 0, n * sizeof(uint32_t), f->host_flags);
    uint32_t sentinel = SENTINEL;
    CL_CHECK(clEnqueueFillBuffer(f->dev->queue, f->indices, &sentinel, sizeof sentinel, 0,
                                 f->capacity * sizeof(uint32_t), 0, NULL, NULL));
    uint32_t expected_count = reference_compact(f->host_flags, n, f->expected);
    uint32_t count = compactor_run(f->compactor, f->flags, f->indices, n);
#define CONTEXT_FORMAT "; n %u, density %g, seed %llu, group size %zu"
#define CONTEXT n, density, (unsigned long long)seed, compactor_group_size(f->compactor)
    cr_assert_eq(count, expected_count, "count %u, expected %u" CONTEXT_FORMAT, count,
                 expected_count, CONTEXT);
    uint32_t readback = n < f->capacity ? n + 1 : n; /* one slot past the count: untouched */
    device_read(f->dev, f->indices, 0, readback * sizeof(uint32_t), f->actual);
    for (uint32_t i = 0; i < count; i++)
        if (f->actual[i] != f->expected[i])
            cr_assert_fail("indices[%u] = %u, expected %u" CONTEXT_FORMAT, i, f->actual[i],
                           f->expected[i], CONTEXT);
    for (uint32_t i = count; i < readback; i++)
        if (f->actual[i] != SENTINEL)
            cr_assert_fail("indices[%u] written past the count %u" CONTEXT_FORMAT, i, count,
                           CONTEXT);

    /* The free list of the same compaction: the dead slots, ascending, n - count of them. */
    uint32_t num_free = 0;
    for (uint32_t i = 0; i < n; i++)
        if (!f->host_flags[i])
            f->expected[num_free++] = i;
    CL_CHECK(clEnqueueFillBuffer(f->dev->queue, f->indices, &sentinel, sizeof sentinel, 0,
                                 f->capacity * sizeof(uint32_t), 0, NULL, NULL));
    compactor_enqueue_free(f->compactor, f->indices);
    device_read(f->dev, f->indices, 0, readback * sizeof(uint32_t), f->actual);
    for (uint32_t i = 0; i < num_free; i++)
        if (f->actual[i] != f->expected[i])
            cr_assert_fail("free[%u] = %u, expected %u" CONTEXT_FORMAT, i, f->actual[i],
                           f->expected[i], CONTEXT);
    for (uint32_t i = num_free; i < readback; i++)
        if (f->actual[i] != SENTINEL)
            cr_assert_fail("free[%u] written past the %u free slots" CONTEXT_FORMAT, i, num_free,
                           CONTEXT);
#undef CONTEXT
#undef CONTEXT_FORMAT
}

static void check_all_sizes(double density)
{
    Fixture f = fixture_open(MAX_SIZE, 0);
    for (size_t s = 0; s < NUM_SIZES; s++)
        check_compaction(&f, sizes[s], density, 1000 + s);
    fixture_close(&f);
}

Test(scan, all_dead) { check_all_sizes(0.0); }
Test(scan, all_alive) { check_all_sizes(1.0); }
Test(scan, half_alive) { check_all_sizes(0.5); }
Test(scan, one_percent_alive) { check_all_sizes(0.01); }

/* Every power-of-two work-group size is correct; the small ones take several scan levels. */
Test(scan, any_power_of_two_group_size)
{
    const size_t group_sizes[] = {1, 2, 4, 8, 32, 64, 128, 512, 2048};
    const uint32_t small_sizes[] = {1, 31, 32, 33, 255, 256, 257, 4097, 65537};
    bool saw_multi_level = false;
    for (size_t g = 0; g < sizeof group_sizes / sizeof group_sizes[0]; g++) {
        Fixture f = fixture_open(65537, group_sizes[g]);
        size_t actual = compactor_group_size(f.compactor);
        cr_assert(actual > 0 && (actual & (actual - 1)) == 0 && actual <= group_sizes[g],
                  "group size %zu for a request of %zu", actual, group_sizes[g]);
        for (size_t s = 0; s < sizeof small_sizes / sizeof small_sizes[0]; s++) {
            uint32_t n = small_sizes[s];
            saw_multi_level |= compactor_launches(f.compactor, n) > 3;
            check_compaction(&f, n, 0.5, 7 * g + s);
            check_compaction(&f, n, 0.97, 11 * g + s);
        }
        fixture_close(&f);
    }
    cr_expect(saw_multi_level, "no case needed more than one scan level");
}

/* One compactor, many calls of different sizes in a row, larger and smaller than before. */
Test(scan, reused_compactor_with_changing_n)
{
    Fixture f = fixture_open(MAX_SIZE, 0);
    const uint32_t order[] = {MAX_SIZE, 3, 0, 65537, 1, (1u << 20) + 3, 257, 0, 4097, 100000};
    for (size_t i = 0; i < sizeof order / sizeof order[0]; i++)
        check_compaction(&f, order[i], i % 2 ? 0.3 : 0.8, 500 + i);
    fixture_close(&f);
}

/* compactor_enqueue writes the count into the caller's buffer (at element 0, nothing else), and the
 * profile hook adds kernel time without changing the result. */
Test(scan, enqueue_into_caller_count_buffer_and_profile)
{
    Fixture f = fixture_open(4097, 0);
    Error err = {0};
    uint32_t init[2] = {SENTINEL, SENTINEL};
    cl_mem count_buf = device_buffer(f.dev, "count", CL_MEM_READ_WRITE, sizeof init, init, &err);
    cr_assert(count_buf, "%s", err.message);
    random_flags(f.host_flags, 4097, 0.5, 42);
    device_write(f.dev, f.flags, 0, 4097 * sizeof(uint32_t), f.host_flags);
    uint32_t expected = reference_compact(f.host_flags, 4097, f.expected);

    double ms = 0.0;
    compactor_set_profile(f.compactor, &ms);
    compactor_enqueue(f.compactor, f.flags, f.indices, count_buf, 4097);
    uint32_t counts[2];
    device_read(f.dev, count_buf, 0, sizeof counts, counts);
    cr_expect_eq(counts[0], expected);
    cr_expect_eq(counts[1], SENTINEL, "count_buf[1] was overwritten");
    cr_expect(ms > 0.0, "profiled time %g ms", ms);

    compactor_enqueue(f.compactor, f.flags, f.indices, count_buf, 0);
    device_read(f.dev, count_buf, 0, sizeof counts, counts);
    cr_expect_eq(counts[0], 0, "n = 0 must write a count of 0");
    CL_CHECK(clReleaseMemObject(count_buf));
    fixture_close(&f);
}

/* The work-group scan primitive alone, for several group sizes, against a host prefix sum. */
Test(scan, group_exclusive_sum_matches_host)
{
    Device *dev = test_device();
    Error err = {0};
    enum { N = 4096 };
    uint32_t *in = malloc(N * sizeof *in), *prefix = malloc(N * sizeof *prefix);
    uint32_t totals[N];
    rng_state = 99;
    for (int i = 0; i < N; i++)
        in[i] = rng_next() % 1000;
    cl_mem in_buf = device_buffer(dev, "in", CL_MEM_READ_ONLY, N * 4, in, &err);
    cl_mem prefix_buf = device_buffer(dev, "prefix", CL_MEM_WRITE_ONLY, N * 4, NULL, &err);
    cl_mem totals_buf = device_buffer(dev, "totals", CL_MEM_WRITE_ONLY, N * 4, NULL, &err);
    cr_assert(in_buf && prefix_buf && totals_buf, "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "test_group_exclusive_sum");
    for (size_t group = 1; group <= 256 && group <= dev->max_work_group; group *= 2) {
        KERNEL_ARGS(kernel, 0, KARG(in_buf), KARG(prefix_buf), KARG(totals_buf),
                    KARG_LOCAL(2 * group * sizeof(cl_uint)));
        device_run(dev, kernel, N, group, NULL);
        device_read(dev, prefix_buf, 0, N * 4, prefix);
        device_read(dev, totals_buf, 0, N / group * 4, totals);
        for (size_t g = 0; g < N / group; g++) {
            uint32_t sum = 0;
            for (size_t i = g * group; i < (g + 1) * group; i++) {
                cr_assert_eq(prefix[i], sum, "group size %zu, item %zu", group, i);
                sum += in[i];
            }
            cr_assert_eq(totals[g], sum, "group size %zu, group %zu", group, g);
        }
    }
    CL_CHECK(clReleaseKernel(kernel));
    CL_CHECK(clReleaseMemObject(in_buf));
    CL_CHECK(clReleaseMemObject(prefix_buf));
    CL_CHECK(clReleaseMemObject(totals_buf));
    free(in), free(prefix);
    test_device_release(dev);
}

Test(scan, oversized_compactor_is_an_error)
{
    if (SIZE_MAX <= UINT32_MAX)
        cr_skip_test("size_t is 32-bit");
    Device *dev = test_device();
    Error err = {0};
    Compactor *c = compactor_create(dev, (size_t)UINT32_MAX + 1, &err);
    cr_expect_null(c);
    cr_expect_eq(err.code, ERR_TOO_LARGE);
    test_device_release(dev);
}
