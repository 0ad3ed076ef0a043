/* SPDX-License-Identifier: MIT */
/* viewer.h: 'pt view', the interactive window: progressive rendering of the scene with camera
 * controls (keys: viewer_input.h). */
#ifndef PT_VIEWER_H
#define PT_VIEWER_H

#include <stdbool.h>

#include "io/tonemap.h"
#include "render/session.h"
#include "render/wavefront.h"

/* What 'pt view' is asked for; zero means default. */
typedef struct {
    RenderDesc render;       /* .spp 0 = sample until closed */
    RenderSettings settings; /* from the command line (app/cli.h cli_render_settings): seed,
                              * --clamp, adaptive sampling, ...; the scene's part settled here */
    float exposure;          /* stops */
    Tonemap tonemap;         /* display curve (io/tonemap.h); 0 is AgX, the default */
    float bloom_strength, bloom_radius; /* --bloom (render/bloom.h): 0 = none; radius 0 = default */
    bool quiet;
    int sort_materials; /* SORT_MATERIALS_* (render/session.h) */
    bool print_events;       /* --events: a stdout line per input event and state change */
    int frames;              /* quit after this many frames; 0 = run until closed */
    const char *screenshot;  /* at exit: FILE.exr the linear film, else a PNG of the framebuffer */
    bool denoise;            /* --denoise: start with the denoised view (Ctrl+D) */
    int denoise_device;      /* DenoiseDevice (render/denoise.h) */
} ViewerDesc;

/* Runs the window until Esc, closing it, or o->frames frames; returns the exit status. Without a
 * display it ends with one line pointing to 'pt render' and status 1. */
int command_view(const ViewerDesc *o);

#endif
