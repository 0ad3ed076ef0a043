/* SPDX-License-Identifier: MIT */
/* viewer_state.h: the state of one 'pt view' window, shared by host/viewer/viewer.c (the frame loop) and
 * host/viewer/actions.c (what single keys do). */
#ifndef PT_VIEWER_STATE_H
#define PT_VIEWER_STATE_H

#include <stdbool.h>
#include <stdint.h>

#include "render/session.h"
#include "viewer/viewer.h"
#include "viewer/denoise_view.h"
#include "viewer/display.h"
#include "viewer/input.h"
#include "viewer/stats.h"
#include "render/wavefront.h"

typedef struct {
    const ViewerDesc *options;
    Session session;         /* session.scene.desc holds the live camera and the film size */
    GLFWwindow *window;
    ViewerInput input;
    ViewerDisplay display;
    Wavefront *wavefront;
    RenderSettings settings;
    char scene_name[256];
    int target_spp;
    float exposure;          /* stops */
    Tonemap tonemap;         /* the display curve (T cycles) */
    bool paused, film_changed;
    float scene_size;        /* bounding-box diagonal: the scale of flying and of the lens */
    double paths_per_second; /* measured; 0 before the first window */
    double recent_paths, recent_seconds; /* decaying sums behind paths_per_second */
    uint64_t last_paths;     /* traced in the last sampling step */
    double last_sampling_seconds; /* that step's time; 0 when the frame traced nothing */
    double display_seconds;  /* decaying mean of a frame's time outside sampling */
    ViewerStats stats;       /* for the summary at exit */
    double title_time, title_frame_ms;
    uint64_t title_paths;
    unsigned film_generation; /* counts the film's restarts: a denoised image is of one */
    bool denoise_on;          /* Ctrl+D (or --denoise) */
    DenoiseView denoise;
    unsigned shown_generation; /* the denoised image in the display's texture: of this film */
    int shown_spp;             /* at this many spp; 0: the texture holds the noisy film */
    char title_denoised[48];   /* the title's denoising part, as last set */
} Viewer;

#endif
