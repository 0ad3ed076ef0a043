// SPDX-License-Identifier: MIT
/* bench_sort: time of the material sort (host/parallel/material_sort.c) for n paths and several material
 * counts, against the device's copy of the same list.
 *
 *   build/tools/bench_sort [--device gpu|cpu|P:D] [--n N] [--materials 8,64,1024] [--reps R]
 *                          [--group-size G] [--out FILE.csv]
 *
 * The list is n ascending slots (as compaction leaves it), one path each, a tenth of them misses.
 * Two key layouts: "random" (each hit an independent uniform material: the sort's worst case and
 * the case where sorting could help shading most) and "coherent" (the material changes about
 * every 64 slots: neighbouring pixels hitting one object, the usual camera-ray case). Times: the
 * device time of the sort's commands from profiling events (kernel_ms, mean over R runs), and the
 * wall time of R back-to-back runs divided by R (wall_ms: launch gaps included, which is what the
 * integrator pays). Each configuration is checked once: the output is a permutation of the slots,
 * keys ascend, slots ascend within a key. CSV: bench/results/<device>/material_sort.csv. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_common.h"
#include "base/shared_types.h"
#include "device/device.h"
#include "parallel/material_sort.h"
#include "xorshift.h"

#define MAX_MATERIAL_COUNTS 16
#define COHERENT_RUN 64

typedef struct {
    const char *device, *out;
    uint32_t n;
    uint32_t materials[MAX_MATERIAL_COUNTS];
    int num_materials, reps;
    size_t group_size;
} Options;

static void usage(void)
{
    fprintf(stderr, "usage: bench_sort [--device gpu|cpu|P:D] [--n N] [--materials M,M,...] "
                    "[--reps R] [--group-size G] [--out FILE.csv]\n");
    exit(2);
}

static int parse_list(const char *text, uint32_t *values, int max_values)
{
    int count = 0;
    for (const char *p = text; *p && count < max_values; p++) {
        char *end;
        values[count++] = (uint32_t)strtoul(p, &end, 10);
        if (end == p || (*end && *end != ','))
            usage();
        p = *end ? end : end - 1;
    }
    return count;
}

static Options parse_options(int argc, char **argv)
{
    Options o = {.n = 1u << 21, .materials = {8, 64, 1024}, .num_materials = 3, .reps = 20};
    for (int i = 1; i < argc; i++) {
        if (i + 1 >= argc)
            usage();
        const char *key = argv[i], *value = argv[++i];
        if (!strcmp(key, "--device"))
            o.device = value;
        else if (!strcmp(key, "--out"))
            o.out = value;
        else if (!strcmp(key, "--n"))
            o.n = (uint32_t)strtoul(value, NULL, 10);
        else if (!strcmp(key, "--materials"))
            o.num_materials = parse_list(value, o.materials, MAX_MATERIAL_COUNTS);
        else if (!strcmp(key, "--reps"))
            o.reps = atoi(value);
        else if (!strcmp(key, "--group-size"))
            o.group_size = (size_t)atol(value);
        else
            usage();
    }
    if (o.n == 0 || o.reps < 1 || o.num_materials < 1)
        usage();
    return o;
}


/* hit[slot].w and its key (material, or num_materials on a miss); triangle t has material t. */
static void make_keys(cl_float4 *hit, uint32_t *keys, uint32_t n, uint32_t num_materials,
                      bool coherent)
{
    uint64_t rng_state = 0x9e3779b97f4a7c15ull;
    uint32_t material = 0;
    for (uint32_t slot = 0; slot < n; slot++) {
        if (!coherent || xorshift_next(&rng_state) % COHERENT_RUN == 0)
            material = xorshift_next(&rng_state) % num_materials;
        bool miss = xorshift_next(&rng_state) % 10 == 0;
        uint32_t prim = miss ? HIT_NONE : material;
        hit[slot] = (cl_float4){{1.0f, 0.25f, 0.5f, 0.0f}};
        memcpy(&hit[slot].s[3], &prim, sizeof prim);
        keys[slot] = miss ? num_materials : material;
    }
}

/* Dies unless sorted[0..n) holds each slot once, keys ascend, and slots ascend within a key. */
static void check_sorted(const uint32_t *sorted, const uint32_t *keys, uint32_t n, bool *seen)
{
    memset(seen, 0, n * sizeof *seen);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t slot = sorted[i];
        if (slot >= n || seen[slot])
            die("bench_sort: output %u is slot %u, out of range or repeated", i, slot);
        seen[slot] = true;
        if (i > 0) {
            uint32_t previous = sorted[i - 1];
            bool ordered = keys[previous] < keys[slot] ||
                           (keys[previous] == keys[slot] && previous < slot);
            if (!ordered)
                die("bench_sort: outputs %u and %u out of order", i - 1, i);
        }
    }
}

static double wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct {
    Device *dev;
    cl_mem hit, material_ids, active, sorted;
    uint32_t *host_sorted;
    bool *seen;
} Buffers;

