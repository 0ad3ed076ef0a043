// SPDX-License-Identifier: MIT
#include "render/wavefront.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "render/film.h"
#include "scene/camera.h"
#include "parallel/compact.h"
#include "parallel/material_sort.h"

const char *const stage_names[STAGE_COUNT] = {
    "generate_camera_rays", "intersect_closest", "sort_materials", "shade_surface",
    "intersect_shadow",     "compact_paths",     "accumulate_film",
};

static volatile sig_atomic_t g_stop_requested;
void wavefront_request_stop(void) { g_stop_requested = 1; }

/* Everything one render holds on the device. */
struct Wavefront {
    Device *dev;
    const SceneBuffers *scene;
    RenderSettings settings;
    RenderParams params;
    RenderStats *stats;
    Film film;
    cl_mem params_buf, counters, active, free_slots;
    cl_mem shadow_queue, shadow_count; /* unless settings.shadow_flags */
    cl_mem sorted_active;              /* with settings.sort_materials: shade_surface's list */
    MaterialSorter *sorter;
#define PATH_STATE_MEMBER(type, name) cl_mem name;
    PATH_STATE_FIELDS(PATH_STATE_MEMBER)
    SAMPLE_STATE_FIELDS(PATH_STATE_MEMBER)
#undef PATH_STATE_MEMBER
    cl_kernel kernels[STAGE_COUNT];
    cl_uint n_active_arg[STAGE_COUNT]; /* index of the n_active argument of the traced stages */
    cl_uint generate_counts_arg;       /* index of generate_camera_rays' n_live */
    Compactor *compactor;
    uint32_t num_pixels;
    uint32_t next_sample, next_pixel; /* where the next batch starts (next_sample counts the
                                       * film's samples: its index is first_sample + next_sample) */
    RenderStats own_stats;
};

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Device bytes per path slot and per window sample (the film, the scene and the compactor's few
 * bits per slot aside). */
#define FIELD_BYTES(type, name) +sizeof(type)
static const uint64_t bytes_per_slot = 2 * sizeof(uint32_t) /* active, free_slots */ PATH_STATE_FIELDS(FIELD_BYTES);
static const uint64_t bytes_per_sample = 0 SAMPLE_STATE_FIELDS(FIELD_BYTES);
#undef FIELD_BYTES

/* Path slots and window: enough paths in flight to fill a GPU, modest on a CPU; both shrink until
 * every buffer fits the device's max allocation and all of them half its memory. */
static void choose_pool_size(const Device *dev, const RenderSettings *s, uint64_t total_samples,
                             uint32_t *pool_out, uint32_t *window_out)
{
    uint64_t pool = s->pool_size ? s->pool_size : (dev->type & CL_DEVICE_TYPE_GPU) ? 1u << 21 : 1u << 16;
    uint64_t window = s->window_size ? s->window_size : WINDOW_PER_POOL * pool;
    if (s->no_compaction || window < pool)
        window = pool; /* without compaction there are no free slots to refill */
    while (pool > 1024 && (window * sizeof(float4) > dev->max_alloc ||
                           pool * bytes_per_slot + window * bytes_per_sample > dev->global_mem / 2)) {
        pool /= 2;
        window /= 2;
    }
    if (window > total_samples)
        window = total_samples;
    if (pool > window)
        pool = window;
    *pool_out = (uint32_t)pool;
    *window_out = (uint32_t)window;
}

static void set_all_args(Wavefront *w);

static cl_mem state_buffer(Wavefront *w, const char *name, size_t size, Error *err)
{
    if (error_is_set(err))
        return NULL;
    return device_buffer(w->dev, name, CL_MEM_READ_WRITE, size, NULL, err);
}

/* The kernel of a stage: the brute-force ablation (every ray against every triangle) has
 * intersection kernels of its own, so that the production ones carry no branch for it. */
static const char *stage_kernel(int stage, bool brute_force)
{
    if (brute_force && stage == STAGE_EXTEND)
        return "intersect_closest_brute_force";
    if (brute_force && stage == STAGE_CONNECT)
        return "intersect_shadow_brute_force";
    return stage_names[stage];
}

