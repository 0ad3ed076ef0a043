/* SPDX-License-Identifier: MIT */
/* megakernel.h: the CPU's way through a window (PATH_KERNEL_MEGAKERNEL in render/wavefront.h): every
 * stage of a path in one kernel, cl/stages/megakernel.cl's trace_paths (one path per work item) or
 * trace_paths_packets (eight, their rays traced as packets); and the same for the last paths of
 * the wavefront's windows on any device (finish_paths, the tail). */
#ifndef PT_MEGAKERNEL_H
#define PT_MEGAKERNEL_H

#include "render/wavefront.h"

/* Chooses the path kernel for w's settings and device (PATH_KERNEL_AUTO: PT_MEGAKERNEL, else the
 * megakernel on CPUs; PT_PACKETS) and, when it is the megakernel, creates trace_paths_packets where
 * the program has it and is asked for, else trace_paths, with its arguments bound in
 * w->kernels[STAGE_TRACE_PATHS]. False with err set on a bad PT_MEGAKERNEL or PT_PACKETS. Call
 * after the path state buffers and the geodesic stage exist. */
bool megakernel_init(Wavefront *w, Error *err);

/* Traces window samples 0 .. window_size - 1 (w->params already on the device) to their ends into
 * the window's radiance, a pool of paths per launch. */
void megakernel_trace_window(Wavefront *w, uint32_t window_size);

/* The wavefront's tail: once a window has no samples left to start, its last live paths, when
 * there are at most settings.tail_paths of them (0: PT_TAIL_PATHS, else TAIL_PATHS_DEFAULT), go
 * to their ends in one launch of finish_paths (cl/stages/megakernel.cl) instead of a step per
 * bounce, each of which costs its launches and a count read-back however few paths it has. Same
 * stage functions, same order: the same bits. tail_init sets w->tail_paths for a wavefront render
 * that can take the kernel (not the megakernel, the ablations or scenes with black holes) and
 * starts building its part on a thread of its own (device_build_in_background: a first build is
 * a compile of seconds that no render needs to wait for; a tail_paths given in the settings
 * builds it now instead). Not earlier, beside the wavefront's own part: NVIDIA's driver builds one
 * program at a time, so that put off the first pixel by the tail's compile (bench/README.md,
 * "The wavefront's tail"). False with err set on a bad PT_TAIL_PATHS. tail_kernel_ready: whether
 * finish_paths is there for this window's tail (taken in and bound once its part is built). */
#define TAIL_PATHS_DEFAULT 65536
bool tail_init(Wavefront *w, Error *err);
bool tail_kernel_ready(Wavefront *w);

#endif
