// SPDX-License-Identifier: MIT
/* megakernel.c: the path-per-work-item kernels on CPUs. PoCL runs each work item on one core, one
 * operation after another, so the wavefront's per-stage kernels buy nothing there that a GPU needs
 * them for, and cost a round trip of each path's state through memory per stage, a compaction and
 * a count read-back per step (bench/README.md, "CPU (PoCL) throughput"). trace_paths and
 * trace_paths_packets (eight paths per work item, their rays traced as packets) run the same
 * stage functions (cl/stages/megakernel.cl), so the film's bits are the wavefront's. */
#include "base/env.h"
#include "render/megakernel.h"
#include "render/wavefront_internal.h"

/* trace_paths_packets' work-group: 8 items of 8 paths, as many paths as trace_paths' 64 items.
 * Groups of 64 packet items (512 paths) left one of the 2 cores idle for a sixth of the dragon
 * box's render on PoCL (wall 2.5 s for 4.2 CPU seconds, against 2.3 for 4.25 with one path per
 * item); with 8 the two kernels keep both cores busy alike. */
#define PACKET_GROUP_ITEMS 8

static bool wants_megakernel(const Wavefront *w, Error *err, bool *out)
{
    const RenderSettings *s = &w->settings;
    bool cpu = (w->dev->type & CL_DEVICE_TYPE_CPU) != 0;
    if (s->path_kernel == PATH_KERNEL_AUTO) {
        if (!env_flag("PT_MEGAKERNEL", cpu, out, err))
            return false;
    } else {
        *out = s->path_kernel == PATH_KERNEL_MEGAKERNEL ||
               s->path_kernel == PATH_KERNEL_MEGAKERNEL_SINGLE;
    }
    /* The ablations measure the wavefront's parts; bent rays are a stage of their own. Material
     * sorting orders the wavefront's shading launches and has nothing to order here (and loses on
     * PoCL, bench/README.md): it does not keep a render off the megakernel. */
    if (s->no_compaction || s->brute_force || w->kernels[STAGE_INTEGRATE_GEODESIC])
        *out = false;
    return true;
}

bool megakernel_init(Wavefront *w, Error *err)
{
    bool use;
    if (!wants_megakernel(w, err, &use))
        return false;
    w->stats->config.megakernel = use;
    if (!use)
        return true;
    /* Packets where the program has them (8-wide layout, one BVH level, no cut-outs: see
     * cl/stages/megakernel.cl); PT_PACKETS=0 or PATH_KERNEL_MEGAKERNEL_SINGLE keep one path per
     * work item (the A/B). */
    bool packets = w->settings.path_kernel != PATH_KERNEL_MEGAKERNEL_SINGLE;
    if (w->settings.path_kernel == PATH_KERNEL_AUTO && !env_flag("PT_PACKETS", true, &packets, err))
        return false;
    cl_kernel k = packets ? device_kernel_if_built(w->dev, "trace_paths_packets") : NULL;
    w->stats->config.packets = k != NULL;
    w->megakernel_paths = k ? PACKET_RAYS : 1;
    if (!k)
        k = device_kernel(w->dev, "trace_paths");
    w->kernels[STAGE_TRACE_PATHS] = k;
    cl_uint zero = 0;
    w->megakernel_counts_arg = wavefront_set_path_args(w, k, true);
    KERNEL_ARGS(k, w->megakernel_counts_arg, KARG(zero), KARG(zero), KARG(w->counters));
    return true;
}

void megakernel_trace_window(Wavefront *w, uint32_t window_size)
{
    cl_kernel k = w->kernels[STAGE_TRACE_PATHS];
    uint32_t pool = w->stats->config.pool_size;
    for (uint32_t first = 0; first < window_size; first += pool) {
        cl_uint n = window_size - first < pool ? window_size - first : pool;
        KERNEL_ARGS(k, w->megakernel_counts_arg, KARG(first), KARG(n));
        double ms = 0.0;
        size_t items = (n + w->megakernel_paths - 1) / w->megakernel_paths;
        device_run(w->dev, k, items, w->megakernel_paths > 1 ? PACKET_GROUP_ITEMS : 0,
                   w->settings.profile ? &ms : NULL);
        w->stats->stage_ms[STAGE_TRACE_PATHS] += ms;
        w->stats->stage_launches[STAGE_TRACE_PATHS]++;
    }
}

bool tail_init(Wavefront *w, Error *err)
{
    const RenderSettings *s = &w->settings;
    w->tail_paths = 0;
    if (w->kernels[STAGE_TRACE_PATHS] || s->no_compaction || s->brute_force ||
        w->kernels[STAGE_INTEGRATE_GEODESIC] || s->tail_paths < 0)
        return true;
    long paths = s->tail_paths;
    if (paths == 0 && !env_int("PT_TAIL_PATHS", 0, 1L << 30, TAIL_PATHS_DEFAULT, &paths, err))
        return false;
    w->tail_paths = (uint32_t)paths;
    if (s->tail_paths > 0) /* asked for: from the first window on */
        w->kernels[STAGE_FINISH_PATHS] = device_kernel(w->dev, "finish_paths");
    else if (paths > 0) {
        device_build_in_background(w->dev, "finish_paths");
        tail_kernel_ready(w); /* a part from the kernel cache is there now: its kernel too, so
                               * that no render's time includes creating it */
    }
    return true;
}

bool tail_kernel_ready(Wavefront *w)
{
    if (!w->kernels[STAGE_FINISH_PATHS] && w->tail_paths > 0) {
        w->kernels[STAGE_FINISH_PATHS] = device_kernel_ready(w->dev, "finish_paths");
        if (w->kernels[STAGE_FINISH_PATHS])
            wavefront_bind_tail(w);
    }
    return w->kernels[STAGE_FINISH_PATHS] != NULL;
}