/* One configuration: check once, then time; returns the kernel and wall ms per sort. */
static void time_sort(Buffers *b, MaterialSorter *s, uint32_t n, const uint32_t *keys, int reps,
                      double *kernel_ms, double *wall_ms)
{
    material_sorter_run(s, b->hit, b->material_ids, b->active, b->sorted, n);
    device_read(b->dev, b->sorted, 0, (size_t)n * 4, b->host_sorted);
    check_sorted(b->host_sorted, keys, n, b->seen);

    double total_ms = 0.0;
    material_sorter_set_profile(s, &total_ms);
    for (int r = 0; r < reps; r++)
        material_sorter_run(s, b->hit, b->material_ids, b->active, b->sorted, n);
    material_sorter_set_profile(s, NULL);
    *kernel_ms = total_ms / reps;

    CL_CHECK(clFinish(b->dev->queue));
    double start = wall_seconds();
    for (int r = 0; r < reps; r++)
        material_sorter_run(s, b->hit, b->material_ids, b->active, b->sorted, n);
    CL_CHECK(clFinish(b->dev->queue));
    *wall_ms = (wall_seconds() - start) * 1e3 / reps;
}

int main(int argc, char **argv)
{
    Options o = parse_options(argc, argv);
    Device dev;
    Error err = {0};
    if (!device_open(&dev, o.device, &err) ||
        !device_build(&dev, PROGRAM_FEATURES_ALL, NULL, NULL, &err))
        die("%s", err.message);
    uint32_t n = o.n, max_materials = 1;
    for (int m = 0; m < o.num_materials; m++)
        max_materials = o.materials[m] > max_materials ? o.materials[m] : max_materials;

    Buffers b = {.dev = &dev};
    cl_float4 *host_hit = malloc((size_t)n * sizeof *host_hit);
    uint32_t *keys = malloc((size_t)n * 4), *slots = malloc((size_t)n * 4);
    uint32_t *triangle_materials = malloc((size_t)max_materials * 4);
    b.host_sorted = malloc((size_t)n * 4);
    b.seen = malloc(n);
    if (!host_hit || !keys || !slots || !triangle_materials || !b.host_sorted || !b.seen)
        die("out of memory");
    for (uint32_t i = 0; i < n; i++)
        slots[i] = i;
    for (uint32_t t = 0; t < max_materials; t++)
        triangle_materials[t] = t;
    b.hit = device_buffer(&dev, "hit", CL_MEM_READ_ONLY, (size_t)n * 16, NULL, &err);
    b.material_ids = device_buffer(&dev, "material_ids", CL_MEM_READ_ONLY,
                                   (size_t)max_materials * 4, triangle_materials, &err);
    b.active = device_buffer(&dev, "active", CL_MEM_READ_WRITE, (size_t)n * 4, slots, &err);
    b.sorted = device_buffer(&dev, "sorted", CL_MEM_READ_WRITE, (size_t)n * 4, NULL, &err);
    if (!b.hit || !b.material_ids || !b.active || !b.sorted)
        die("%s", err.message);

    char path[1024];
    FILE *csv = bench_open_results_csv(dev.name, o.out, "material_sort.csv", path, sizeof path);
    fprintf(csv, "device,n,materials,layout,group_size,local_histogram,launches,reps,kernel_ms,"
                 "wall_ms,mpaths_per_s,copy_ms\n");
    double copy = bench_copy_ms(&dev, b.active, b.sorted, (size_t)n * 4, o.reps);
    printf("device %s (%s); %u paths, a tenth misses; copy of the list %.4f ms\n", dev.name,
           dev.platform_name, n, copy);
    printf("%9s %9s %5s %5s %4s %10s %10s %9s %8s\n", "materials", "layout", "group", "hist",
           "lnch", "kernel ms", "wall ms", "Mpaths/s", "x copy");

    for (int m = 0; m < o.num_materials; m++) {
        uint32_t num_materials = o.materials[m];
        MaterialSorter *s = material_sorter_create_sized(&dev, n, num_materials, o.group_size, &err);
        if (!s)
            die("%s", err.message);
        for (int layout = 0; layout < 2; layout++) {
            const char *layout_name = layout ? "coherent" : "random";
            make_keys(host_hit, keys, n, num_materials, layout == 1);
            device_write(&dev, b.hit, 0, (size_t)n * 16, host_hit);
            double kernel_ms, wall_ms;
            time_sort(&b, s, n, keys, o.reps, &kernel_ms, &wall_ms);
            double rate = n / (wall_ms * 1e3);
            const char *histogram = material_sorter_local_histogram(s) ? "local" : "global";
            int launches = material_sorter_launches(s, n);
            printf("%9u %9s %5zu %5s %4d %10.4f %10.4f %9.1f %8.1f\n", num_materials, layout_name,
                   material_sorter_group_size(s), histogram, launches, kernel_ms, wall_ms, rate,
                   wall_ms / copy);
            fprintf(csv, "\"%s\",%u,%u,%s,%zu,%s,%d,%d,%.5f,%.5f,%.2f,%.5f\n", dev.name, n,
                    num_materials, layout_name, material_sorter_group_size(s), histogram, launches,
                    o.reps, kernel_ms, wall_ms, rate, copy);
        }
        material_sorter_destroy(s);
    }
    fclose(csv);
    printf("wrote %s\n", path);
    cl_mem buffers[] = {b.hit, b.material_ids, b.active, b.sorted};
    for (size_t i = 0; i < sizeof buffers / sizeof buffers[0]; i++)
        CL_CHECK(clReleaseMemObject(buffers[i]));
    free(host_hit), free(keys), free(slots), free(triangle_materials), free(b.host_sorted);
    free(b.seen);
    device_close(&dev);
    return 0;
}
