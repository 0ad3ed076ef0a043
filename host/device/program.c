// SPDX-License-Identifier: MIT
/* program.c: the one program of a device: its build options (with the BVH layout the kernels are
 * compiled for), the source assembled from the embedded cl/ files, its parts, and its kernels. A
 * part's build is program_build.c's; a part built on a thread of its own program_background.c's. */
#include "device/device_internal.h"

#include "base/env.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const unsigned char pt_kernel_source[];
extern const size_t pt_kernel_source_length;

/* Room in Device.build_options for PT_CL_OPTIONS next to the options pt always adds. */
#define MAX_CL_OPTIONS_LENGTH 160

#define CORRECTLY_ROUNDED_OPTION "-cl-fp32-correctly-rounded-divide-sqrt"

/* The maths options. Conservative maths: no fast-relaxed-math, which
 * would let the compiler drop the Inf/NaN handling that the traversal and the film guard depend
 * on. Correctly rounded division and square root where the device offers them, but on NVIDIA
 * only with PT_EXACT_MATHS=1: its default ones (within 2.5 ulp) made the H100 3.8-12% faster,
 * mostly in shading and in the instances' ray set-up (bench/README.md, "Maths options"), and
 * move no image's mean (the same paths, a few diverging where a rounding flips a decision). They
 * round differently from the host's and PoCL's, so a hit on an edge may go to the other triangle:
 * the tests, which compare GPU hits with the host's, ask for exact maths (tests/support.c).
 * PT_CL_OPTIONS replaces the maths options (for experiments; the vendor switch stays). */
const char *device_maths_options(bool correctly_rounded, bool nvidia, bool exact)
{
    return correctly_rounded && (exact || !nvidia)
               ? "-cl-mad-enable -cl-no-signed-zeros " CORRECTLY_ROUNDED_OPTION
               : "-cl-mad-enable -cl-no-signed-zeros";
}

/* The program's build options for this device: the maths options (PT_CL_OPTIONS replaces them),
 * the BVH layout, the vendor, and whether division is exact. */
static bool choose_build_options(Device *dev, Error *err)
{
    cl_device_fp_config fp = 0;
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp, &fp, NULL));
    bool correctly_rounded = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0, exact;
    if (!env_flag("PT_EXACT_MATHS", false, &exact, err))
        return false;
    const char *maths = device_maths_options(correctly_rounded, dev->is_nvidia, exact);
    if (!env_text("PT_CL_OPTIONS", MAX_CL_OPTIONS_LENGTH, maths, &maths, err))
        return false;
    /* Without correctly rounded division the box test widens its margin (box_test.cl). */
    bool inexact = !correctly_rounded || !strstr(maths, CORRECTLY_ROUNDED_OPTION);
    snprintf(dev->build_options, sizeof dev->build_options,
             "-cl-std=CL1.2 %s -DBVH_WIDTH=%d%s%s%s", maths, dev->bvh_width,
             dev->bvh_quantized ? " -DBVH_QUANTIZED=1" : "",
             dev->is_nvidia ? " -DPT_VENDOR_NVIDIA=1" : "",
             inexact ? " -DPT_INEXACT_DIVIDE=1" : "");
    return true;
}

/* The BVH layout (bvh_wide.h). A GPU runs each work item as one SIMD lane, so the 2-wide tree
 * with one box per lane is its natural layout; a CPU runs a work item on a whole core, whose
 * SIMD units only work when one item tests many boxes at once (8 lanes of AVX). The 2-wide nodes
 * are 64-byte floats by default; PT_BVH_QUANTIZED=1 halves them (bvh_quantized.h), which
 * measured 9-10% slower on the H100 (bench/README.md) but halves the nodes' memory. */
static bool choose_bvh_width(Device *dev, Error *err)
{
    long width;
    if (!env_int("PT_BVH_WIDTH", 2, 8, (dev->type & CL_DEVICE_TYPE_CPU) ? 8 : 2, &width, err))
        return false;
    if (width != 2 && width != 4 && width != 8) {
        error_set(err, ERR_SETTINGS, NULL, 0,
                  "environment variable PT_BVH_WIDTH=%ld: the BVH layouts are 2, 4 and 8 wide",
                  width);
        return false;
    }
    dev->bvh_width = (int)width;
    if (!env_flag("PT_BVH_QUANTIZED", false, &dev->bvh_quantized, err))
        return false;
    if (dev->bvh_quantized && dev->bvh_width != 2) {
        error_set(err, ERR_SETTINGS, NULL, 0,
                  "environment variable PT_BVH_QUANTIZED=1: quantised nodes are a 2-wide layout, "
                  "and this device walks the %d-wide one (PT_BVH_WIDTH=2 selects it)",
                  dev->bvh_width);
        return false;
    }
    return true;
}

