// SPDX-License-Identifier: MIT
/* bench_env_build: the host side of a large environment map. Generates a sky in memory (a
 * gradient, noise and a small sun), times environment_build (the bilinear-aware sampling table:
 * 3 x 3 maxima, the rows' and texels' CDFs, pdfs; best of --reps) at 4096 x 2048 (the issue's
 * goal: < 0.2 s) and at 8192 x 4096, and prints the device memory a map takes: env_texels (float4
 * per texel) + env_cdf (8 bytes per texel and per row: CDFs and guides). --write-hdr FILE also writes the 8192 x 4096 map as
 * a Radiance .hdr (for tools/bench_env_8k.sh's render). Appends to --csv FILE when given.
 *   build/tools/bench_env_build [--reps 3] [--write-hdr FILE] [--csv FILE] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include <stb_image_write.h>

#include "base/clock.h"
#include "bench_common.h"
#include "scene/environment.h"

static float *sky(int w, int h)
{
    float *rgb = malloc((size_t)w * h * 3 * sizeof *rgb);
    if (!rgb)
        die("out of memory for a %dx%d map", w, h);
    uint64_t state = 0x9e3779b97f4a7c15ull;
    for (int j = 0; j < h; j++)
        for (int i = 0; i < w; i++) {
            state = state * 6364136223846793005ull + 1442695040888963407ull;
            float noise = (float)(state >> 40) / 16777216.0f, up = 1.0f - (float)j / (float)h;
            float *t = &rgb[3 * ((size_t)j * w + i)];
            t[0] = 0.2f + 0.5f * up + 0.1f * noise, t[1] = 0.3f + 0.5f * up, t[2] = 0.5f + 0.6f * up;
            int di = i - w / 3, dj = j - h / 3;
            if (di * di + dj * dj < (w / 512) * (w / 512) + 1)
                t[0] = 5e4f, t[1] = 4.5e4f, t[2] = 4e4f;
        }
    return rgb;
}

/* CPU seconds of this process so far, user and system (the kernel's page faults on fresh memory). */
static void cpu_seconds(double *user, double *sys)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    *user = u.ru_utime.tv_sec + 1e-6 * u.ru_utime.tv_usec;
    *sys = u.ru_stime.tv_sec + 1e-6 * u.ru_stime.tv_usec;
}

static uint64_t device_bytes(uint64_t w, uint64_t h)
{
    return w * h * 16u + 2 * (w * h + h) * sizeof(uint32_t);
}

int main(int argc, char **argv)
{
    int reps = 3;
    const char *hdr = NULL, *csv_path = NULL;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--reps")) reps = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--write-hdr")) hdr = argv[i + 1];
        else if (!strcmp(argv[i], "--csv")) csv_path = argv[i + 1];
        else die("unknown option %s", argv[i]);
    }
    if (argc % 2 == 0)
        die("%s: missing value", argv[argc - 1]);
    FILE *csv = csv_path ? bench_open_csv(csv_path) : NULL;
    if (csv)
        fprintf(csv, "width,height,build_seconds_best,build_seconds_mean,user_seconds,system_seconds,device_bytes\n");
    static const int sizes[2][2] = {{4096, 2048}, {8192, 4096}};
    for (int s = 0; s < 2; s++) {
        int w = sizes[s][0], h = sizes[s][1];
        float *rgb = sky(w, h);
        double best = 1e30, total = 0.0, user0, sys0, user1, sys1;
        cpu_seconds(&user0, &sys0);
        for (int r = 0; r < reps; r++) {
            Environment env;
            Error err = {0};
            double start = seconds_now();
            if (!environment_build(&env, rgb, w, h, 1.0f, 0.0f, "generated sky", &err))
                die("%s", err.message);
            double t = seconds_now() - start;
            best = fmin(best, t), total += t;
            environment_free(&env);
        }
        cpu_seconds(&user1, &sys1);
        uint64_t bytes = device_bytes((uint64_t)w, (uint64_t)h);
        double user = (user1 - user0) / reps, sys = (sys1 - sys0) / reps;
        printf("%dx%d: sampling tables built in %.3f s (best of %d, mean %.3f s: CPU %.3f s user + %.3f s "
               "system, the page faults of fresh memory); device memory %.1f MiB (env_texels %.1f + CDFs %.1f)\n",
               w, h, best, reps, total / reps, user, sys, bytes / 1048576.0, (double)w * h * 16 / 1048576.0,
               (bytes - (double)w * h * 16) / 1048576.0);
        if (csv)
            fprintf(csv, "%d,%d,%.4f,%.4f,%.4f,%.4f,%llu\n", w, h, best, total / reps, user, sys,
                    (unsigned long long)bytes);
        if (hdr && s == 1) {
            if (!stbi_write_hdr(hdr, w, h, 3, rgb))
                die("cannot write %s", hdr);
            printf("wrote %s\n", hdr);
        }
        free(rgb);
    }
    if (csv)
        fclose(csv);
    return 0;
}
