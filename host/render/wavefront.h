/* SPDX-License-Identifier: MIT */
/* wavefront.h: the path tracer. One kernel per stage (cl/<stage>.cl), a pool of path slots sized
 * to the device, parallel-scan compaction of live paths between bounces (host/parallel/compact.h), and
 * slots refilled with new camera paths as paths end, a window of samples at a time. */
#ifndef PT_WAVEFRONT_H
#define PT_WAVEFRONT_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "device/device.h"
#include "scene/scene.h"
#include "render/film.h"
#include "render/pool_size.h"
#include "render/scene_upload.h"

typedef struct {
    int spp, max_depth;  /* required */
    unsigned seed;
    int sampler;         /* SAMPLER_* (cl/shared/render.h); 0: the scene's render.sampler, else
                          * sobol (scene/sampler.h sampler_resolve) */
    uint32_t first_sample; /* the film gets samples first_sample .. first_sample + spp - 1 of each
                            * pixel: films of disjoint blocks add up (film_sums_add) to one render */
    bool no_nee;         /* BSDF sampling only */
    bool no_compaction;  /* every bounce runs over the whole window; dead slots idle, no refill */
    bool profile;        /* time every kernel (waits after each launch) */
    bool brute_force;    /* no BVH: every ray against every triangle (benchmark ablation) */
    bool sort_materials; /* shade the live paths grouped by the material they hit */
    bool split_shadow;   /* intersect_shadow as a stage of its own, reading the shadow rays that
                          * shade_surface stored, instead of shading that traces them itself
                          * (the kernel shade_surface, the default up to CONNECT_MAX_TRIANGLES
                          * traced triangles, wavefront_state.c); PT_CONNECT_IN_SHADING=0|1
                          * overrides that choice.
                          * shadow_flags and brute_force imply it (pt bench's split-shadow row) */
    bool shadow_flags;   /* with split_shadow: intersect_shadow checks a flag per active path
                          * instead of reading the queue that shade_surface appends to with
                          * atomics (1.5 to 6% slower on an H100; pt bench measures both) */
    float clamp_indirect; /* > 0: every contribution of indirect light (reaching the camera over
                           * 2 or more scattering vertices) is scaled so that no channel exceeds
                           * this (--clamp, Cycles' "clamp indirect"; biased, off by default; see
                           * clamp_indirect in cl/stages/shade_surface.cl) */
    float noise_threshold; /* > 0: adaptive sampling (render/adaptive.h); 0 = the scene's
                            * render.noise_threshold (0 there too: off) */
    int min_spp;          /* adaptive sampling: samples every pixel gets before the first
                           * decision; 0 = the scene's render.min_spp, else ADAPTIVE_MIN_SPP */
    bool moments;         /* also sum the samples' squares (the variance AOV; adaptive sampling
                           * turns it on itself) */
    uint32_t pool_size;  /* path slots in flight; 0 = chosen from the device */
    uint32_t window_size; /* samples per window, the unit of progress (and of wavefront_advance's
                           * steps); 0 = the default (render/pool_size.h); at least the pool */
    int path_kernel;      /* PATH_KERNEL_*: the wavefront or one work item per path (megakernel.h) */
    int tail_paths;       /* the wavefront takes a window's last paths to their ends in one launch
                           * (finish_paths, megakernel.h) once no samples are left to start and at
                           * most this many are live; 0: PT_TAIL_PATHS, else TAIL_PATHS_DEFAULT;
                           * < 0: never (every bounce a step of its own) */
} RenderSettings;

/* How the paths of a window are traced: the wavefront (a kernel per stage, compaction, refills)
 * or the megakernel (cl/stages/megakernel.cl, the same stage functions; the film gets the same
 * bits): eight paths per work item with their rays traced as packets (trace_paths_packets) where
 * the program has that kernel (8-wide layout, one BVH level, no cut-outs), else one path per work
 * item (trace_paths); MEGAKERNEL_SINGLE: one path per work item always. AUTO: PT_MEGAKERNEL=0|1 if
 * set, else the megakernel on CPU devices, with packets unless PT_PACKETS=0. Either way the
 * ablations (no_compaction, brute_force) and scenes with black holes use the wavefront;
 * sort_materials applies to the wavefront only. */
enum { PATH_KERNEL_AUTO, PATH_KERNEL_WAVEFRONT, PATH_KERNEL_MEGAKERNEL, PATH_KERNEL_MEGAKERNEL_SINGLE };

