// SPDX-License-Identifier: MIT
/* bench_geodesic: the cost of black holes (integrate_geodesic.cl) on one scene.
 *
 *   build/tools/bench_geodesic SCENE [--width W] [--height H] [--spp N] [--device D]
 *
 * Renders SCENE twice with --profile-style stage timing: as written, then with its black holes
 * left out (same program, same film). Prints Mpaths/s of both, the geodesic stage's share of the
 * device time, and the steps per curved ray (mean, and p99 from the stage's histogram, to within
 * its GEODESIC_BIN_STEPS bins). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/session.h"
#include "render/wavefront_internal.h"

static double render(Session *s, RenderSettings rs, uint32_t geo[GEODESIC_STAT_WORDS],
                     double *share)
{
    Error err = {0};
    Wavefront *w = wavefront_create(&s->dev, &s->scene, &s->buffers, &rs, &err);
    if (!w)
        die("%s", err.message);
    wavefront_advance(w, (uint64_t)rs.spp * s->scene.desc.width * s->scene.desc.height, rs.spp);
    RenderStats *st = wavefront_stats(w);
    double total = 0.0;
    for (int k = 0; k < STAGE_COUNT; k++)
        total += st->stage_ms[k];
    *share = total > 0.0 ? st->stage_ms[STAGE_INTEGRATE_GEODESIC] / total : 0.0;
    if (w->geodesic_stats)
        device_read(&s->dev, w->geodesic_stats, 0, GEODESIC_STAT_WORDS * sizeof(uint32_t), geo);
    double mpaths = (double)st->paths / st->seconds * 1e-6;
    wavefront_destroy(w);
    return mpaths;
}

int main(int argc, char **argv)
{
    RenderDesc desc = {0};
    int spp = 1;
    for (int i = 1; i < argc; i++) {
        if (i + 1 < argc && !strcmp(argv[i], "--width"))
            desc.width = atoi(argv[++i]);
        else if (i + 1 < argc && !strcmp(argv[i], "--height"))
            desc.height = atoi(argv[++i]);
        else if (i + 1 < argc && !strcmp(argv[i], "--spp"))
            spp = atoi(argv[++i]);
        else if (i + 1 < argc && !strcmp(argv[i], "--device"))
            desc.device = argv[++i];
        else if (argv[i][0] != '-' && !desc.scene)
            desc.scene = argv[i];
        else
            die("usage: bench_geodesic SCENE [--width W] [--height H] [--spp N] [--device D]");
    }
    if (!desc.scene)
        die("usage: bench_geodesic SCENE [--width W] [--height H] [--spp N] [--device D]");
    Session s;
    Error err = {0};
    if (!session_open(&s, &desc, &err))
        die("%s", err.message);
    RenderSettings rs = {.spp = spp, .max_depth = s.scene.desc.max_depth, .profile = true};
    uint32_t geo[GEODESIC_STAT_WORDS] = {0}, none[GEODESIC_STAT_WORDS];
    double share, share0;
    /* A first render warms the device (PoCL's kernel compile on first launch). */
    render(&s, (RenderSettings){.spp = 1, .max_depth = 1}, none, &share);
    double with = render(&s, rs, geo, &share);
    int holes = s.scene.desc.num_black_holes;
    s.scene.desc.num_black_holes = 0;
    double without = render(&s, rs, none, &share0);
    s.scene.desc.num_black_holes = holes;
    uint32_t rays = geo[GEODESIC_STAT_RAYS], p99 = 0, seen = 0;
    for (uint32_t b = 0; b < GEODESIC_BINS; b++) {
        seen += geo[GEODESIC_STAT_HISTOGRAM + b];
        if (rays > 0 && seen >= rays - rays / 100) {
            p99 = (b + 1) * GEODESIC_BIN_STEPS;
            break;
        }
    }
    printf("scene %s, %dx%d, %d spp, device %s\n", desc.scene, s.scene.desc.width,
           s.scene.desc.height, spp, s.dev.name);
    printf("with holes:    %.4f Mpaths/s (integrate_geodesic %.1f%% of device time)\n", with,
           100.0 * share);
    printf("without holes: %.4f Mpaths/s\n", without);
    printf("curved rays %u (%u captured), steps per curved ray: mean %.1f, p99 <= %u\n", rays,
           geo[GEODESIC_STAT_CAPTURED], rays ? (double)geo[GEODESIC_STAT_STEPS] / rays : 0.0, p99);
    session_close(&s);
    return 0;
}