static bool wavefront_init(Wavefront *w, Device *dev, const Scene *scene,
                           const SceneBuffers *buffers, const RenderSettings *s, Error *err)
{
    memset(w, 0, sizeof *w);
    RenderStats *stats = &w->own_stats;
    w->dev = dev, w->scene = buffers, w->settings = *s, w->stats = stats;
    const SceneDesc *desc = &scene->desc;
    w->num_pixels = (uint32_t)desc->width * (uint32_t)desc->height;
    uint32_t pool, window;
    choose_pool_size(dev, s, (uint64_t)w->num_pixels * (uint64_t)s->spp, &pool, &window);
    stats->pool_size = pool;
    stats->window_size = window;
    stats->device_bytes = pool * bytes_per_slot + window * bytes_per_sample +
                          (uint64_t)w->num_pixels * FILM_BYTES_PER_PIXEL;

    w->params = (RenderParams){
        .camera = camera_from_desc(&desc->camera, desc->width, desc->height),
        .background = {{desc->background[0], desc->background[1], desc->background[2], 0.0f}},
        .width = (uint)desc->width,
        .height = (uint)desc->height,
        .seed = s->seed,
        .max_depth = (uint)s->max_depth,
        .num_bvh_prims = buffers->num_bvh_prims,
        .num_emissive = buffers->num_emissive,
        .emissive_power = buffers->emissive_power,
        .flags = (s->no_nee ? RENDER_NO_NEE : 0u) | (s->shadow_flags ? 0u : RENDER_SHADOW_QUEUE),
    };
    w->params_buf = state_buffer(w, "params", sizeof w->params, err);
    if (error_is_set(err) || !film_init(&w->film, dev, w->num_pixels, err))
        return false;
    w->counters = state_buffer(w, "counters", COUNTER_COUNT * sizeof(uint32_t), err);
    w->active = state_buffer(w, "active_paths", pool * sizeof(uint32_t), err);
    w->free_slots = state_buffer(w, "free_slots", pool * sizeof(uint32_t), err);
    w->shadow_queue = state_buffer(w, "shadow_queue", (s->shadow_flags ? 1 : pool) * sizeof(uint32_t), err);
    w->shadow_count = state_buffer(w, "shadow_count", sizeof(uint32_t), err);
#define PATH_STATE_ALLOC(type, name) w->name = state_buffer(w, #name, pool * sizeof(type), err);
    PATH_STATE_FIELDS(PATH_STATE_ALLOC)
#undef PATH_STATE_ALLOC
#define SAMPLE_STATE_ALLOC(type, name) w->name = state_buffer(w, #name, window * sizeof(type), err);
    SAMPLE_STATE_FIELDS(SAMPLE_STATE_ALLOC)
#undef SAMPLE_STATE_ALLOC
    if (error_is_set(err))
        return false;
    /* Every slot starts free: compaction reads the flags of the whole pool. */
    uint32_t zero = 0;
    CL_CHECK(clEnqueueFillBuffer(dev->queue, w->path_depth, &zero, sizeof zero, 0,
                                 pool * sizeof(uint32_t), 0, NULL, NULL));
    w->compactor = compactor_create(dev, pool, err);
    if (!w->compactor)
        return false;
    if (s->sort_materials) {
        w->sorted_active = state_buffer(w, "sorted_active_paths", pool * sizeof(uint32_t), err);
        w->sorter = w->sorted_active ? material_sorter_create(dev, pool, scene->data.num_materials, err) : NULL;
        if (!w->sorter)
            return false;
    }
    for (int k = 0; k < STAGE_COUNT; k++)
        if (k != STAGE_COMPACT && k != STAGE_SORT)
            w->kernels[k] = device_kernel(dev, stage_kernel(k, s->brute_force));
    set_all_args(w);
    wavefront_reset(w);
    return true;
}

