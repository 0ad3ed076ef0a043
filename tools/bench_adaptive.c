// SPDX-License-Identifier: MIT
/* bench_adaptive: does adaptive sampling (--noise-threshold) pay? Renders in-process a converged
 * reference (uniform, --ref-spp), then per seed an adaptive render (--noise-threshold T, --spp as
 * the most a pixel gets) and a uniform render of the same total samples (its spp = the adaptive
 * render's paths / pixels, rounded), and prints relMSE against the reference for both, their
 * sample-loop times, and relMSE x time (at equal time relMSE scales as 1 / time, so the ratio of
 * relMSE x time is the ratio of relMSE at equal time: it charges adaptive sampling its decisions
 * and its shorter windows). Scene default: the Cornell box with a mirror and a glass sphere (a
 * small light's caustics on the floor, large smooth walls). Writes bench/results/<device>/
 * adaptive.csv (or --csv FILE).
 *   build/tools/bench_adaptive [--device gpu|cpu|P:D] [--scene FILE] [--width 128 --height 128]
 *       [--spp 256] [--threshold 0.05] [--min-spp 0 (default)] [--ref-spp 4096] [--seeds 2]
 *       [--csv FILE] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "bench_common.h"
#include "render/session.h"
#include "render/wavefront.h"

typedef struct {
    const char *device, *scene, *csv;
    int width, height, spp, min_spp, ref_spp, seeds;
    float threshold;
} Options;

typedef struct {
    float *rgb;
    uint64_t paths;
    double seconds;
} Render;

static Render render(Session *s, const Options *o, int spp, float threshold, unsigned seed)
{
    RenderSettings settings = {.spp = spp, .max_depth = s->scene.desc.max_depth, .seed = seed,
                               .noise_threshold = threshold, .min_spp = threshold > 0 ? o->min_spp : 0};
    Error err = {0};
    Wavefront *w = wavefront_create(&s->dev, &s->scene, &s->buffers, &settings, &err);
    if (!w)
        die("%s", err.message);
    while (wavefront_spp_done(w) < spp)
        wavefront_advance(w, UINT64_MAX, spp);
    Render r = {malloc((size_t)o->width * o->height * 3 * sizeof(float)), 0, 0};
    if (!r.rgb)
        die("out of memory");
    wavefront_read_film(w, r.rgb);
    r.paths = wavefront_stats(w)->paths;
    r.seconds = wavefront_stats(w)->seconds;
    wavefront_destroy(w);
    return r;
}

/* Mean over pixels and channels of (x - ref)^2 / (ref^2 + 1e-3), as tools/bench_env_variance.c. */
static double relative_mse(const float *x, const float *ref, size_t n)
{
    double sum = 0.0;
    for (size_t i = 0; i < n; i++)
        sum += ((double)x[i] - ref[i]) * ((double)x[i] - ref[i]) / ((double)ref[i] * ref[i] + 1e-3);
    return sum / (double)n;
}

static Options parse(int argc, char **argv)
{
    Options o = {NULL, "scenes/cornell-box/sphere.json", NULL, 128, 128, 256, 0, 4096, 2, 0.05f};
    for (int i = 1; i < argc; i += 2) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v)
            die("%s: missing value (see the comment at the top of tools/bench_adaptive.c)", a);
        if (!strcmp(a, "--device")) o.device = v;
        else if (!strcmp(a, "--scene")) o.scene = v;
        else if (!strcmp(a, "--csv")) o.csv = v;
        else if (!strcmp(a, "--width")) o.width = atoi(v);
        else if (!strcmp(a, "--height")) o.height = atoi(v);
        else if (!strcmp(a, "--spp")) o.spp = atoi(v);
        else if (!strcmp(a, "--min-spp")) o.min_spp = atoi(v);
        else if (!strcmp(a, "--ref-spp")) o.ref_spp = atoi(v);
        else if (!strcmp(a, "--seeds")) o.seeds = atoi(v);
        else if (!strcmp(a, "--threshold")) o.threshold = (float)atof(v);
        else die("unknown option %s", a);
    }
    if (o.width <= 0 || o.height <= 0 || o.spp <= 0 || o.ref_spp <= 0 || o.seeds <= 0 ||
        o.min_spp < 0 || o.min_spp > o.spp || !(o.threshold > 0))
        die("--width, --height, --spp, --ref-spp, --seeds and --threshold must be > 0, "
            "--min-spp in [0, spp]");
    return o;
}

