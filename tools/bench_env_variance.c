// SPDX-License-Identifier: MIT
/* bench_env_variance: is importance sampling the environment map worth it? Renders an env-lit
 * scene (default scenes/venice/sphere.json: a diffuse sphere on a floor under the Venice sunset)
 * with the pt binary: a converged reference (NEE + MIS at --ref-spp), then NEE + MIS and BSDF-only
 * (--no-nee) at the same --spp, each timed by pt's own "N spp in T s" line (kernel build and
 * scene load excluded). Prints relMSE against the reference, the time, and relMSE x time (the
 * inverse efficiency: at equal time relMSE scales as 1 / time, so the ratio of relMSE x time is the
 * ratio of relMSE at equal time). Writes bench/results/<device>/env_variance.csv (or --csv FILE).
 *   build/tools/bench_env_variance [--pt build/pt] [--device gpu|cpu|P:D] [--scene FILE]
 *       [--width 128 --height 96] [--spp 32] [--ref-spp 2048] [--seeds 3] [--csv FILE] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/error.h"
#include "bench_common.h"
#include "io/image_io.h"

typedef struct {
    const char *pt, *device, *scene, *csv;
    int width, height, spp, ref_spp, seeds;
} Options;

static char device_name[256] = "unknown-device";

/* Runs pt render and returns its render time in seconds (from "N spp in T s"); the image goes to
 * exr. Dies with pt's output when it fails. */
static double run_pt(const Options *o, int spp, int seed, int no_nee, const char *exr)
{
    char command[4096];
    snprintf(command, sizeof command, "'%s' render '%s' --width %d --height %d --spp %d --seed %d %s%s%s -o '%s' 2>&1",
             o->pt, o->scene, o->width, o->height, spp, seed, no_nee ? "--no-nee " : "",
             o->device ? "--device " : "", o->device ? o->device : "", exr);
    FILE *p = popen(command, "r");
    if (!p)
        die("cannot run %s", o->pt);
    char line[1024], all[8192] = "";
    double seconds = -1.0;
    while (fgets(line, sizeof line, p)) {
        if (strlen(all) + strlen(line) < sizeof all)
            strcat(all, line);
        int done;
        double t;
        if (sscanf(line, "pt: %d spp in %lf s", &done, &t) == 2)
            seconds = t;
        const char *dev = strstr(line, "pt: device ");
        if (dev) {
            snprintf(device_name, sizeof device_name, "%s", dev + strlen("pt: device "));
            char *paren = strstr(device_name, " (");
            if (paren)
                *paren = '\0';
        }
    }
    int status = pclose(p);
    if (status != 0 || seconds < 0.0)
        die("%s failed (status %d):\n%s", command, status, all);
    return seconds;
}

static float *read_exr(const char *path, int width, int height)
{
    float *rgb;
    int w, h;
    Error err = {0};
    if (!image_read_exr(path, &rgb, &w, &h, &err) || w != width || h != height)
        die("%s: %s", path, err.message);
    return rgb;
}

/* Mean over pixels and channels of (x - ref)^2 / (ref^2 + 1e-3): relative MSE, with a small
 * floor for black reference pixels. */
static double rel_mse(const float *x, const float *ref, size_t n)
{
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) {
        double d = (double)x[i] - ref[i];
        sum += d * d / ((double)ref[i] * ref[i] + 1e-3);
    }
    return sum / (double)n;
}

static Options parse(int argc, char **argv)
{
    Options o = {"build/pt", NULL, "scenes/venice/sphere.json", NULL, 128, 96, 32, 2048, 3};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v)
            die("%s: missing value (see the comment at the top of tools/bench_env_variance.c)", a);
        if (!strcmp(a, "--pt")) o.pt = v;
        else if (!strcmp(a, "--device")) o.device = v;
        else if (!strcmp(a, "--scene")) o.scene = v;
        else if (!strcmp(a, "--csv")) o.csv = v;
        else if (!strcmp(a, "--width")) o.width = atoi(v);
        else if (!strcmp(a, "--height")) o.height = atoi(v);
        else if (!strcmp(a, "--spp")) o.spp = atoi(v);
        else if (!strcmp(a, "--ref-spp")) o.ref_spp = atoi(v);
        else if (!strcmp(a, "--seeds")) o.seeds = atoi(v);
        else die("unknown option %s", a);
        i++;
    }
    if (o.width <= 0 || o.height <= 0 || o.spp <= 0 || o.ref_spp <= 0 || o.seeds <= 0)
        die("--width, --height, --spp, --ref-spp and --seeds must be > 0");
    return o;
}

int main(int argc, char **argv)
{
    Options o = parse(argc, argv);
    char dir[] = "/tmp/pt-bench-env-XXXXXX", ref_path[256], path[256];
    if (!mkdtemp(dir))
        die("cannot create a temporary folder");
    snprintf(ref_path, sizeof ref_path, "%s/reference.exr", dir);
    double ref_seconds = run_pt(&o, o.ref_spp, 1000, 0, ref_path);
    fprintf(stderr, "reference: %d spp NEE + MIS in %.2f s on %s\n", o.ref_spp, ref_seconds, device_name);
    size_t n = (size_t)o.width * o.height * 3;
    float *ref = read_exr(ref_path, o.width, o.height);
    double mse[2] = {0, 0}, seconds[2] = {0, 0};
    static const char *names[2] = {"nee_mis", "bsdf_only"};
    for (int mode = 0; mode < 2; mode++)
        for (int s = 0; s < o.seeds; s++) {
            snprintf(path, sizeof path, "%s/%s-%d.exr", dir, names[mode], s);
            seconds[mode] += run_pt(&o, o.spp, 1 + s, mode, path) / o.seeds;
            float *img = read_exr(path, o.width, o.height);
            mse[mode] += rel_mse(img, ref, n) / o.seeds;
            free(img);
            unlink(path);
        }
    unlink(ref_path);
    rmdir(dir);
    free(ref);
    char csv_path[1024];
    FILE *csv = bench_open_results_csv(device_name, o.csv, "env_variance.csv", csv_path, sizeof csv_path);
    fprintf(csv, "device,scene,width,height,spp,ref_spp,mode,seconds,rel_mse,rel_mse_x_seconds\n");
    printf("%s, %s %dx%d, %d spp (mean of %d seeds), reference %d spp\n", device_name, o.scene, o.width,
           o.height, o.spp, o.seeds, o.ref_spp);
    for (int mode = 0; mode < 2; mode++) {
        printf("  %-9s  %7.3f s  relMSE %.5f  relMSE x time %.5f\n", names[mode], seconds[mode], mse[mode],
               mse[mode] * seconds[mode]);
        fprintf(csv, "\"%s\",%s,%d,%d,%d,%d,%s,%.4f,%.6g,%.6g\n", device_name, o.scene, o.width, o.height,
                o.spp, o.ref_spp, names[mode], seconds[mode], mse[mode], mse[mode] * seconds[mode]);
    }
    printf("  NEE + MIS is %.2fx as efficient as BSDF-only (relMSE x time ratio; > 1: lower relMSE at equal time)\n",
           (mse[1] * seconds[1]) / (mse[0] * seconds[0]));
    fclose(csv);
    printf("wrote %s\n", csv_path);
    return 0;
}