/* The frame loop's stages, one line each, in the order of the --profile table:
 * X(ID, kernel, launch, made, variant). STAGE_<ID> indexes the per-stage tables (the kernels,
 * RenderStats' times and launches); `kernel` is the stage's kernel (cl/stages/<kernel>.cl) and its
 * name in stage_names and the profile table.
 *   launch   OVER_ACTIVE: a work item per entry of the active list, its count set before each
 *            launch; OWN_COUNT: a count of its own; HELPER: a module of parallel/ with kernels of
 *            its own, which adds their device time to the stage.
 *   made     INIT: by wavefront_init; HOLES: by black_holes_init, for scenes with black holes only;
 *            MEGAKERNEL: by megakernel_init (trace_paths or trace_paths_packets, megakernel.h);
 *            TAIL: by tail_init or tail_kernel_ready (megakernel.h), the windows' last paths;
 *            HELPER: by the helper.
 *   variant  a second kernel "<kernel>_<variant>" that some settings take instead: BRUTE_FORCE (the
 *            brute-force ablation, no BVH), MOMENTS (the film with its second moments), SPLIT
 *            (shading that stores its shadow rays for intersect_shadow, split_shadow), or NONE.
 *            shade_surface's row of the profile holds the shadow rays' tracing unless split. */
#define STAGES(X)                                                                                  \
    X(GENERATE_CAMERA_RAYS, generate_camera_rays, OWN_COUNT, INIT, NONE)                           \
    X(INTERSECT_CLOSEST, intersect_closest, OVER_ACTIVE, INIT, BRUTE_FORCE)                        \
    X(SORT_MATERIALS, sort_materials, HELPER, HELPER, NONE)                                        \
    X(SHADE_SURFACE, shade_surface, OVER_ACTIVE, INIT, SPLIT)                                      \
    X(INTERSECT_SHADOW, intersect_shadow, OVER_ACTIVE, INIT, BRUTE_FORCE)                          \
    X(COMPACT_PATHS, compact_paths, HELPER, HELPER, NONE)                                          \
    X(ACCUMULATE_FILM, accumulate_film, OWN_COUNT, INIT, MOMENTS)                                  \
    X(INTEGRATE_GEODESIC, integrate_geodesic, OVER_ACTIVE, HOLES, NONE)                            \
    X(TRACE_PATHS, trace_paths, OWN_COUNT, MEGAKERNEL, NONE)                                      \
    X(FINISH_PATHS, finish_paths, OVER_ACTIVE, TAIL, NONE)

#define STAGE_ENUM(id, kernel, launch, made, variant) STAGE_##id,
enum { STAGES(STAGE_ENUM) STAGE_COUNT };
#undef STAGE_ENUM

/* How a render is laid out on its device: set by wavefront_create, kept by wavefront_reset. */
typedef struct {
    uint32_t pool_size;
    uint32_t window_size;
    uint64_t device_bytes; /* path state (with the sorted list when sorting), window and film on
                            * the device; render_stats_add sums it: the devices' memory together */
    bool megakernel;       /* traced by the megakernel (PATH_KERNEL_*) */
    bool packets;          /* ... by trace_paths_packets: eight paths per work item */
} RenderConfig;

#define RENDER_LIVE_STEPS 64 /* steps whose live paths RenderStats counts */

/* What a render counts: X(type, name) a scalar, ARRAY(type, name, length) an array. Zeroed by
 * wavefront_reset, summed over devices and ranks by render_stats_add; a new counter is one line
 * here. */
#define RENDER_COUNTERS(X, ARRAY)                                                                  \
    X(uint64_t, paths)          /* camera paths traced */                                          \
    X(uint64_t, extension_rays) /* closest-hit rays traced (live paths per bounce) */              \
    X(uint64_t, shadow_rays)    /* any-hit rays traced for next-event estimation */                \
    X(uint32_t, nonfinite)      /* samples dropped as NaN/Inf */                                   \
    X(uint32_t, windows)        /* windows rendered */                                             \
    ARRAY(double, stage_ms, STAGE_COUNT) /* device time per stage, with settings.profile */        \
    ARRAY(uint32_t, stage_launches, STAGE_COUNT)                                                   \
    ARRAY(uint64_t, live_per_step, RENDER_LIVE_STEPS) /* entering each step, all windows */