void wavefront_reset(Wavefront *w)
{
    uint32_t zero = 0;
    film_clear(&w->film);
    CL_CHECK(clEnqueueFillBuffer(w->dev->queue, w->counters, &zero, sizeof zero, 0,
                                 COUNTER_COUNT * sizeof(uint32_t), 0, NULL, NULL));
    RenderStats sizes = *w->stats;
    memset(w->stats, 0, sizeof *w->stats);
    w->stats->pool_size = sizes.pool_size;
    w->stats->window_size = sizes.window_size;
    w->stats->device_bytes = sizes.device_bytes;
    w->next_sample = w->next_pixel = 0;
}

void wavefront_set_camera(Wavefront *w, const Camera *camera)
{
    w->params.camera = *camera;
    wavefront_reset(w);
}

/* Arguments in the order of cl/stages/path_state.cl: params, [scene buffers], path state, then
 * the stage's own. Returns the index of the first of the stage's own arguments. */
static cl_uint set_path_args(Wavefront *w, cl_kernel k, bool with_scene)
{
    cl_uint i = KERNEL_ARGS(k, 0, KARG(w->params_buf));
    if (with_scene)
        i = scene_buffers_set_args(w->scene, k, i);
#define PATH_STATE_ARG(type, name) KARG(w->name),
    KernelArg state[] = {PATH_STATE_FIELDS(PATH_STATE_ARG) SAMPLE_STATE_FIELDS(PATH_STATE_ARG)};
#undef PATH_STATE_ARG
    return kernel_set_args(k, i, sizeof state / sizeof state[0], state);
}

/* Binds every argument once; the counts that change per launch (n_active, generate's counts) are
 * set again before each launch at the indices recorded here. */
static void set_all_args(Wavefront *w)
{
    cl_uint zero = 0, i;
    cl_kernel generate = w->kernels[STAGE_GENERATE];
    i = set_path_args(w, generate, false);
    w->generate_counts_arg = KERNEL_ARGS(generate, i, KARG(w->active), KARG(w->free_slots));

    cl_kernel extend = w->kernels[STAGE_EXTEND];
    i = set_path_args(w, extend, true);
    w->n_active_arg[STAGE_EXTEND] = i + 1;
    KERNEL_ARGS(extend, i, KARG(w->active), KARG(zero), KARG(w->counters));

    cl_kernel shade = w->kernels[STAGE_SHADE];
    cl_mem shade_list = w->sorted_active ? w->sorted_active : w->active;
    i = set_path_args(w, shade, true);
    w->n_active_arg[STAGE_SHADE] = i + 1;
    KERNEL_ARGS(shade, i, KARG(shade_list), KARG(zero), KARG(w->shadow_queue), KARG(w->shadow_count));

    cl_kernel connect = w->kernels[STAGE_CONNECT];
    i = set_path_args(w, connect, true);
    w->n_active_arg[STAGE_CONNECT] = i + 1;
    KERNEL_ARGS(connect, i, KARG(w->active), KARG(zero), KARG(w->counters), KARG(w->shadow_queue),
                KARG(w->shadow_count));

    cl_kernel accumulate = w->kernels[STAGE_ACCUMULATE];
    i = set_path_args(w, accumulate, false);
    KERNEL_ARGS(accumulate, i, KARG(w->film.sums), KARG(w->counters));
}

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

static uint32_t compact_paths(Wavefront *w, uint32_t pool)
{
    double t = seconds_now();
    uint32_t live = compactor_run(w->compactor, w->path_depth, w->active, pool);
    if (w->settings.profile)
        w->stats->stage_ms[STAGE_COMPACT] += 1e3 * (seconds_now() - t);
    w->stats->stage_launches[STAGE_COMPACT]++;
    return live;
}

/* The slots that the last compaction found dead, into free_slots (timed with the compaction). */
static void list_free_slots(Wavefront *w)
{
    double t = seconds_now();
    compactor_enqueue_free(w->compactor, w->free_slots);
    if (w->settings.profile) {
        CL_CHECK(clFinish(w->dev->queue));
        w->stats->stage_ms[STAGE_COMPACT] += 1e3 * (seconds_now() - t);
    }
}

/* Starts window samples first .. first + n_new - 1 in free slots (slots 0.. when fresh) and
 * appends them to the active list after its n_live entries. */
