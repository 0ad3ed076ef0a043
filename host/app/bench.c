// SPDX-License-Identifier: MIT
/* pt bench: a warm-up render (kernel compilation and first-launch costs stay out of the figures),
 * then timed renders of each mode (with and without compaction and refills), then one profiled
 * render for per-stage times (profiling waits after every launch, so its wall time is not used for
 * throughput), then the unit modes (bench_units.c). --device all or a list: the modes above run on
 * the first device, the unit modes on one and on all. */
#include "app/bench.h"

#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "render/session.h"
#include "render/wavefront.h"

RenderStats bench_render(Session *s, RenderSettings settings, float *rgb)
{
    RenderStats stats;
    Error err = {0};
    if (!wavefront_render(&s->dev, &s->scene, &s->buffers, &settings, rgb, &stats, &err))
        die("%s", err.message);
    return stats;
}

void bench_print_row(const char *label, const RenderStats *st)
{
    printf("%-16s %8.1f %12.2f %12.2f %12.2f %12.2f %9.3f\n", label, st->seconds * 1e3,
           st->paths / st->seconds * 1e-6, (st->extension_rays + st->shadow_rays) / st->seconds * 1e-6,
           st->extension_rays / st->seconds * 1e-6, st->shadow_rays / st->seconds * 1e-6,
           (double)(st->extension_rays + st->shadow_rays) / (double)st->paths);
}

FILE *bench_open_csv(const char *path, const char *header)
{
    FILE *f = fopen(path, "a");
    if (!f)
        die("cannot append to %s", path);
    if (ftell(f) == 0)
        fputs(header, f);
    return f;
}

void bench_append_csv(const char *path, const Session *s, const char *mode, const RenderStats *st)
{
    FILE *f = bench_open_csv(path, "device,scene,width,height,spp,max_depth,mode,seconds,"
                                   "mpaths_per_s,mrays_per_s,mext_per_s,mshadow_per_s,pool,window,"
                                   "state_mib\n");
    fprintf(f, "\"%s\",\"%s\",%d,%d,%d,%d,%s,%.6f,%.3f,%.3f,%.3f,%.3f,%u,%u,%.1f\n", s->dev.name,
            s->scene.desc.path, s->scene.desc.width, s->scene.desc.height, st->spp_done,
            s->scene.desc.max_depth, mode, st->seconds, st->paths / st->seconds * 1e-6,
            (st->extension_rays + st->shadow_rays) / st->seconds * 1e-6,
            st->extension_rays / st->seconds * 1e-6, st->shadow_rays / st->seconds * 1e-6,
            st->config.pool_size, st->config.window_size, st->config.device_bytes / 1048576.0);
    fclose(f);
}

/* FILE.csv -> FILE_<suffix>.csv */
void bench_sibling_path(char *out, size_t size, const char *csv, const char *suffix)
{
    size_t n = strlen(csv);
    if (n >= 4 && !strcmp(csv + n - 4, ".csv"))
        n -= 4;
    snprintf(out, size, "%.*s_%s.csv", (int)n, csv, suffix);
}

/* The profiled run: per-stage launches and ms into FILE_stages.csv, live paths per step into
 * FILE_live.csv (next to the --csv FILE). */
static void append_profile_csv(const char *csv, const Session *s, const RenderStats *st)
{
    char path[4096];
    bench_sibling_path(path, sizeof path, csv, "stages");
    FILE *f = bench_open_csv(path, "device,scene,width,height,spp,stage,launches,ms\n");
    for (int k = 0; k < STAGE_COUNT; k++)
        fprintf(f, "\"%s\",\"%s\",%d,%d,%d,%s,%u,%.4f\n", s->dev.name, s->scene.desc.path,
                s->scene.desc.width, s->scene.desc.height, st->spp_done, stage_names[k],
                st->stage_launches[k], st->stage_ms[k]);
    fclose(f);
    bench_sibling_path(path, sizeof path, csv, "live");
    f = bench_open_csv(path, "device,scene,width,height,spp,step,live_paths\n");
    for (int b = 0; b < RENDER_LIVE_STEPS && st->live_per_step[b]; b++)
        fprintf(f, "\"%s\",\"%s\",%d,%d,%d,%d,%llu\n", s->dev.name, s->scene.desc.path,
                s->scene.desc.width, s->scene.desc.height, st->spp_done, b,
                (unsigned long long)st->live_per_step[b]);
    fclose(f);
}

/* The ablations: "default" is what pt render does (compaction, slots refilled from a window of
 * WINDOW_PER_POOL pools, shadow rays queued, material sorting when session_sorts_materials says
 * so); "refill" the same never sorted; then with a shadow flag per active path, with material sorting,
 * compaction without refills (window = pool: each pool's worth of paths runs to the end), and
 * neither (every bounce over the whole pool). "default" takes the path kernel pt render takes (on
 * CPUs the megakernel, render/megakernel.h); the wavefront's ablations are pinned to the
 * wavefront; "megakernel" is the megakernel on any device (with packets where it has them),
 * "megakernel-single" the one with one path per work item; "split-shadow" the wavefront whose
 * shading leaves its shadow rays to intersect_shadow (RenderSettings.split_shadow), sorting as
 * the default; "shadow-flags" is split too. */
