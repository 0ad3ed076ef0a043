/* SPDX-License-Identifier: MIT */
/* wavefront.h: the path tracer. One kernel per stage (cl/<stage>.cl), a path pool sized to the
 * device, parallel-scan compaction of live paths between bounces (host/compact.h). */
#ifndef PT_WAVEFRONT_H
#define PT_WAVEFRONT_H

#include <stdbool.h>
#include <stdint.h>

#include "device.h"
#include "scene.h"
#include "scene_gpu.h"

typedef struct {
    int spp, max_depth;  /* required */
    unsigned seed;
    bool no_nee;         /* BSDF sampling only */
    bool no_compaction;  /* every bounce runs over the whole batch; dead slots idle */
    bool quiet;          /* no progress line */
    bool profile;        /* time every kernel (waits after each launch) */
    uint32_t pool_size;  /* paths in flight; 0 = chosen from the device */
} RenderSettings;

enum { STAGE_GENERATE, STAGE_EXTEND, STAGE_SHADE, STAGE_CONNECT, STAGE_COMPACT, STAGE_ACCUMULATE, STAGE_COUNT };

typedef struct {
    int spp_done;              /* samples per pixel in the film (fewer than asked if interrupted) */
    double seconds;            /* wall time of the sample loop */
    uint64_t paths;            /* camera paths traced */
    uint64_t extension_rays;   /* closest-hit rays traced (live paths per bounce) */
    uint64_t shadow_rays;      /* any-hit rays traced for next-event estimation */
    uint32_t nonfinite;        /* samples dropped as NaN/Inf */
    uint32_t pool_size;
    uint32_t batches;
    double stage_ms[STAGE_COUNT];   /* with settings.profile */
    uint32_t stage_launches[STAGE_COUNT];
    uint64_t live_per_bounce[64];   /* live paths entering each bounce, summed over batches */
} RenderStats;

/* Renders scene into rgb (width * height * 3 floats, row 0 at the top): the mean of spp samples
 * per pixel. Stops early, keeping what is done, after wavefront_request_stop(). */
bool wavefront_render(Device *dev, const Scene *scene, const SceneBuffers *buffers,
                      const RenderSettings *settings, float *rgb, RenderStats *stats, Error *err);

/* Async-signal-safe: asks a running render to stop after the current batch (Ctrl-C). */
void wavefront_request_stop(void);

extern const char *const stage_names[STAGE_COUNT];

#endif