bool device_choose_program_options(Device *dev, Error *err)
{
    return choose_bvh_width(dev, err) && choose_build_options(dev, err);
}

const char *device_build_options(const Device *dev) { return dev->build_options; }

#define PROGRAM_PART_ROW(id, nv_registers, kernel_list) \
    {#id, PT_PART_BIT_##id, nv_registers, kernel_list},
const ProgramPart program_parts[PROGRAM_PART_COUNT] = {PROGRAM_PARTS(PROGRAM_PART_ROW)};
#undef PROGRAM_PART_ROW

int program_part_of_kernel(const char *name)
{
    size_t n = strlen(name);
    for (int i = 0; i < PROGRAM_PART_COUNT; i++)
        for (const char *k = program_parts[i].kernels; *k;) {
            size_t len = strcspn(k, " ");
            if (len == n && strncmp(k, name, n) == 0)
                return i;
            k += len;
            k += strspn(k, " ");
        }
    return PROGRAM_PART_CORE;
}

bool device_build(Device *dev, ProgramFeatures features, const char *extra_source,
                  const char *extra_name, Error *err)
{
    /* The features are the program's specialisation: part of its options, so of the cache key. */
    size_t used = strlen(device_build_options(dev));
    dev->options = malloc(used + PROGRAM_FEATURE_OPTIONS_SIZE);
    dev->source = malloc(pt_kernel_source_length + (extra_source ? strlen(extra_source) : 0) + 600);
    if (!dev->options || !dev->source)
        die("out of memory");
    memcpy(dev->options, device_build_options(dev), used);
    program_features_options(features, dev->options + used);
    dev->features = features;
    memcpy(dev->source, pt_kernel_source, pt_kernel_source_length + 1);
    if (extra_source)
        sprintf(dev->source + pt_kernel_source_length, "\n#line 1 \"%.500s\"\n%s",
                extra_name ? extra_name : "extra", extra_source);
    /* A program with kernels of its own is built whole: its kernels are in no part's list. */
    bool parts = true;
    if (!env_flag("PT_PROGRAM_PARTS", true, &parts, err))
        return false;
    dev->whole_program = extra_source != NULL || !parts;
    dev->build_seconds = 0.0;
    dev->cache_hit = true;
    /* Now: the part of the device's own way to render (a CPU's megakernel, a GPU's wavefront, and
     * the wavefront for bent rays everywhere: render/megakernel.c), so that the time reported
     * with the scene is the wait for it. */
    bool megakernel = (dev->type & CL_DEVICE_TYPE_CPU) && !(features & FEATURE_BLACK_HOLES);
    return program_build_part(dev, megakernel && !dev->whole_program ? PROGRAM_PART_MEGAKERNEL
                                                             : PROGRAM_PART_CORE, err);
}

/* Kernel `name` from the parts already built (a kernel in no part's list may be in several), else
 * from its own part, built first; *status as clCreateKernel's. */
static cl_kernel create_kernel(Device *dev, const char *name, cl_int *status)
{
    int part = dev->whole_program ? 0 : program_part_of_kernel(name);
    program_wait_for_background_part(dev, part); /* rather than build it a second time */
    if (!dev->whole_program && part == PROGRAM_PART_CORE)
        for (int i = 0; i < PROGRAM_PART_COUNT; i++) {
            if (!dev->programs[i])
                continue;
            cl_kernel kernel = clCreateKernel(dev->programs[i], name, status);
            if (*status != CL_INVALID_KERNEL_NAME)
                return kernel;
        }
    if (!dev->programs[part]) {
        Error err = {0};
        if (!program_build_part(dev, part, &err))
            die("%s", err.message);
    }
    return clCreateKernel(dev->programs[part], name, status);
}

cl_kernel device_kernel_if_built(Device *dev, const char *name)
{
    cl_int status;
    cl_kernel kernel = create_kernel(dev, name, &status);
    if (status == CL_INVALID_KERNEL_NAME)
        return NULL;
    if (status != CL_SUCCESS)
        cl_fail(status, "clCreateKernel", __FILE__, __LINE__);
    return kernel;
}

cl_kernel device_kernel(Device *dev, const char *name)
{
    cl_int status;
    cl_kernel kernel = create_kernel(dev, name, &status);
    if (status != CL_SUCCESS) {
        fprintf(stderr, "pt: kernel '%s' not found\n", name);
        cl_fail(status, "clCreateKernel", __FILE__, __LINE__);
    }
    return kernel;
}
