// SPDX-License-Identifier: MIT
/* bench_relmse REF.exr IMAGE.exr...: the relative mean squared error of each image against the
 * reference, mean over pixels and channels of (a - ref)^2 / (ref^2 + 0.01) (the error measure of
 * issue 34 and tools/bench_efficiency.py), one line per image: "relmse PATH VALUE". For the
 * estimator studies on machines without numpy. Exit 2 on unreadable input or a size mismatch. */
#include <stdio.h>
#include <stdlib.h>

#include "io/image_io.h"

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: bench_relmse REF.exr IMAGE.exr...\n");
        return 2;
    }
    Error err = {0};
    float *ref;
    int w, h;
    if (!image_read_exr(argv[1], &ref, &w, &h, &err)) {
        fprintf(stderr, "bench_relmse: %s\n", err.message);
        return 2;
    }
    for (int i = 2; i < argc; i++) {
        float *a;
        int wa, ha;
        if (!image_read_exr(argv[i], &a, &wa, &ha, &err) || wa != w || ha != h) {
            fprintf(stderr, "bench_relmse: %s: %s\n", argv[i], error_is_set(&err) ? err.message : "size differs");
            return 2;
        }
        double sum = 0.0;
        for (size_t k = 0; k < (size_t)w * h * 3; k++) {
            double d = (double)a[k] - ref[k];
            sum += d * d / ((double)ref[k] * ref[k] + 0.01);
        }
        printf("relmse %s %.6g\n", argv[i], sum / (3.0 * w * h));
        free(a);
    }
    free(ref);
    return 0;
}