static void generate(Wavefront *w, uint32_t n_live, uint32_t first, uint32_t n_new, bool fresh)
{
    cl_kernel k = w->kernels[STAGE_GENERATE];
    cl_uint fresh_arg = fresh ? 1u : 0u;
    KERNEL_ARGS(k, w->generate_counts_arg, KARG(n_live), KARG(first), KARG(n_new), KARG(fresh_arg));
    run(w, STAGE_GENERATE, n_new);
}

/* One step of every path in the active list: extend, shade, connect. */
static void trace_step(Wavefront *w, uint32_t n_active, uint32_t step)
{
    if (step < 64)
        w->stats->live_per_step[step] += n_active;
    run_over_active(w, STAGE_EXTEND, n_active);
    if (w->sorter) {
        double ms = 0.0;
        material_sorter_set_profile(w->sorter, w->settings.profile ? &ms : NULL);
        material_sorter_run(w->sorter, w->hit, w->scene->material_ids, w->active, w->sorted_active,
                            n_active);
        w->stats->stage_ms[STAGE_SORT] += ms;
        w->stats->stage_launches[STAGE_SORT]++;
    }
    if (!w->settings.shadow_flags) {
        uint32_t zero = 0;
        CL_CHECK(clEnqueueFillBuffer(w->dev->queue, w->shadow_count, &zero, sizeof zero, 0,
                                     sizeof zero, 0, NULL, NULL));
    }
    run_over_active(w, STAGE_SHADE, n_active);
    run_over_active(w, STAGE_CONNECT, n_active);
}

/* One window of samples, traced to the end: the wavefront loop. With compaction, each step's live
 * paths are compacted into the active list and the slots of the paths that ended are refilled
 * with the window's next samples, so the pool stays full until the window runs dry; the host
 * reads back one count per step. Without compaction (window = pool) every step runs over the
 * whole window, dead slots idle. The film gets the window's samples at the end, as exact sums. */
static void render_window(Wavefront *w, uint32_t window_start, uint32_t window_size, uint32_t sample_index)
{
    w->params.batch_start = window_start;
    w->params.batch_size = window_size;
    w->params.sample_index = w->settings.first_sample + sample_index;
    device_write(w->dev, w->params_buf, 0, sizeof w->params, &w->params);

    uint32_t pool = w->stats->pool_size;
    if (w->settings.no_compaction) {
        generate(w, 0, 0, window_size, true);
        for (uint32_t depth = 1; depth <= (uint32_t)w->settings.max_depth; depth++)
            trace_step(w, window_size, depth - 1);
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
        }
    }
    run(w, STAGE_ACCUMULATE, window_size < w->num_pixels ? window_size : w->num_pixels);
    w->stats->paths += window_size;
    w->stats->batches++;
    /* The per-window ray counters stay far below 2^32; fold them into the 64-bit totals. */
    uint32_t rays[2], zeros[2] = {0, 0};
    _Static_assert(COUNTER_EXTENSION_RAYS == COUNTER_SHADOW_RAYS + 1, "ray counters are adjacent");
    device_read(w->dev, w->counters, COUNTER_SHADOW_RAYS * sizeof(uint32_t), sizeof rays, rays);
    w->stats->shadow_rays += rays[0];
    w->stats->extension_rays += rays[1];
    device_write(w->dev, w->counters, COUNTER_SHADOW_RAYS * sizeof(uint32_t), sizeof zeros, zeros);
}

static void print_progress(const RenderStats *stats, int spp, double elapsed, uint64_t done,
                           uint64_t total)
{
    double rate = done / (elapsed > 0 ? elapsed : 1e-9);
    double eta = (double)(total - done) / (rate > 0 ? rate : 1);
    fprintf(stderr, "\rpt: %5.1f%%  %d/%d spp  %.2f Msamples/s  elapsed %.1f s  ETA %.1f s   ",
            100.0 * (double)done / (double)total, stats->spp_done, spp, rate * 1e-6, elapsed, eta);
    fflush(stderr);
}

