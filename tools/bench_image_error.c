// SPDX-License-Identifier: MIT
/* bench_image_error IMAGE.exr REFERENCE.exr: the error of an image's beauty (R, G, B) against a
 * reference of the same size, as one CSV fragment "relmse,psnr":
 *   relMSE = mean over pixels and channels of (x - r)^2 / (r^2 + 0.01)  (Rousselle et al. 2011;
 *            the 0.01 keeps black pixels from dominating), what denoising papers and OIDN report;
 *   PSNR   = 10 log10(1 / MSE) of the values clamped to [0, 1] (the displayable range).
 * For tools/bench_denoise.sh (issue 35), in C so that it runs from a bundle on a machine without
 * Python. Exit 2 on unreadable input or a size mismatch. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "io/image_io.h"

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: bench_image_error IMAGE.exr REFERENCE.exr\n");
        return 2;
    }
    Error err = {0};
    float *image, *ref;
    int wi, hi, wr, hr;
    if (!image_read_exr(argv[1], &image, &wi, &hi, &err) ||
        !image_read_exr(argv[2], &ref, &wr, &hr, &err)) {
        fprintf(stderr, "bench_image_error: %s\n", err.message);
        return 2;
    }
    if (wi != wr || hi != hr) {
        fprintf(stderr, "bench_image_error: %s is %dx%d, %s %dx%d\n", argv[1], wi, hi, argv[2], wr,
                hr);
        return 2;
    }
    size_t n = (size_t)wi * (size_t)hi * 3;
    double rel = 0.0, squared = 0.0;
    for (size_t i = 0; i < n; i++) {
        double x = image[i], r = ref[i], d = x - r;
        rel += d * d / (r * r + 0.01);
        double dc = fmin(fmax(x, 0.0), 1.0) - fmin(fmax(r, 0.0), 1.0);
        squared += dc * dc;
    }
    double mse = squared / (double)n;
    printf("%.6g,%.3f\n", rel / (double)n, mse > 0.0 ? 10.0 * log10(1.0 / mse) : INFINITY);
    free(image);
    free(ref);
    return 0;
}
