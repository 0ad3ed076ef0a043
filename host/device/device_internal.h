/* SPDX-License-Identifier: MIT */
/* device_internal.h: what the files of host/device/ share: device.c opens a device and asks
 * program.c for its build options; launch.c sizes work-groups with the same default as
 * device_open; program.c, program_build.c and program_background.c share the program's parts.
 * Not for use outside host/device/. */
#ifndef PT_DEVICE_INTERNAL_H
#define PT_DEVICE_INTERNAL_H

#include <stdbool.h>

#include "device/device.h"

/* The wavefront kernels' work-group size unless PT_LOCAL_SIZE says otherwise. */
#define DEFAULT_LOCAL_SIZE 64

/* Sets dev->bvh_width, dev->bvh_quantized and dev->build_options for the device device_open
 * found (its type and vendor are known); false with ERR_SETTINGS on a bad PT_BVH_WIDTH,
 * PT_BVH_QUANTIZED, PT_EXACT_MATHS or PT_CL_OPTIONS. */
bool device_choose_program_options(Device *dev, Error *err);
/* The maths build options of a device that offers correctly rounded division and square root or
 * not, from NVIDIA or not, with PT_EXACT_MATHS or not (program.c says why they differ). */
const char *device_maths_options(bool correctly_rounded, bool nvidia, bool exact);

/* ---- The program's parts (program.c), their builds (program_build.c) and the builds on a thread
 * of their own (program_background.c) ---- */

/* The parts: each one's -DPT_PARTS bit, register cap on NVIDIA and the kernels only it has
 * (PROGRAM_PARTS). */
typedef struct {
    const char *name;
    unsigned bit;
    unsigned nv_registers;
    const char *kernels;
} ProgramPart;
extern const ProgramPart program_parts[PROGRAM_PART_COUNT];
/* The part that has kernel `name`: the one whose list names it, else CORE. */
int program_part_of_kernel(const char *name);
/* A part's name in lower case ("tail"), for the lines that name it. */
#define PROGRAM_PART_WORD_SIZE 32
void program_part_word(int part, char out[PROGRAM_PART_WORD_SIZE]);

/* Part `part` from the kernel cache or the source into *out, without touching dev (so that a
 * thread of its own can run it: device_build_in_background); *compiled: the cache could not spare
 * the compile, which is announced first when `announce`. Errors are returned, never an abort. */
bool program_build_part_program(const Device *dev, int part, bool announce, cl_program *out,
                                bool *compiled, Error *err);
/* Builds part `part` (or the whole program: dev->whole_program) into dev->programs[part], adding
 * its time to dev->build_seconds. */
bool program_build_part(Device *dev, int part, Error *err);
/* Whether the kernel cache has part `part`'s entry (a load is then milliseconds). */
bool program_part_cached(const Device *dev, int part);
/* Whether compiles are announced (device_set_build_notice). */
bool program_build_notice(void);
/* Waits for and takes in a build of part `part` under way on its own thread, if any. */
void program_wait_for_background_part(Device *dev, int part);

#endif
