/* SPDX-License-Identifier: MIT */
/* options.h: what the command line asks for, one struct (zero = default): filled by cli.c from the
 * option table (cli_options.c), read by the commands. Its own header so that the table and the
 * parser both use it without including each other. */
#ifndef PT_OPTIONS_H
#define PT_OPTIONS_H

#include <stdbool.h>

#include "io/tonemap.h"

typedef enum { CMD_NONE, CMD_HELP, CMD_VERSION, CMD_RENDER, CMD_VIEW, CMD_DEVICES, CMD_BENCH, CMD_TONEMAP } Command;

typedef struct {
    Command command;
    const char *scene;  /* SCENE argument */
    const char *device; /* --device, NULL = default */
    const char *output; /* -o, NULL = out/<scene name>.{exr,png}, never overwriting */
    unsigned aov_mask;  /* --aov LIST: AOV_MASK bits (render/aov_layers.h), EXR layers beside the
                         * beauty; 0 = none */
    int spp, max_depth, width, height; /* 0 = from the scene */
    unsigned seed;
    int sampler;    /* --sampler: SAMPLER_* (scene/sampler.h); 0 = the scene's */
    bool seed_given;
    float exposure; /* stops, PNG and the viewer */
    Tonemap tonemap;      /* --tonemap, PNG and the viewer; TONEMAP_DEFAULT unless asked */
    float bloom_strength; /* --bloom STRENGTH[,RADIUS]: 0 = no bloom */
    float bloom_radius;   /* pixels; 0 = the default radius (render/bloom.h) */
    float clamp_max;      /* --clamp MAX: per-sample clamp of indirect radiance; 0 = off */
    float noise_threshold; /* --noise-threshold T: adaptive sampling; 0 = the scene's setting */
    int min_spp;          /* --min-spp N: samples every pixel gets first; 0 = the scene's */
    double time_limit;    /* --time-limit SECONDS: stop at the next whole sample; 0 = none */
    double checkpoint_seconds; /* --checkpoint S: save the film every S seconds; 0 = never */
    bool resume;          /* --resume: continue from the checkpoint beside the output */
    int unit_spp, unit_rows; /* --unit-spp, --unit-rows: work unit size; 0 = the default */
    bool quiet;
    bool progress;  /* progress as lines on stderr, even when it is not a terminal */
    bool preview;   /* with -o X.exr, also write X.png */
    bool no_nee, no_compaction, profile;
    int sort_materials; /* SORT_MATERIALS_* (render/session.h); AUTO unless asked */
    bool no_cache;   /* compile the kernels even if the kernel cache has them */
    bool no_default_light; /* a scene without any light stays dark */
    bool no_ground;  /* --no-ground: the default rig without its ground */
    bool frame;      /* --frame: ignore the file's camera, frame the model */
    int up_axis;     /* --up: UpAxis (scene/camera.h), UP_AXIS_Y unless asked */
    int instancing;  /* --instancing: InstancingMode (scene/scene.h), AUTO unless asked */
    const char *csv; /* pt bench: append results to this CSV file */
    int frames;              /* pt view: quit after this many frames; 0 = run until closed */
    const char *screenshot;  /* pt view: at exit, the film (FILE.exr) or the framebuffer (PNG) */
    bool print_events;       /* pt view --events: stdout lines for scripts to wait on */
    bool denoise;            /* --denoise: OIDN (render/denoise.h); the scene's render.denoise too */
    int denoise_device;      /* --denoise-device: DenoiseDevice, AUTO unless asked */
    const char *camera_json; /* --camera: the scene's camera replaced (render) or the start pose
                              * (view), a JSON object with the keys of the scene's camera */
} Options;

#endif
