// SPDX-License-Identifier: MIT
/* wavefront.c: the frame loop. A render traces windows of samples; each window generates camera
 * paths into free slots, steps every live path (extend, [sort], shade and connect), compacts the
 * survivors and refills the pool, then accumulates the window into the film. The device state it
 * drives is set up in render/wavefront_state.c. */
#include <stdio.h>

#include "base/clock.h"
#include "render/megakernel.h"
#include "render/wavefront_internal.h"

static void run(Wavefront *w, int stage, size_t n)
{
    double ms = 0.0;
    device_run(w->dev, w->kernels[stage], n, 0, w->settings.profile ? &ms : NULL);
    w->stats->stage_ms[stage] += ms;
    w->stats->stage_launches[stage]++;
}

static void run_over_active(Wavefront *w, int stage, uint32_t n_active)
{
    cl_uint n = n_active;
    KERNEL_ARG(w->kernels[stage], w->n_active_arg[stage], n);
    run(w, stage, n_active);
}

/* With --profile the compactor adds its kernels' device time to stage_ms[STAGE_COMPACT_PATHS]
 * itself (compactor_set_profile in wavefront_state.c). */
static uint32_t compact_paths(Wavefront *w, uint32_t pool)
{
    uint32_t live = compactor_run(w->compactor, w->path_depth, w->active, pool);
    w->stats->stage_launches[STAGE_COMPACT_PATHS]++;
    return live;
}

/* The slots that the last compaction found dead, into free_slots (timed with the compaction). */
static void list_free_slots(Wavefront *w) { compactor_enqueue_free(w->compactor, w->free_slots); }

/* Starts window samples first .. first + n_new - 1 in free slots (slots 0.. when fresh) and
 * appends them to the active list after its n_live entries. */
static void generate(Wavefront *w, uint32_t n_live, uint32_t first, uint32_t n_new, bool fresh)
{
    cl_kernel k = w->kernels[STAGE_GENERATE_CAMERA_RAYS];
    cl_uint fresh_arg = fresh ? 1u : 0u;
    KERNEL_ARGS(k, w->generate_counts_arg, KARG(n_live), KARG(first), KARG(n_new), KARG(fresh_arg));
    run(w, STAGE_GENERATE_CAMERA_RAYS, n_new);
}

/* One step of every path in the active list: extend, shade, connect. */
static void trace_step(Wavefront *w, uint32_t n_active, uint32_t step)
{
    if (step < RENDER_LIVE_STEPS)
        w->stats->live_per_step[step] += n_active;
    if (w->kernels[STAGE_INTEGRATE_GEODESIC]) /* bends the rays near black holes */
        run_over_active(w, STAGE_INTEGRATE_GEODESIC, n_active);
    run_over_active(w, STAGE_INTERSECT_CLOSEST, n_active);
    if (w->sorter) {
        double ms = 0.0;
        material_sorter_set_profile(w->sorter, w->settings.profile ? &ms : NULL);
        material_sorter_run(w->sorter, w->hit, w->scene->material_ids, w->active, w->sorted_active,
                            n_active);
        w->stats->stage_ms[STAGE_SORT_MATERIALS] += ms;
        w->stats->stage_launches[STAGE_SORT_MATERIALS]++;
    }
    bool split = w->settings.split_shadow; /* else shading traces the shadow rays itself */
    if (split && !w->settings.shadow_flags) {
        uint32_t zero = 0;
        device_fill(w->dev, w->shadow_count, &zero, sizeof zero, 0, sizeof zero, NULL);
    }
    run_over_active(w, STAGE_SHADE_SURFACE, n_active);
    if (split)
        run_over_active(w, STAGE_INTERSECT_SHADOW, n_active);
}

/* The window's extension rays so far (a read-back: waits for the queue). */
static uint32_t extension_rays(Wavefront *w)
{
    uint32_t n;
    device_read(w->dev, w->counters, COUNTER_EXTENSION_RAYS * sizeof(uint32_t), sizeof n, &n);
    return n;
}

/* One window of samples, traced to the end: the wavefront loop. With compaction, each step's live
 * paths are compacted into the active list and the slots of the paths that ended are refilled
 * with the window's next samples, so the pool stays full until the window runs dry; the host
 * reads back one count per step. Without compaction (window = pool) every step runs over the
 * whole window, dead slots idle. The film gets the window's samples at the end, as exact sums. */
