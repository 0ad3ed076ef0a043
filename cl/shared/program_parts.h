/* SPDX-License-Identifier: MIT */
/* shared/program_parts.h: the parts the program is built in. Part of cl/shared.h (read its rules).
 *
 * NVIDIA's compiler builds one program on one thread and inlines the whole shading code into
 * every kernel that shades: shade_surface, the megakernel's two kernels and render_aov each
 * carried a copy, and a first build of a feature-rich scene waited for all four although a GPU
 * render runs only the wavefront's. So pt builds the program in parts (host/device/program.c):
 * each part is the whole source compiled with -DPT_PARTS=<its bit>, whose #if PT_PART(NAME) keeps
 * that part's kernels; the wavefront's part is built first, the others when a kernel of theirs is
 * first asked for. A build with no -DPT_PARTS (the tests' programs with kernels of their own) has
 * every part. The host's list of which kernels live where is PROGRAM_PARTS in
 * host/device/device.h, by these bits; a kernel in several parts is taken from a part already
 * built. */
#ifndef PT_SHARED_PROGRAM_PARTS_H
#define PT_SHARED_PROGRAM_PARTS_H

#define PT_PART_BIT_CORE 1u       /* the wavefront's stages but shading, the device-wide primitives */
#define PT_PART_BIT_MEGAKERNEL 2u /* trace_paths, trace_paths_packets */
#define PT_PART_BIT_AOV 4u        /* render_aov */
#define PT_PART_BIT_ABLATION 8u   /* the brute-force intersection kernels (--brute-force) */
#define PT_PART_BIT_TAIL 16u      /* finish_paths: the last paths of the wavefront's windows */
#define PT_PART_BIT_SPLIT 32u     /* shade_surface_split, intersect_shadow (RenderSettings.split_shadow) */
#define PT_PART_BIT_CONNECT 64u   /* shade_surface, which traces its shadow rays */
#define PT_PARTS_ALL 127u

#ifdef __OPENCL_C_VERSION__
#ifndef PT_PARTS
#define PT_PARTS PT_PARTS_ALL
#endif
/* Whether this build has part NAME's kernels. Kernels outside every #if are in every part: keep
 * only small ones there. */
#define PT_PART(name) ((PT_PARTS & PT_PART_BIT_##name) != 0)
#endif

#endif
