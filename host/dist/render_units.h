/* SPDX-License-Identifier: MIT */
/* render_units.h: `pt render` through work units (dist/work_units.h): on several devices of this
 * process (--device all or a list: one host thread per device, each taking runs of units from one
 * scheduler as it finishes the last, so a fast device takes more), with checkpoints (--checkpoint,
 * --resume: dist/checkpoint.h), and as one rank of an MPI job (dist/mpi_link.h). Every device
 * renders into its own film; a device's film goes into the host's (dist/unit_film.h) whole
 * units at a time, and the image is that film: the same bits whatever the split. */
#ifndef PT_RENDER_UNITS_H
#define PT_RENDER_UNITS_H

#include <stdbool.h>
#include <stdint.h>

#include "app/render_loop.h"
#include "dist/checkpoint.h"
#include "render/session.h"
#include "dist/unit_film.h"
#include "render/wavefront.h"

/* An MPI job's link between ranks (dist/render_ranks.h). */
typedef struct RankLink RankLink;

/* The devices a unit render uses: the session's own, then the extra ones. */
typedef struct {
    Session *session;
    SessionDevice *extra;
    int num_extra;
} UnitDevices;

typedef struct {
    RenderSettings settings;
    UnitGrid grid;
    ProgressStyle progress;
    double time_limit;         /* as in RenderLoopDesc; stops at the next whole run */
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
 * all are done, a stop signal, or the time limit; stats as render_loop_run's (spp_done: samples
 * every pixel holds). */
bool render_units_run(const UnitDevices *devices, const UnitRenderDesc *desc, UnitFilm *film,
                      RenderStats *stats, RenderStop *stop, UnitRenderReport *report, Error *err);

#endif
