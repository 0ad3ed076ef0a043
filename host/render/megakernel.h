/* SPDX-License-Identifier: MIT */
/* megakernel.h: the CPU's way through a window (PATH_KERNEL_MEGAKERNEL in render/wavefront.h): every
 * stage of a path in one kernel, cl/stages/megakernel.cl's trace_paths (one path per work item) or
 * trace_paths_packets (eight, their rays traced as packets). */
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

#endif
