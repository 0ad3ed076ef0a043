// SPDX-License-Identifier: MIT
/* megakernel.c: the path-per-work-item kernel on CPUs. PoCL runs each work item on one core, one
 * operation after another, so the wavefront's per-stage kernels buy nothing there that a GPU needs
 * them for, and cost a round trip of each path's state through memory per stage, a compaction and
 * a count read-back per step (bench/README.md, "CPU (PoCL) throughput"). trace_paths runs the same
 * stage functions (cl/stages/megakernel.cl), so the film's bits are the wavefront's. */
#include "base/env.h"
#include "render/megakernel.h"
#include "render/wavefront_internal.h"

static bool wants_megakernel(const Wavefront *w, Error *err, bool *out)
{
    const RenderSettings *s = &w->settings;
    bool cpu = (w->dev->type & CL_DEVICE_TYPE_CPU) != 0;
    if (s->path_kernel == PATH_KERNEL_AUTO) {
        if (!env_flag("PT_MEGAKERNEL", cpu, out, err))
            return false;
    } else {
        *out = s->path_kernel == PATH_KERNEL_MEGAKERNEL;
    }
    /* The ablations measure the wavefront's parts; bent rays are a stage of their own. Material
     * sorting orders the wavefront's shading launches and has nothing to order here (and loses on
     * PoCL, bench/README.md): it does not keep a render off the megakernel. */
    if (s->no_compaction || s->brute_force || w->kernels[STAGE_GEODESIC])
        *out = false;
    return true;
}

bool megakernel_init(Wavefront *w, Error *err)
{
    bool use;
    if (!wants_megakernel(w, err, &use))
        return false;
    w->stats->megakernel = use;
    if (!use)
        return true;
    cl_kernel k = device_kernel(w->dev, "trace_paths");
    w->kernels[STAGE_MEGAKERNEL] = k;
    cl_uint zero = 0;
    w->megakernel_counts_arg = wavefront_set_path_args(w, k, true);
    KERNEL_ARGS(k, w->megakernel_counts_arg, KARG(zero), KARG(zero), KARG(w->counters));
    return true;
}

void megakernel_trace_window(Wavefront *w, uint32_t window_size)
{
    cl_kernel k = w->kernels[STAGE_MEGAKERNEL];
    uint32_t pool = w->stats->pool_size;
    for (uint32_t first = 0; first < window_size; first += pool) {
        cl_uint n = window_size - first < pool ? window_size - first : pool;
        KERNEL_ARGS(k, w->megakernel_counts_arg, KARG(first), KARG(n));
        double ms = 0.0;
        device_run(w->dev, k, n, 0, w->settings.profile ? &ms : NULL);
        w->stats->stage_ms[STAGE_MEGAKERNEL] += ms;
        w->stats->stage_launches[STAGE_MEGAKERNEL]++;
    }
}
