// SPDX-License-Identifier: MIT
/* bench_tlas: build time of the two-level BVH's top level (host/accel/tlas.c).
 *
 *   build/tools/bench_tlas [--reps R] [--out FILE]
 *
 * For 10^4 and 10^5 random instance boxes (centres uniform in a cube whose side grows with the
 * cube root of the count, so that the density stays the same; half-sizes up to 2 units), times on
 * one core, best of R runs (default 5): the binned-SAH tree over the boxes alone
 * (bvh_build_over_boxes: the TLAS build proper, goal <= 50 ms at 10^5), and the whole two-level
 * scene_bvh_build over one small mesh for each layout (2-wide float, quantised, 4- and 8-wide:
 * the TLAS plus its layout and join; the BLAS is 80 triangles). Writes FILE (default
 * bench/results/host/tlas_build.csv) and prints a table. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/scene_bvh.h"
#include "base/clock.h"
#include "bench_common.h"
#include "procedural_mesh.h"

static BvhInstance *random_instances(uint32_t n, uint64_t seed)
{
    BvhInstance *instances = malloc(n * sizeof *instances);
    if (!instances)
        die("out of memory for %u instances", n);
    uint64_t rng = seed;
    float side = 10.0f * cbrtf((float)n);
    for (uint32_t i = 0; i < n; i++) {
        instances[i].mesh = 0;
        for (int k = 0; k < 3; k++) {
            float centre = side * mesh_rng_float(&rng), half = 2.0f * mesh_rng_float(&rng);
            instances[i].lo[k] = centre - half;
            instances[i].hi[k] = centre + half;
        }
    }
    return instances;
}

static double best_boxes_ms(const BvhInstance *instances, uint32_t n, int reps, uint32_t *nodes)
{
    float (*lo)[3] = malloc(n * sizeof *lo), (*hi)[3] = malloc(n * sizeof *hi);
    if (!lo || !hi)
        die("out of memory for %u boxes", n);
    for (uint32_t i = 0; i < n; i++)
        memcpy(lo[i], instances[i].lo, sizeof lo[i]), memcpy(hi[i], instances[i].hi, sizeof hi[i]);
    double best = INFINITY;
    for (int r = 0; r < reps; r++) {
        Bvh tlas;
        double t0 = seconds_now();
        bvh_build_over_boxes(&tlas, (const float(*)[3])lo, (const float(*)[3])hi, n);
        double ms = 1e3 * (seconds_now() - t0);
        best = ms < best ? ms : best;
        *nodes = tlas.num_nodes;
        bvh_free(&tlas);
    }
    free(lo);
    free(hi);
    return best;
}

static double best_scene_ms(const TestMesh *mesh, const BvhInstance *instances, uint32_t n, int width,
                            bool quantized, int reps, double *tlas_ms)
{
    BvhMesh meshes[1] = {{0, mesh->num_triangles}};
    double best = INFINITY;
    *tlas_ms = INFINITY;
    for (int r = 0; r < reps; r++) {
        SceneBvh bvh;
        double t0 = seconds_now();
        scene_bvh_build(&bvh, mesh->positions, mesh->triangles, meshes, 1, instances, n, width,
                        quantized, BVH_TWO_LEVEL);
        double ms = 1e3 * (seconds_now() - t0);
        best = ms < best ? ms : best;
        *tlas_ms = fmin(*tlas_ms, 1e3 * bvh.tlas_seconds);
        scene_bvh_free(&bvh);
    }
    return best;
}

int main(int argc, char **argv)
{
    int reps = 5;
    const char *out = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            out = argv[++i];
        else
            die("usage: bench_tlas [--reps R] [--out FILE] (got '%s')", argv[i]);
    }
    if (reps < 1)
        die("bench_tlas: --reps must be at least 1");
    char path[1024];
    FILE *csv = bench_open_results_csv("host", out, "tlas_build.csv", path, sizeof path);
    fprintf(csv, "instances,what,ms,tlas_ms,tlas_nodes\n");
    TestMesh mesh = mesh_icosphere(1);
    const uint32_t counts[] = {10000, 100000};
    const struct {
        const char *name;
        int width;
        bool quantized;
    } layouts[] = {{"scene 2-wide", 2, false}, {"scene quantised", 2, true}, {"scene 4-wide", 4, false},
                   {"scene 8-wide", 8, false}};
    printf("%10s  %-18s %10s %10s\n", "instances", "build", "ms", "TLAS ms");
    for (size_t c = 0; c < sizeof counts / sizeof *counts; c++) {
        uint32_t n = counts[c], nodes = 0;
        BvhInstance *instances = random_instances(n, 1 + c);
        double ms = best_boxes_ms(instances, n, reps, &nodes);
        printf("%10u  %-18s %10.2f %10.2f\n", n, "TLAS (boxes)", ms, ms);
        fprintf(csv, "%u,tlas,%.4f,%.4f,%u\n", n, ms, ms, nodes);
        for (size_t l = 0; l < sizeof layouts / sizeof *layouts; l++) {
            double tlas_ms;
            double total = best_scene_ms(&mesh, instances, n, layouts[l].width, layouts[l].quantized,
                                         reps, &tlas_ms);
            printf("%10u  %-18s %10.2f %10.2f\n", n, layouts[l].name, total, tlas_ms);
            fprintf(csv, "%u,%s,%.4f,%.4f,%u\n", n, layouts[l].name, total, tlas_ms, nodes);
        }
        free(instances);
    }
    fclose(csv);
    test_mesh_free(&mesh);
    printf("wrote %s\n", path);
    return 0;
}
