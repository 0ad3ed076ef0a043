/* SPDX-License-Identifier: MIT */
/* render_units.h: a render through work units (dist/work_units.h): on several devices of this
 * process (--device all or a list: one host thread per device, each taking runs of units from one
 * scheduler as it finishes the last, so a fast device takes more), with checkpoints (--checkpoint,
 * --resume: dist/checkpoint.h), and as one rank of an MPI job (dist/mpi_link.h). Every device
 * renders into its own film; a device's film goes into the host's (dist/unit_film.h) whole
 * units at a time, and the image is that film: the same bits whatever the split. */
#ifndef PT_RENDER_UNITS_H
#define PT_RENDER_UNITS_H

#include <stdbool.h>
#include <stdint.h>

#include "dist/checkpoint.h"
#include "dist/unit_film.h"
#include "render/render_stop.h"
#include "render/session.h"
#include "render/wavefront.h"

/* An MPI job's link between ranks (dist/render_ranks.h). */
typedef struct RankLink RankLink;

/* The devices a unit render uses: the session's own, then the extra ones. */
typedef struct {
    Session *session;
    SessionDevice *extra;
    int num_extra;
} UnitDevices;

/* What the unit render asks of the command that runs it (app/render_cmd_units.c fills them from
 * app/stop_signals.h and app/render_loop.h), so that dist/ needs nothing from app/. Every member
 * may be NULL: no stop requests, no progress, no test points. */
typedef struct {
    /* The signal that asks the render to stop, 0 while none; called from every thread. */
    int (*stop_requested)(void);
    /* The signal's name for a message ("SIGTERM"). */
    const char *(*stop_name)(int signal);
    /* Every progress_interval seconds from the main thread: spp_done of spp, done of total
     * camera paths, elapsed seconds; progress_end once after the last. */
    void (*progress)(void *context, int spp_done, int spp, uint64_t done, uint64_t total,
                     double elapsed);
    void (*progress_end)(void *context);
    void *progress_context;
    double progress_interval;
    /* A moment tests may stop at (PT_TEST_RAISE): "unit" (a run rendered, from a device thread),
     * "checkpoint" (a periodic checkpoint written). */
    void (*test_point)(const char *point);
} UnitRenderHooks;

typedef struct {
    RenderSettings settings;
    UnitGrid grid;
    UnitRenderHooks hooks;
    double time_limit;         /* seconds of rendering; stops at the next whole run; 0 = none */
    double checkpoint_seconds; /* 0: no checkpoints */
    const char *checkpoint_path;
    RenderIdentity identity;   /* render_identity: goes into every checkpoint */
    bool resume;               /* film starts from the checkpoint at checkpoint_path */
    bool report_devices;       /* print the units and Mpaths/s of each device at the end */
    RankLink *ranks;           /* MPI: this rank's link (rank 0 schedules every rank's devices,
                                * the others ask it for runs); NULL: this process alone */
} UnitRenderDesc;

/* Per device, for the report and pt bench. */
typedef struct {
    char spec[16];
    char name[256];
    uint32_t units, runs;
    uint64_t paths;
    double busy_seconds; /* time spent rendering its runs */
} UnitDeviceReport;

typedef struct {
    int num_devices;
    UnitDeviceReport device[DEVICE_LIST_MAX + 1];
    uint32_t units_resumed;   /* units the checkpoint held */
    uint32_t checkpoints;     /* checkpoints written */
    double merge_seconds;     /* reading device films and adding them to the host's */
} UnitRenderReport;

/* Renders the units not yet in film (all, or what a resumed checkpoint lacks) into film, until
 * all are done, hooks.stop_requested, or the time limit; stats as the one-device render's
 * (spp_done: samples every pixel holds). */
bool render_units_run(const UnitDevices *devices, const UnitRenderDesc *desc, UnitFilm *film,
                      RenderStats *stats, RenderStop *stop, UnitRenderReport *report, Error *err);

#endif
