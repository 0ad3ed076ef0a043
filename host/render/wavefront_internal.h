/* SPDX-License-Identifier: MIT */
/* wavefront_internal.h: the device state of one render, shared by the frame loop
 * (render/wavefront.c) and its setup and teardown (render/wavefront_state.c). */
#ifndef PT_WAVEFRONT_INTERNAL_H
#define PT_WAVEFRONT_INTERNAL_H

#include "parallel/compact.h"
#include "parallel/material_sort.h"
#include "render/adaptive.h"
#include "render/film.h"
#include "render/megakernel.h"
#include "render/wavefront.h"

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
    PIXEL_STATE_FIELDS(PATH_STATE_MEMBER)
#undef PATH_STATE_MEMBER
    cl_kernel kernels[STAGE_COUNT];
    cl_uint n_active_arg[STAGE_COUNT]; /* index of the n_active argument of the traced stages */
    cl_uint generate_counts_arg;       /* index of generate_camera_rays' n_live */
    Compactor *compactor;
    /* Black holes (scene/black_holes.h): the holes and integrate_geodesic's step counts
     * (GEODESIC_STAT_*); NULL without holes, and kernels[STAGE_INTEGRATE_GEODESIC] too. */
    cl_mem black_holes, geodesic_stats;
    cl_uint num_black_holes;
    cl_float4 scene_box[2]; /* the scene's world box (lo, hi) with a margin */
    uint32_t num_pixels;
    uint32_t next_sample, next_pixel; /* where the next window starts (next_sample counts the
                                       * film's samples: its index is first_sample + next_sample) */
    uint32_t block_first_sample;      /* wavefront_render_block: the block's first sample, added
                                       * to next_sample's; 0 otherwise */
    RenderStats own_stats;
    Adaptive adaptive; /* adaptive sampling (render/adaptive.h); adaptive.on false: off */
    cl_uint megakernel_counts_arg; /* index of trace_paths' first_sample (render/megakernel.c) */
    uint32_t megakernel_paths;     /* paths per work item: 1, or PACKET_RAYS for
                                    * trace_paths_packets */
    uint32_t tail_paths;           /* finish_paths takes a window's last paths once at most this
                                    * many are live (tail_init); 0: never */
};

/* Binds params, [the scene's buffers] and the path state to k's first arguments, in the order of
 * cl/stages/path_state.cl; returns the index of the kernel's own first argument. */
cl_uint wavefront_set_path_args(Wavefront *w, cl_kernel k, bool with_scene);
/* Binds finish_paths' arguments (kernels[STAGE_FINISH_PATHS]): the path state, the active list,
 * n_active (set again before each launch) and the counters. */
void wavefront_bind_tail(Wavefront *w);

#endif
