// SPDX-License-Identifier: MIT
/* The path RNG gives every (pixel, sample) pair of a large render its own random sequence: over
 * 2^26 pairs (128 x 128 pixels x 4096 samples) no two sequences start alike. Colliding samples
 * trace the same path: correlated noise that more samples never average out. A key that folds
 * (pixel, sample, seed) into 32 bits as hash(pixel ^ hash(sample ^ hash(seed))) collides for whole
 * rows at once: samples s, s' whose hashes agree above the pixel bits (about one pair in 2^18
 * here, 32 of the 8 million) share all 2^14 pixels' sequences, some 2^19 pairs in all. */
#include <criterion/criterion.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "support.h"

#define PIXELS (128u * 128u)
#define SAMPLES 4096u
#define CHUNK (1u << 22) /* pairs per launch */

/* LSD radix sort, 16 bits a pass. */
static void sort_u64(uint64_t *values, uint64_t *scratch, size_t n)
{
    static size_t count[1 << 16];
    for (int shift = 0; shift < 64; shift += 16) {
        memset(count, 0, sizeof count);
        for (size_t i = 0; i < n; i++)
            count[(values[i] >> shift) & 0xffff]++;
        size_t sum = 0;
        for (size_t d = 0; d < (1 << 16); d++) {
            size_t c = count[d];
            count[d] = sum;
            sum += c;
        }
        for (size_t i = 0; i < n; i++)
            scratch[count[(values[i] >> shift) & 0xffff]++] = values[i];
        uint64_t *swap = values;
        values = scratch;
        scratch = swap;
    }
    /* Four passes: the sorted data ends in the array it started in. */
}

Test(rng, distinct_samples_start_distinct_sequences, .timeout = 300)
{
    Device *dev = test_device();
    size_t n = (size_t)PIXELS * SAMPLES;
    uint64_t *starts = malloc(n * sizeof *starts), *scratch = malloc(n * sizeof *scratch);
    cr_assert(starts && scratch, "out of memory for %zu sequence starts", n);
    Error err = {0};
    cl_mem out = device_buffer(dev, "starts", CL_MEM_WRITE_ONLY, CHUNK * sizeof(cl_ulong), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "rng_test_sequence_starts");
    for (size_t first = 0; first < n; first += CHUNK) {
        cl_uint num_pixels = PIXELS, sample_base = (cl_uint)(first / PIXELS), seed = 7, count = CHUNK;
        cl_uint arg = 0;
        KERNEL_ARG(kernel, arg++, num_pixels);
        KERNEL_ARG(kernel, arg++, sample_base);
        KERNEL_ARG(kernel, arg++, seed);
        KERNEL_ARG(kernel, arg++, count);
        KERNEL_ARG(kernel, arg++, out);
        device_run(dev, kernel, CHUNK, 0, NULL);
        device_read(dev, out, 0, CHUNK * sizeof(cl_ulong), starts + first);
    }
    clReleaseKernel(kernel);
    clReleaseMemObject(out);
    sort_u64(starts, scratch, n);
    size_t duplicates = 0;
    for (size_t i = 1; i < n; i++)
        duplicates += starts[i] == starts[i - 1];
    /* 64 bits of a good generator: 2^51 / 2^64 = 2^-13 duplicates expected. */
    cr_expect_eq(duplicates, 0, "%zu of %zu (pixel, sample) pairs start the same sequence as another",
                 duplicates, n);
    free(starts);
    free(scratch);
    test_device_release(dev);
}

/* Each dimension is uniform and pairs of dimensions are independent, across pixels and samples:
 * neighbours (d, d + 1), dimensions 32 apart (the rotation of the sample word repeats every 32)
 * and a bounce's light and BSDF numbers. A 2-D chi-square over 16 x 16 cells of 2^20 draws. */
Test(rng, dimensions_are_uniform_and_pairwise_independent, .timeout = 120)
{
    static const cl_uint pairs[][2] = {{0, 1}, {0, 32}, {5, 37}, {31, 32}, {8, 12}, {9, 25}, {40, 72}, {3, 100}};
    enum { COUNT = 1 << 20, CELLS = 16 };
    Device *dev = test_device();
    Error err = {0};
    cl_mem out = device_buffer(dev, "bins", CL_MEM_WRITE_ONLY, COUNT * sizeof(cl_ushort), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "rng_test_dimension_pair");
    cl_ushort *bins = malloc(COUNT * sizeof *bins);
    cr_assert(bins);
    for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++) {
        cl_uint num_pixels = 4096, seed = 3, count = COUNT;
        KERNEL_ARGS(kernel, 0, KARG(num_pixels), KARG(seed), KARG(pairs[p][0]), KARG(pairs[p][1]),
                    KARG(count), KARG(out));
        device_run(dev, kernel, COUNT, 0, NULL);
        device_read(dev, out, 0, COUNT * sizeof *bins, bins);
        static double cell[CELLS][CELLS], margin0[CELLS], margin1[CELLS];
        memset(cell, 0, sizeof cell), memset(margin0, 0, sizeof margin0), memset(margin1, 0, sizeof margin1);
        for (size_t i = 0; i < COUNT; i++) {
            int a = (bins[i] >> 8) / (256 / CELLS), b = (bins[i] & 0xff) / (256 / CELLS);
            cell[a][b]++, margin0[a]++, margin1[b]++;
        }
        double chi2 = 0.0, chi2_0 = 0.0, chi2_1 = 0.0;
        double e2 = (double)COUNT / (CELLS * CELLS), e1 = (double)COUNT / CELLS;
        for (int a = 0; a < CELLS; a++) {
            chi2_0 += (margin0[a] - e1) * (margin0[a] - e1) / e1;
            chi2_1 += (margin1[a] - e1) * (margin1[a] - e1) / e1;
            for (int b = 0; b < CELLS; b++)
                chi2 += (cell[a][b] - e2) * (cell[a][b] - e2) / e2;
        }
        /* 255 and 15 degrees of freedom; limits at about p = 1e-5. */
        cr_expect(chi2 < 360.0, "dimensions %u and %u: joint chi-square %.1f (255 dof)",
                  pairs[p][0], pairs[p][1], chi2);
        cr_expect(chi2_0 < 50.0 && chi2_1 < 50.0, "dimensions %u, %u: marginal chi-square %.1f, %.1f",
                  pairs[p][0], pairs[p][1], chi2_0, chi2_1);
    }
    free(bins);
    clReleaseKernel(kernel);
    clReleaseMemObject(out);
    test_device_release(dev);
}
