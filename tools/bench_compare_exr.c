// SPDX-License-Identifier: MIT
/* bench_compare_exr A.exr B.exr [--tolerance REL]: compares the beauty pixels of two EXRs (the
 * header's render_time and the like differ between runs; the pixels of one seed must not). Prints
 * the number of differing values, the largest absolute and relative difference, the image means,
 * and README's criterion for devices that round differently as tests/test_multi_device_film.c
 * computes it (the mean |a - b| over the image's mean, and the share of pixels with a channel
 * more than 1% of max(|a|, the mean) apart); exit 0 when bit-identical (or, with --tolerance, when
 * every value is within REL relative difference), 1 otherwise, 2 on unreadable input. For the
 * multi-device benchmarks on machines without Python (bench/README.md, issue 21). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/image_io.h"

int main(int argc, char **argv)
{
    if (argc != 3 && !(argc == 5 && strcmp(argv[3], "--tolerance") == 0)) {
        fprintf(stderr, "usage: bench_compare_exr A.exr B.exr [--tolerance REL]\n");
        return 2;
    }
    double tolerance = argc == 5 ? atof(argv[4]) : -1.0;
    Error err = {0};
    float *a, *b;
    int wa, ha, wb, hb;
    if (!image_read_exr(argv[1], &a, &wa, &ha, &err) || !image_read_exr(argv[2], &b, &wb, &hb, &err)) {
        fprintf(stderr, "bench_compare_exr: %s\n", err.message);
        return 2;
    }
    if (wa != wb || ha != hb) {
        printf("size differs: %dx%d vs %dx%d\n", wa, ha, wb, hb);
        return 1;
    }
    size_t n = (size_t)wa * (size_t)ha * 3, differing = 0, beyond = 0, far_pixels = 0;
    double max_abs = 0.0, max_rel = 0.0, sum_a = 0.0, sum_b = 0.0, sum_diff = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (memcmp(&a[i], &b[i], sizeof a[i]) != 0)
            differing++;
        double d = fabs((double)a[i] - (double)b[i]);
        double scale = fmax(fabs((double)a[i]), fabs((double)b[i]));
        double rel = scale > 0 ? d / scale : 0.0;
        max_abs = fmax(max_abs, d);
        max_rel = fmax(max_rel, rel);
        beyond += tolerance >= 0 && rel > tolerance;
        sum_a += a[i], sum_b += b[i], sum_diff += d;
    }
    double mean = sum_a / (double)n;
    for (size_t p = 0; p < n / 3; p++)
        for (size_t i = 3 * p; i < 3 * p + 3; i++)
            if (fabs((double)a[i] - b[i]) > 0.01 * fmax(fabs((double)a[i]), mean)) {
                far_pixels++;
                break;
            }
    printf("%dx%d: %zu of %zu values differ; max abs %.3g, max rel %.3g; image means %.9g vs %.9g; "
           "mean |a - b| / mean %.3g, %.3g%% of pixels over 1%% apart\n",
           wa, ha, differing, n, max_abs, max_rel, sum_a / (double)n, sum_b / (double)n,
           sum_a > 0 ? sum_diff / sum_a : 0.0, 100.0 * (double)far_pixels / (double)(n / 3));
    free(a);
    free(b);
    return tolerance >= 0 ? beyond != 0 : differing != 0;
}
