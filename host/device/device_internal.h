/* SPDX-License-Identifier: MIT */
/* device_internal.h: what the files of host/device/ share: device.c opens a device and asks
 * program.c for its build options; launch.c sizes work-groups with the same default as
 * device_open. Not for use outside host/device/. */
#ifndef PT_DEVICE_INTERNAL_H
#define PT_DEVICE_INTERNAL_H

#include <stdbool.h>

#include "device/device.h"

/* The wavefront kernels' work-group size unless PT_LOCAL_SIZE says otherwise. */
#define DEFAULT_LOCAL_SIZE 64

/* Sets dev->bvh_width, dev->bvh_quantized and dev->build_options for the device device_open
 * found (its type and vendor are known); false with ERR_SETTINGS on a bad PT_BVH_WIDTH,
 * PT_BVH_QUANTIZED or PT_CL_OPTIONS. */
bool device_choose_program_options(Device *dev, Error *err);

#endif