int main(int argc, char **argv)
{
    Options o = parse(argc, argv);
    Session s;
    Error err = {0};
    RenderDesc desc = {.scene = o.scene, .device = o.device, .width = o.width, .height = o.height};
    if (!session_open(&s, &desc, &err))
        die("%s", err.message);
    size_t pixels = (size_t)o.width * o.height, n = pixels * 3;
    Render ref = render(&s, &o, o.ref_spp, 0, 1000);
    fprintf(stderr, "reference: %d spp in %.2f s on %s\n", o.ref_spp, ref.seconds, s.dev.name);
    /* A short adaptive render first: the device compiles its kernels at their first launch (PoCL
     * does), which is no part of the time compared. */
    Options warm = o;
    warm.min_spp = 2;
    free(render(&s, &warm, 4, o.threshold, 99).rgb);
    double mse[2] = {0, 0}, seconds[2] = {0, 0}, spp[2] = {0, 0};
    for (int seed = 1; seed <= o.seeds; seed++) {
        Render a = render(&s, &o, o.spp, o.threshold, (unsigned)seed);
        int uniform_spp = (int)((double)a.paths / (double)pixels + 0.5);
        Render u = render(&s, &o, uniform_spp > 0 ? uniform_spp : 1, 0, (unsigned)seed);
        const Render *r[2] = {&a, &u};
        for (int m = 0; m < 2; m++) {
            mse[m] += relative_mse(r[m]->rgb, ref.rgb, n) / o.seeds;
            seconds[m] += r[m]->seconds / o.seeds;
            spp[m] += (double)r[m]->paths / (double)pixels / o.seeds;
        }
        free(a.rgb), free(u.rgb);
    }
    free(ref.rgb);
    char csv_path[1024];
    FILE *csv = bench_open_results_csv(s.dev.name, o.csv, "adaptive.csv", csv_path, sizeof csv_path);
    fprintf(csv, "device,scene,width,height,max_spp,threshold,ref_spp,mode,mean_spp,seconds,rel_mse,"
                 "rel_mse_x_seconds\n");
    printf("%s, %s %dx%d, at most %d spp, threshold %g (mean of %d seeds), reference %d spp\n",
           s.dev.name, o.scene, o.width, o.height, o.spp, o.threshold, o.seeds, o.ref_spp);
    static const char *names[2] = {"adaptive", "uniform"};
    for (int m = 0; m < 2; m++) {
        printf("  %-8s  %7.1f spp  %7.3f s  relMSE %.6f  relMSE x time %.6f\n", names[m], spp[m],
               seconds[m], mse[m], mse[m] * seconds[m]);
        fprintf(csv, "\"%s\",%s,%d,%d,%d,%g,%d,%s,%.2f,%.4f,%.6g,%.6g\n", s.dev.name, o.scene, o.width,
                o.height, o.spp, o.threshold, o.ref_spp, names[m], spp[m], seconds[m], mse[m],
                mse[m] * seconds[m]);
    }
    printf("  equal samples: adaptive relMSE is %.2fx lower; equal time (relMSE x time): %.2fx\n",
           mse[1] / mse[0], (mse[1] * seconds[1]) / (mse[0] * seconds[0]));
    fclose(csv);
    printf("wrote %s\n", csv_path);
    session_close(&s);
    return 0;
}