static void render_window(Wavefront *w, uint32_t window_start, uint32_t window_size, uint32_t sample_index)
{
    w->params.window_start = window_start;
    w->params.window_size = window_size;
    w->params.sample_index = w->settings.first_sample + w->block_first_sample + sample_index;
    device_write(w->dev, w->params_buf, 0, sizeof w->params, &w->params);

    uint32_t pool = w->stats->config.pool_size;
    if (w->kernels[STAGE_TRACE_PATHS]) {
        megakernel_trace_window(w, window_size); /* render/megakernel.c */
    } else if (w->settings.no_compaction) {
        generate(w, 0, 0, window_size, true);
        uint32_t step = 0;
        for (; step < (uint32_t)w->settings.max_depth; step++)
            trace_step(w, window_size, step);
        /* Passing an `interface` surface takes a step but is no bounce: with media a path may need
         * more steps than max_depth. Go on until a step extends no path. */
        if (w->dev->features & FEATURE_MEDIA) /* without media: no read-back at all */
            for (uint32_t before = extension_rays(w);; step++) {
                trace_step(w, window_size, step);
                uint32_t now = extension_rays(w);
                if (now == before)
                    break;
                before = now;
            }
    } else {
        uint32_t n_live = 0, next = 0;
        for (uint32_t step = 0;; step++) {
            uint32_t n_new = pool - n_live < window_size - next ? pool - n_live : window_size - next;
            if (n_new > 0) {
                if (step > 0)
                    list_free_slots(w);
                generate(w, n_live, next, n_new, step == 0);
                next += n_new;
            }
            uint32_t n_active = n_live + n_new;
            if (n_active == 0)
                break;
            trace_step(w, n_active, step);
            n_live = compact_paths(w, pool);
            if (next == window_size && n_live > 0 && n_live <= w->tail_paths &&
                tail_kernel_ready(w)) {
                run_over_active(w, STAGE_FINISH_PATHS, n_live); /* megakernel.h */
                break;
            }
        }
    }
    uint32_t np = w->params.window_pixels;
    run(w, STAGE_ACCUMULATE_FILM, window_size < np ? window_size : np);
    w->stats->paths += window_size;
    w->stats->windows++;
    /* The per-window ray counters stay far below 2^32; fold them into the 64-bit totals. */
    uint32_t rays[2], zeros[2] = {0, 0};
    _Static_assert(COUNTER_EXTENSION_RAYS == COUNTER_SHADOW_RAYS + 1, "ray counters are adjacent");
    device_read(w->dev, w->counters, COUNTER_SHADOW_RAYS * sizeof(uint32_t), sizeof rays, rays);
    w->stats->shadow_rays += rays[0];
    w->stats->extension_rays += rays[1];
    device_write(w->dev, w->counters, COUNTER_SHADOW_RAYS * sizeof(uint32_t), sizeof zeros, zeros);
}

/* The next window from the cursor: whole samples per pixel when the window holds the film (the
 * pixels adaptive sampling still samples), else a slice of pixels of one sample; never past the
 * next adaptive decision. Returns the paths traced. */
static uint32_t render_next_window(Wavefront *w, uint32_t max_spp)
{
    uint32_t window = w->stats->config.window_size, np = w->params.window_pixels, n;
    uint32_t end = adaptive_window_end(w, max_spp);
    if (window >= np && w->next_pixel == 0) {
        uint32_t k = window / np;
        if (k > end - w->next_sample)
            k = end - w->next_sample;
        n = k * np;
        render_window(w, 0, n, w->next_sample);
        w->next_sample += k;
    } else {
        n = np - w->next_pixel < window ? np - w->next_pixel : window;
        render_window(w, w->next_pixel, n, w->next_sample);
        w->next_pixel += n;
        if (w->next_pixel == np)
            w->next_pixel = 0, w->next_sample++;
    }
    adaptive_after_window(w);
    w->stats->spp_done = wavefront_spp_done(w);
    return n;
}

bool wavefront_at_whole_sample(const Wavefront *w) { return w->next_pixel == 0; }

uint64_t wavefront_advance(Wavefront *w, uint64_t min_paths, int max_spp)
{
    double start = seconds_now();
    uint64_t done = 0;
    while (done < min_paths && wavefront_spp_done(w) < max_spp && !w->adaptive.done)
        done += render_next_window(w, (uint32_t)max_spp);
    device_finish(w->dev);
    w->stats->seconds += seconds_now() - start;
    return done;
}

void wavefront_render_block(Wavefront *w, const PixelBlock *b)
{
    if (w->adaptive.on)
        die("wavefront_render_block: adaptive sampling decides per pixel over the whole film");
    double start = seconds_now();
    w->params.pixel_offset = b->first_pixel;
    w->params.window_pixels = b->num_pixels;
    w->block_first_sample = b->first_sample;
    w->next_sample = w->next_pixel = 0;
    while (w->next_sample < b->num_samples)
        render_next_window(w, b->num_samples);
    device_finish(w->dev);
    w->params.pixel_offset = 0;
    w->params.window_pixels = w->num_pixels;
    w->block_first_sample = 0;
    w->next_sample = w->next_pixel = 0;
    w->stats->seconds += seconds_now() - start;
}

bool wavefront_render(Device *dev, const Scene *scene, const SceneBuffers *buffers,
                      const RenderSettings *settings, float *rgb, RenderStats *stats, Error *err)
{
    Wavefront *w = wavefront_create(dev, scene, buffers, settings, err);
    if (!w)
        return false;
    /* Progress and stopping early belong to the caller (app/render_loop.c drives
     * wavefront_advance itself); this is the plain whole render that bench and tests use. */
    while (wavefront_spp_done(w) < settings->spp)
        wavefront_advance(w, 1, settings->spp);
    wavefront_read_film(w, rgb);
    *stats = *w->stats;
    wavefront_destroy(w);
    return true;
}