typedef struct {
    RenderConfig config;
    int spp_done;           /* samples per pixel in the film (fewer than asked if interrupted) */
    double seconds;         /* wall time of the sample loop */
    uint32_t active_pixels; /* adaptive sampling: pixels still sampled (all before the first
                             * decision, 0 once every pixel has stopped) */
#define RENDER_COUNTER_MEMBER(type, name) type name;
#define RENDER_COUNTER_ARRAY_MEMBER(type, name, length) type name[length];
    RENDER_COUNTERS(RENDER_COUNTER_MEMBER, RENDER_COUNTER_ARRAY_MEMBER)
#undef RENDER_COUNTER_MEMBER
#undef RENDER_COUNTER_ARRAY_MEMBER
} RenderStats;

/* A block of the film (a run of work units, dist/work_units.h): pixels first_pixel ..
 * + num_pixels - 1 (row-major, row 0 at the top) times samples first_sample .. + num_samples - 1
 * of each. */
typedef struct {
    uint32_t first_pixel, num_pixels, first_sample, num_samples;
} PixelBlock;

typedef struct Wavefront Wavefront;

/* A progressive render: the device state of one film. Samples continue from where the last call
 * stopped; the image is the same whatever the steps (the RNG is keyed on pixel and sample). */
Wavefront *wavefront_create(Device *dev, const Scene *scene, const SceneBuffers *buffers,
                            const RenderSettings *settings, Error *err);
/* Traces windows until at least min_paths camera paths are done or max_spp samples per pixel are
 * complete (lower settings.window_size for short steps); waits for them. */
uint64_t wavefront_advance(Wavefront *w, uint64_t min_paths, int max_spp);
/* Complete samples per pixel in the film so far. With adaptive sampling: the samples that every
 * pixel still sampled has (stopped pixels have fewer), and settings.spp once every pixel has
 * stopped: the render is complete. */
int wavefront_spp_done(const Wavefront *w);
/* Whether the film holds whole samples: every pixel being sampled has the same count (no window
 * has stopped inside a sample's pixels). */
bool wavefront_at_whole_sample(const Wavefront *w);
/* Adds samples b->first_sample .. + num_samples - 1 (counted from settings.first_sample) of pixels
 * b->first_pixel .. + num_pixels - 1 to the film, whole, and waits for them: a run of work units
 * (dist/work_units.h). The film's sample count (wavefront_spp_done) does not follow blocks;
 * not with adaptive sampling. */
void wavefront_render_block(Wavefront *w, const PixelBlock *b);
void wavefront_read_film(Wavefront *w, float *rgb); /* mean per pixel, 0 where none yet */
/* The variance of each pixel's mean per channel (the `variance` AOV: sample variance / n, 0 below
 * 2 samples) into rgb; false (rgb untouched) unless the render keeps moments. */
bool wavefront_read_variance(Wavefront *w, float *rgb);
/* The samples each pixel holds (the film's count word; the `spp` AOV), one float per pixel. */
void wavefront_read_spp(Wavefront *w, float *spp);
Film *wavefront_film(Wavefront *w);                 /* its sums: to merge or resume films */
void wavefront_reset(Wavefront *w);                  /* empty film, sample 0 */
void wavefront_set_camera(Wavefront *w, const Camera *camera); /* and reset */
RenderStats *wavefront_stats(Wavefront *w);
/* Adds the counters of from (another device's, another rank's) to into: every RENDER_COUNTERS
 * entry, and the device bytes. */
void render_stats_add(RenderStats *into, const RenderStats *from);
/* The --profile table: launches, device time and share of each stage (headed `title` where the
 * table says "stage"), then the live paths per step. */
void render_stats_print_profile(FILE *out, const RenderStats *stats, const char *title);
/* Reads the device's counters into the stats (nonfinite: wavefront_read_film does it too). */
void wavefront_read_counters(Wavefront *w);
void wavefront_destroy(Wavefront *w);

/* Renders scene into rgb (width * height * 3 floats, row 0 at the top): the mean of spp samples
 * per pixel, all of them, silently (pt render's own loop, app/render_loop.c, shows progress and
 * stops early on a signal through wavefront_advance). */
bool wavefront_render(Device *dev, const Scene *scene, const SceneBuffers *buffers,
                      const RenderSettings *settings, float *rgb, RenderStats *stats, Error *err);

extern const char *const stage_names[STAGE_COUNT]; /* the kernels of STAGES */

#endif