typedef struct {
    const char *name;
    bool no_compaction;
    uint32_t window_size; /* 1: clamped up to the pool, i.e. no refills */
    bool shadow_flags;
    int sort_materials; /* SORT_MATERIALS_* (render/session.h) */
    bool brute_force; /* only on scenes of at most BRUTE_FORCE_MAX_TRIANGLES */
    int path_kernel;  /* PATH_KERNEL_* */
    bool split_shadow;
} BenchMode;

static const BenchMode modes[] = {
    {"default", false, 0, false, SORT_MATERIALS_AUTO, false, PATH_KERNEL_AUTO, false},
    {"refill", false, 0, false, SORT_MATERIALS_OFF, false, PATH_KERNEL_WAVEFRONT, false},
    {"megakernel", false, 0, false, SORT_MATERIALS_OFF, false, PATH_KERNEL_MEGAKERNEL, false},
    {"megakernel-single", false, 0, false, SORT_MATERIALS_OFF, false, PATH_KERNEL_MEGAKERNEL_SINGLE, false},
    {"shadow-flags", false, 0, true, SORT_MATERIALS_OFF, false, PATH_KERNEL_WAVEFRONT, false},
    {"no-refill", false, 1, false, SORT_MATERIALS_OFF, false, PATH_KERNEL_WAVEFRONT, false},
    {"no-compaction", true, 0, false, SORT_MATERIALS_OFF, false, PATH_KERNEL_WAVEFRONT, false},
    {"sort-materials", false, 0, false, SORT_MATERIALS_ON, false, PATH_KERNEL_WAVEFRONT, false},
    {"split-shadow", false, 0, false, SORT_MATERIALS_AUTO, false, PATH_KERNEL_WAVEFRONT, true},
    {"brute-force", false, 0, false, SORT_MATERIALS_OFF, true, PATH_KERNEL_WAVEFRONT, false},
};
#define BRUTE_FORCE_MAX_TRIANGLES 4096
#define NUM_MODES (sizeof modes / sizeof modes[0])

int command_bench(const Options *o)
{
    Error err = {0};
    Session s;
    RenderDesc desc = cli_render_desc(o);
    DeviceSpecList list = {0};
    if (device_spec_is_list(o->device)) {
        if (!device_spec_list(o->device, &list, &err))
            die("%s", err.message);
        desc.device = list.spec[0];
    }
    if (!session_open(&s, &desc, &err))
        die("%s", err.message);
    session_print_summary(&s);
    const SceneDesc *d = &s.scene.desc;
    float *rgb = malloc((size_t)d->width * d->height * 3 * sizeof *rgb);
    if (!rgb)
        die("out of memory for a %dx%d film", d->width, d->height);
    /* The options' settings (--clamp measured as pt render renders with it); the switches below
     * are the modes'. */
    RenderSettings base = cli_render_settings(o);
    session_settle_settings(&s, &base, SORT_MATERIALS_OFF);

    RenderStats stats[NUM_MODES];
    size_t num_modes = NUM_MODES;
    if (s.scene.data.num_triangles > BRUTE_FORCE_MAX_TRIANGLES)
        num_modes--; /* the brute-force row comes last */
    RenderSettings settings[NUM_MODES];
    for (size_t m = 0; m < num_modes; m++) {
        settings[m] = base;
        settings[m].no_compaction = modes[m].no_compaction;
        settings[m].window_size = modes[m].window_size;
        settings[m].shadow_flags = modes[m].shadow_flags;
        settings[m].brute_force = modes[m].brute_force;
        settings[m].path_kernel = modes[m].path_kernel;
        settings[m].split_shadow = modes[m].split_shadow;
        settings[m].sort_materials = session_sorts_materials(&s.scene.data, modes[m].sort_materials);
        /* Warm-up: PoCL specialises each kernel for the launch sizes it first sees (a second or
         * more, once per machine); keep that out of the figures. */
        RenderSettings warm = settings[m];
        warm.spp = 1;
        bench_render(&s, warm, rgb);
    }
    for (size_t m = 0; m < num_modes; m++)
        stats[m] = bench_render(&s, settings[m], rgb);

    printf("pt bench: %s, %dx%d, %d spp, max depth %d, device %s, pool %u paths, window %u samples, "
           "%.1f MiB of path state\n",
           d->path, d->width, d->height, d->spp, d->max_depth, s.dev.name,
           stats[0].config.pool_size, stats[0].config.window_size,
           stats[0].config.device_bytes / 1048576.0);
    printf("%-16s %8s %12s %12s %12s %12s %9s\n", "mode", "ms", "Mpaths/s", "Mrays/s", "Mext/s",
           "Mshadow/s", "rays/path");
    for (size_t m = 0; m < num_modes; m++) {
        bench_print_row(modes[m].name, &stats[m]);
        if (o->csv)
            bench_append_csv(o->csv, &s, modes[m].name, &stats[m]);
    }

    RenderSettings profiled = settings[0]; /* the default mode */
    profiled.profile = true;
    RenderStats prof = bench_render(&s, profiled, rgb);
    render_stats_print_profile(stdout, &prof, "stage (profiled run)");
    if (o->csv)
        append_profile_csv(o->csv, &s, &prof);
    bench_units(&s, o, &list, settings[0], rgb);
    free(rgb);
    session_close(&s);
    return 0;
}