/* The next window from the cursor: whole samples per pixel when the window holds the film, else a
 * slice of pixels of one sample. Returns the paths traced. */
static uint32_t render_next_window(Wavefront *w, uint32_t max_spp)
{
    uint32_t window = w->stats->window_size, np = w->num_pixels, n;
    if (window >= np && w->next_pixel == 0) {
        uint32_t k = window / np;
        if (k > max_spp - w->next_sample)
            k = max_spp - w->next_sample;
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
    w->stats->spp_done = (int)w->next_sample;
    return n;
}

uint64_t wavefront_advance(Wavefront *w, uint64_t min_paths, int max_spp)
{
    double start = seconds_now();
    uint64_t done = 0;
    while (done < min_paths && (int)w->next_sample < max_spp)
        done += render_next_window(w, (uint32_t)max_spp);
    CL_CHECK(clFinish(w->dev->queue));
    w->stats->seconds += seconds_now() - start;
    return done;
}

int wavefront_spp_done(const Wavefront *w) { return (int)w->next_sample; }
Film *wavefront_film(Wavefront *w) { return &w->film; }
RenderStats *wavefront_stats(Wavefront *w) { return w->stats; }

/* All spp, a pool's worth at a time, with progress; stops early after wavefront_request_stop(). */
static void render_all(Wavefront *w, int spp, bool show_progress)
{
    uint64_t total = (uint64_t)w->num_pixels * (uint64_t)spp, done = 0;
    double start = seconds_now(), last_print = -1.0;
    while ((int)w->next_sample < spp && !g_stop_requested) {
        done += wavefront_advance(w, 1, spp);
        double now = seconds_now() - start;
        if (show_progress && (now - last_print > 0.25 || (int)w->next_sample == spp)) {
            print_progress(w->stats, spp, now, done, total);
            last_print = now;
        }
    }
    if (show_progress)
        fputc('\n', stderr);
}

void wavefront_read_film(Wavefront *w, float *rgb)
{
    film_read(&w->film, rgb);
    uint32_t counters[COUNTER_COUNT];
    device_read(w->dev, w->counters, 0, sizeof counters, counters);
    w->stats->nonfinite = counters[COUNTER_NONFINITE];
}

static void wavefront_release(Wavefront *w)
{
    for (int k = 0; k < STAGE_COUNT; k++)
        if (w->kernels[k])
            CL_CHECK(clReleaseKernel(w->kernels[k]));
    if (w->compactor)
        compactor_destroy(w->compactor);
    if (w->sorter)
        material_sorter_destroy(w->sorter);
    film_release(&w->film);
    cl_mem all[] = {w->params_buf, w->counters, w->active, w->free_slots,
                    w->shadow_queue, w->shadow_count, w->sorted_active,
#define PATH_STATE_LIST(type, name) w->name,
                    PATH_STATE_FIELDS(PATH_STATE_LIST) SAMPLE_STATE_FIELDS(PATH_STATE_LIST)
#undef PATH_STATE_LIST
    };
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (all[i])
            CL_CHECK(clReleaseMemObject(all[i]));
}

Wavefront *wavefront_create(Device *dev, const Scene *scene, const SceneBuffers *buffers,
                            const RenderSettings *settings, Error *err)
{
    Wavefront *w = calloc(1, sizeof *w);
    if (!w)
        die("out of memory");
    if (!wavefront_init(w, dev, scene, buffers, settings, err)) {
        wavefront_release(w);
        free(w);
        return NULL;
    }
    return w;
}

void wavefront_destroy(Wavefront *w)
{
    wavefront_release(w);
    free(w);
}

bool wavefront_render(Device *dev, const Scene *scene, const SceneBuffers *buffers,
                      const RenderSettings *settings, float *rgb, RenderStats *stats, Error *err)
{
    g_stop_requested = 0;
    Wavefront *w = wavefront_create(dev, scene, buffers, settings, err);
    if (!w)
        return false;
    render_all(w, settings->spp, !settings->quiet && isatty(STDERR_FILENO));
    wavefront_read_film(w, rgb);
    *stats = *w->stats;
    wavefront_destroy(w);
    return true;
}
