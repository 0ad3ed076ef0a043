// SPDX-License-Identifier: MIT
/* wavefront_state.c: what a render holds on the device: the path pool and window sized to the
 * device, the stage kernels with their arguments bound once, the compactor and material sorter;
 * and their release. The frame loop that drives them is render/wavefront.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/env.h"
#include "render/megakernel.h"
#include "render/pool_size.h"
#include "render/wavefront_internal.h"
#include "scene/sampler.h"

#define STAGE_NAME(id, kernel, launch, made, variant) #kernel,
const char *const stage_names[STAGE_COUNT] = {STAGES(STAGE_NAME)};
#undef STAGE_NAME

/* The columns of STAGES that setting up the kernels reads (wavefront.h says what they mean). */
enum { STAGE_OVER_ACTIVE, STAGE_OWN_COUNT, STAGE_HELPER };
enum { STAGE_MADE_INIT, STAGE_MADE_HOLES, STAGE_MADE_MEGAKERNEL, STAGE_MADE_TAIL, STAGE_MADE_HELPER };
enum { STAGE_VARIANT_NONE, STAGE_VARIANT_BRUTE_FORCE, STAGE_VARIANT_MOMENTS, STAGE_VARIANT_SPLIT };
#define STAGE_VARIANT_KERNEL_NONE(kernel) NULL
#define STAGE_VARIANT_KERNEL_BRUTE_FORCE(kernel) #kernel "_brute_force"
#define STAGE_VARIANT_KERNEL_MOMENTS(kernel) #kernel "_moments"
#define STAGE_VARIANT_KERNEL_SPLIT(kernel) #kernel "_split"
static const struct {
    int launch, made, variant;
    const char *variant_kernel;
} stage_kinds[STAGE_COUNT] = {
#define STAGE_KIND(id, kernel, launch, made, variant)                                              \
    {STAGE_##launch, STAGE_MADE_##made, STAGE_VARIANT_##variant,                                   \
     STAGE_VARIANT_KERNEL_##variant(kernel)},
    STAGES(STAGE_KIND)
#undef STAGE_KIND
};

static void set_all_args(Wavefront *w);

/* The holes' buffer, the step counts and the integrate_geodesic kernel, for scenes with holes
 * (the program has the kernel exactly then: PT_FEATURE(BLACK_HOLES), render/session.c). */
static bool black_holes_init(Wavefront *w, const SceneDesc *desc, const SceneData *data, Error *err)
{
    if (desc->num_black_holes == 0)
        return true;
    w->num_black_holes = (cl_uint)desc->num_black_holes;
    /* The world box that chords are tested against before the BVH, with a margin for rounding. */
    for (int a = 0; a < 3; a++) {
        float lo = data->bounds_min[a], hi = data->bounds_max[a];
        float margin = 1e-3f * (hi - lo) + 1e-4f * fmaxf(fabsf(lo), fabsf(hi)) + 1e-6f;
        w->scene_box[0].s[a] = lo - margin;
        w->scene_box[1].s[a] = hi + margin;
    }
    w->black_holes = device_buffer(w->dev, "black_holes", CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                   desc->num_black_holes * sizeof(BlackHole), desc->black_holes, err);
    w->geodesic_stats = device_buffer(w->dev, "geodesic_stats", CL_MEM_READ_WRITE,
                                      GEODESIC_STAT_WORDS * sizeof(uint32_t), NULL, err);
    if (error_is_set(err))
        return false;
    w->kernels[STAGE_INTEGRATE_GEODESIC] = device_kernel(w->dev, "integrate_geodesic");
    return true;
}

static cl_mem state_buffer(Wavefront *w, const char *name, size_t size, Error *err)
{
    if (error_is_set(err))
        return NULL;
    return device_buffer(w->dev, name, CL_MEM_READ_WRITE, size, NULL, err);
}

/* Shading traces its own shadow rays (the kernel shade_surface) in scenes of at most this many
 * traced triangles, and leaves them to intersect_shadow in larger ones: the fused kernel holds
 * shading's registers through the walk, which costs more as walks grow longer, while what it
 * saves (the shadow lanes' stores and loads, a launch, the queue) is the same per ray. On an H100
 * it won from 36 triangles (+10%) to 25k (+3.5%) and lost at 50k (-9%) and 114k (-5%)
 * (bench/README.md "Shading that traces its shadow rays"). */
#define CONNECT_MAX_TRIANGLES (1u << 15)

/* The kernel of a stage: the brute-force ablation (every ray against every triangle) has
 * intersection kernels of its own, so that the production ones carry no branch for it; so has the
 * film with its second moments, so that the plain accumulation stays as it was, and shading that
 * leaves its shadow rays to intersect_shadow (the variant column of STAGES). NULL: the stage does
 * not run (intersect_shadow unless split_shadow: shading traces the shadow rays). */
static const char *stage_kernel(int stage, const RenderSettings *s)
{
    int variant = stage_kinds[stage].variant;
    if (stage == STAGE_INTERSECT_SHADOW && !s->split_shadow)
        return NULL;
    if ((variant == STAGE_VARIANT_BRUTE_FORCE && s->brute_force) ||
        (variant == STAGE_VARIANT_MOMENTS && s->moments) ||
        (variant == STAGE_VARIANT_SPLIT && s->split_shadow))
        return stage_kinds[stage].variant_kernel;
    return stage_names[stage];
}

static bool wavefront_init(Wavefront *w, Device *dev, const Scene *scene,
                           const SceneBuffers *buffers, const RenderSettings *asked, Error *err)
{
    memset(w, 0, sizeof *w);
    RenderStats *stats = &w->own_stats;
    w->dev = dev, w->scene = buffers, w->settings = *asked, w->stats = stats;
    const RenderSettings *s = &w->settings;
    if (!(s->clamp_indirect >= 0.0f && isfinite(s->clamp_indirect))) {
        error_set_setting(err, "clamp_indirect", "%g: must be a finite number > 0",
                          s->clamp_indirect);
        return false;
    }
    bool connects =
        !s->split_shadow && scene_traced_triangles(&scene->data) <= CONNECT_MAX_TRIANGLES;
    if (!adaptive_configure(w, scene, &w->settings, err) ||
        !env_flag("PT_CONNECT_IN_SHADING", connects, &connects, err))
        return false;
    /* The ablations measure the split stages (brute force: connect_path's walk is the BVH's). */
    w->settings.split_shadow = !connects || s->shadow_flags || s->brute_force;
    const SceneDesc *desc = &scene->desc;
    w->num_pixels = (uint32_t)desc->width * (uint32_t)desc->height;
    bool gpu = (dev->type & CL_DEVICE_TYPE_GPU) != 0;
    long window_pools, pool_given = s->pool_size;
    if (!env_int("PT_WINDOW_POOLS", 1, 4096, 0, &window_pools, err) ||
        (!pool_given && !env_int("PT_POOL_SIZE", 1024, 1L << 28, 0, &pool_given, err)))
        return false;
    /* Sorting's keys, whether or not the megakernel (decided below) leaves it out. */
    uint32_t sort_keys = s->sort_materials ? scene->data.num_materials + 1u : 0u;
    PoolChoice chosen = pool_choose(
        (PoolDevice){dev->global_mem, dev->max_alloc, gpu},
        (PoolRequest){(uint64_t)pool_given, s->window_size, (uint32_t)window_pools,
                      s->no_compaction, (uint64_t)w->num_pixels * (uint64_t)s->spp, sort_keys});
    uint32_t pool = chosen.pool, window = chosen.window;
    stats->config.pool_size = pool;
    stats->config.window_size = window;
    stats->config.device_bytes =
        pool_device_bytes(pool, window, 0) + (uint64_t)w->num_pixels * FILM_BYTES_PER_PIXEL;

    w->params = render_params_for_scene(desc, buffers);
    w->params.seed = s->seed;
    w->params.max_depth = (uint)s->max_depth;
    w->params.flags = (s->no_nee ? RENDER_NO_NEE : 0u) |
                      (s->split_shadow && !s->shadow_flags ? RENDER_SHADOW_QUEUE : 0u) |
                      (s->clamp_indirect > 0.0f ? RENDER_CLAMP_INDIRECT : 0u) |
                      (sampler_resolve(s->sampler, desc->sampler) == SAMPLER_SOBOL ? RENDER_SOBOL : 0u) |
                      (desc->num_black_holes > 0 ? RENDER_BLACK_HOLES : 0u);
    w->params.window_pixels = w->num_pixels;
    w->params.clamp_indirect = s->clamp_indirect;
    w->params_buf = state_buffer(w, "params", sizeof w->params, err);
    if (error_is_set(err) || !film_init(&w->film, dev, w->num_pixels, err) || !adaptive_init(w, err))
        return false;
    w->counters = state_buffer(w, "counters", COUNTER_COUNT * sizeof(uint32_t), err);
    w->active = state_buffer(w, "active_paths", pool * sizeof(uint32_t), err);
    w->free_slots = state_buffer(w, "free_slots", pool * sizeof(uint32_t), err);
    bool queue = s->split_shadow && !s->shadow_flags; /* RENDER_SHADOW_QUEUE */
    w->shadow_queue = state_buffer(w, "shadow_queue", (queue ? pool : 1) * sizeof(uint32_t), err);
    w->shadow_count = state_buffer(w, "shadow_count", sizeof(uint32_t), err);
#define PATH_STATE_ALLOC(type, name) w->name = state_buffer(w, #name, pool * sizeof(type), err);
    PATH_STATE_FIELDS(PATH_STATE_ALLOC)
#undef PATH_STATE_ALLOC
#define SAMPLE_STATE_ALLOC(type, name) w->name = state_buffer(w, #name, window * sizeof(type), err);
    SAMPLE_STATE_FIELDS(SAMPLE_STATE_ALLOC)
#undef SAMPLE_STATE_ALLOC
    if (error_is_set(err))
        return false;
    /* Every slot starts free: compaction reads the flags of the whole pool. And no slot waits for
     * a shadow ray (render.h shadow_contribution_pack: only queuing writes that lane). */
    uint32_t zero = 0;
    cl_float4 none = {{0.0f, 0.0f, 0.0f, 0.0f}};
    device_fill(dev, w->path_depth, &zero, sizeof zero, 0, pool * sizeof(uint32_t), NULL);
    device_fill(dev, w->shadow_contribution, &none, sizeof none, 0, pool * sizeof none, NULL);
    w->compactor = compactor_create(dev, pool, err);
    if (!w->compactor)
        return false;
    /* --profile: the compaction's own kernels' device time, like every other stage (a wall clock
     * around it also counted the blocking count read). */
    if (s->profile)
        compactor_set_profile(w->compactor, &stats->stage_ms[STAGE_COMPACT_PATHS]);
    if (!black_holes_init(w, &scene->desc, &scene->data, err) || !megakernel_init(w, err))
        return false;
    /* The megakernel replaces every stage but the film's: their kernels are not asked for, so
     * their part of the program is never built (device_kernel builds parts on demand). */
    for (int k = 0; k < STAGE_COUNT; k++)
        if (stage_kinds[k].made == STAGE_MADE_INIT && stage_kernel(k, s) &&
            (!w->kernels[STAGE_TRACE_PATHS] || k == STAGE_ACCUMULATE_FILM))
            w->kernels[k] = device_kernel(dev, stage_kernel(k, s));
    if (!tail_init(w, err))
        return false;
    /* Material sorting orders the wavefront's shading launches: the megakernel has none. */
    if (s->sort_materials && !stats->config.megakernel) {
        w->sorted_active = state_buffer(w, "sorted_active_paths", pool * sizeof(uint32_t), err);
        w->sorter = w->sorted_active ? material_sorter_create(dev, pool, scene->data.num_materials, err) : NULL;
        if (!w->sorter)
            return false;
        stats->config.device_bytes += pool_sort_bytes(pool, sort_keys);
    }
    set_all_args(w);
    wavefront_reset(w);
    return true;
}

void wavefront_reset(Wavefront *w)
{
    uint32_t zero = 0;
    film_clear(&w->film);
    device_fill(w->dev, w->counters, &zero, sizeof zero, 0, COUNTER_COUNT * sizeof(uint32_t), NULL);
    if (w->geodesic_stats)
        device_fill(w->dev, w->geodesic_stats, &zero, sizeof zero, 0,
                    GEODESIC_STAT_WORDS * sizeof(uint32_t), NULL);
    *w->stats = (RenderStats){.config = w->stats->config};
    w->next_sample = w->next_pixel = 0;
    adaptive_reset(w);
}

void wavefront_set_camera(Wavefront *w, const Camera *camera)
{
    w->params.camera = *camera;
    wavefront_reset(w);
}

/* Arguments in the order of cl/stages/path_state.cl: params, [scene buffers], path state, then
 * the stage's own. Returns the index of the first of the stage's own arguments. */
cl_uint wavefront_set_path_args(Wavefront *w, cl_kernel k, bool with_scene)
{
    cl_uint i = KERNEL_ARGS(k, 0, KARG(w->params_buf));
    if (with_scene)
        i = scene_buffers_set_args(w->scene, k, i);
#define PATH_STATE_ARG(type, name) KARG(w->name),
    KernelArg state[] = {PATH_STATE_FIELDS(PATH_STATE_ARG) SAMPLE_STATE_FIELDS(PATH_STATE_ARG)
                             PIXEL_STATE_FIELDS(PATH_STATE_ARG)};
#undef PATH_STATE_ARG
    return kernel_set_args(k, i, sizeof state / sizeof state[0], state);
}

/* Binds every argument once; the counts that change per launch (n_active, generate's counts) are
 * set again before each launch at the indices recorded here. Every OVER_ACTIVE stage takes the
 * path arguments with the scene, then its list and n_active, then its own: own[stage] is the index
 * of the first of its own. */
static void set_all_args(Wavefront *w)
{
    cl_uint zero = 0, i, own[STAGE_COUNT] = {0};
    for (int st = 0; st < STAGE_COUNT; st++) {
        if (stage_kinds[st].launch != STAGE_OVER_ACTIVE || !w->kernels[st] ||
            st == STAGE_FINISH_PATHS) /* wavefront_bind_tail */
            continue;
        /* shade_surface walks the list sorted by material when sorting */
        cl_mem list = st == STAGE_SHADE_SURFACE && w->sorted_active ? w->sorted_active : w->active;
        i = wavefront_set_path_args(w, w->kernels[st], true);
        w->n_active_arg[st] = i + 1;
        own[st] = KERNEL_ARGS(w->kernels[st], i, KARG(list), KARG(zero));
    }
    cl_kernel generate = w->kernels[STAGE_GENERATE_CAMERA_RAYS];
    if (generate) { /* the wavefront's stages (the megakernel has none of them) */
        i = wavefront_set_path_args(w, generate, false);
        w->generate_counts_arg = KERNEL_ARGS(generate, i, KARG(w->active), KARG(w->free_slots));
        KERNEL_ARGS(w->kernels[STAGE_INTERSECT_CLOSEST], own[STAGE_INTERSECT_CLOSEST],
                    KARG(w->counters));
        if (w->settings.split_shadow) {
            KERNEL_ARGS(w->kernels[STAGE_SHADE_SURFACE], own[STAGE_SHADE_SURFACE],
                        KARG(w->shadow_queue), KARG(w->shadow_count));
            KERNEL_ARGS(w->kernels[STAGE_INTERSECT_SHADOW], own[STAGE_INTERSECT_SHADOW],
                        KARG(w->counters), KARG(w->shadow_queue), KARG(w->shadow_count));
        } else { /* shade_surface counts the shadow rays it traces */
            KERNEL_ARG(w->kernels[STAGE_SHADE_SURFACE], own[STAGE_SHADE_SURFACE], w->counters);
        }
    }
    if (w->kernels[STAGE_FINISH_PATHS])
        wavefront_bind_tail(w);
    cl_kernel geodesic = w->kernels[STAGE_INTEGRATE_GEODESIC];
    if (geodesic)
        KERNEL_ARGS(geodesic, own[STAGE_INTEGRATE_GEODESIC], KARG(w->black_holes),
                    KARG(w->num_black_holes), KARG(w->scene_box[0]), KARG(w->scene_box[1]),
                    KARG(w->geodesic_stats));

    cl_kernel accumulate = w->kernels[STAGE_ACCUMULATE_FILM];
    i = wavefront_set_path_args(w, accumulate, false);
    i = KERNEL_ARGS(accumulate, i, KARG(w->film.sums), KARG(w->counters));
    if (w->settings.moments)
        KERNEL_ARG(accumulate, i, w->film.moments);
}

void wavefront_bind_tail(Wavefront *w)
{
    cl_kernel k = w->kernels[STAGE_FINISH_PATHS];
    cl_uint zero = 0, i = wavefront_set_path_args(w, k, true);
    w->n_active_arg[STAGE_FINISH_PATHS] = i + 1;
    KERNEL_ARGS(k, i, KARG(w->active), KARG(zero), KARG(w->counters));
}

int wavefront_spp_done(const Wavefront *w)
{
    return w->adaptive.done ? (int)w->adaptive.spp : (int)w->next_sample;
}
Film *wavefront_film(Wavefront *w) { return &w->film; }
RenderStats *wavefront_stats(Wavefront *w) { return w->stats; }

void render_stats_add(RenderStats *into, const RenderStats *from)
{
#define ADD_COUNTER(type, name) into->name += from->name;
#define ADD_COUNTER_ARRAY(type, name, length)                                                      \
    for (int i = 0; i < (length); i++)                                                             \
        into->name[i] += from->name[i];
    RENDER_COUNTERS(ADD_COUNTER, ADD_COUNTER_ARRAY)
#undef ADD_COUNTER
#undef ADD_COUNTER_ARRAY
    into->config.device_bytes += from->config.device_bytes;
}

void render_stats_print_profile(FILE *out, const RenderStats *stats, const char *title)
{
    double total = 0.0;
    for (int k = 0; k < STAGE_COUNT; k++)
        total += stats->stage_ms[k];
    /* Only what ran: a stage never launched (the megakernel's, a black hole's) and a live-path
     * count the run did not record (the megakernel keeps none) would be empty rows. */
    fprintf(out, "%-22s %9s %11s %7s\n", title, "launches", "total ms", "share");
    for (int k = 0; k < STAGE_COUNT; k++)
        if (stats->stage_launches[k] > 0)
            fprintf(out, "%-22s %9u %11.2f %6.1f%%\n", stage_names[k], stats->stage_launches[k],
                    stats->stage_ms[k], total > 0 ? 100.0 * stats->stage_ms[k] / total : 0.0);
    if (stats->live_per_step[0] == 0)
        return;
    fprintf(out, "live paths per step (all windows):");
    for (int b = 0; b < RENDER_LIVE_STEPS && stats->live_per_step[b]; b++)
        fprintf(out, " %llu", (unsigned long long)stats->live_per_step[b]);
    fputc('\n', out);
}

void wavefront_read_counters(Wavefront *w)
{
    uint32_t counters[COUNTER_COUNT];
    device_read(w->dev, w->counters, 0, sizeof counters, counters);
    w->stats->nonfinite = counters[COUNTER_NONFINITE];
}

void wavefront_read_film(Wavefront *w, float *rgb)
{
    film_read(&w->film, rgb);
    wavefront_read_counters(w);
}

bool wavefront_read_variance(Wavefront *w, float *rgb)
{
    if (!w->settings.moments)
        return false;
    adaptive_compute_variance(w);
    cl_float4 *variance = malloc(w->num_pixels * sizeof *variance);
    if (!variance)
        die("out of memory reading the variance");
    device_read(w->dev, w->adaptive.variance, 0, w->num_pixels * sizeof *variance, variance);
    for (uint32_t i = 0; i < w->num_pixels; i++)
        for (int c = 0; c < 3; c++)
            rgb[3 * i + c] = variance[i].s[c];
    free(variance);
    return true;
}

void wavefront_read_spp(Wavefront *w, float *spp)
{
    uint64_t *sums = malloc((size_t)w->num_pixels * FILM_BYTES_PER_PIXEL);
    if (!sums)
        die("out of memory reading the film");
    film_read_sums(&w->film, sums);
    for (uint32_t i = 0; i < w->num_pixels; i++)
        spp[i] = (float)sums[FILM_WORDS * i + 3];
    free(sums);
}

static void wavefront_release(Wavefront *w)
{
    adaptive_release(w);
    for (int k = 0; k < STAGE_COUNT; k++)
        if (w->kernels[k])
            device_release_kernel(w->kernels[k]);
    if (w->compactor)
        compactor_destroy(w->compactor);
    if (w->sorter)
        material_sorter_destroy(w->sorter);
    film_release(&w->film);
    cl_mem all[] = {w->params_buf, w->counters, w->active, w->free_slots,
                    w->shadow_queue, w->shadow_count, w->sorted_active, w->black_holes, w->geodesic_stats,
#define PATH_STATE_LIST(type, name) w->name,
                    PATH_STATE_FIELDS(PATH_STATE_LIST) SAMPLE_STATE_FIELDS(PATH_STATE_LIST)
#undef PATH_STATE_LIST
    };
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        if (all[i])
            device_release_buffer(all[i]);
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

