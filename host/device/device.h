/* SPDX-License-Identifier: MIT */
/* device.h: OpenCL platform/device selection (device.c), the one program built from the embedded
 * cl/ sources (program.c), checked buffer allocation and kernel launches (launch.c). The one
 * rendering choice made here is the BVH layout the kernels are compiled for (bvh_width,
 * bvh_quantized: program.c), because it follows the device type and must match -DBVH_WIDTH in the
 * build options; render/ and the tests lay the tree out from those two fields. */
#ifndef PT_DEVICE_H
#define PT_DEVICE_H

#include <stdbool.h>
#include <stdio.h>

#include "device/cl_check.h"
#include "base/error.h"
#include "base/shared_types.h"

/* The parts the program is built in (cl/shared/program_parts.h says why): X(NAME, the register
 * cap of its kernels on NVIDIA (-cl-nv-maxrregcount; 0: the compiler's choice), the kernels that
 * only part NAME has, space-separated). A kernel of no list is in CORE and maybe in other parts
 * too: device_kernel takes it from a part already built before building CORE for it. The caps
 * trade registers for occupancy where an H100 measured it faster on the benchmark scenes
 * (bench/README.md, "Texture code per scene, the tight walk and register caps"). */
#define PROGRAM_PARTS(X)                                                                           \
    X(CORE, 40, "")                                                                                \
    X(MEGAKERNEL, 0, "trace_paths trace_paths_packets")                                            \
    X(AOV, 0, "render_aov")                                                                        \
    X(ABLATION, 0, "intersect_closest_brute_force intersect_shadow_brute_force")                  \
    X(TAIL, 0, "finish_paths")                                                                     \
    X(SPLIT, 0, "shade_surface_split intersect_shadow")                                            \
    X(CONNECT, 64, "shade_surface")
typedef struct BackgroundBuild BackgroundBuild;
#define PROGRAM_PART_ENUM(name, nv_registers, kernels) PROGRAM_PART_##name,
enum { PROGRAM_PARTS(PROGRAM_PART_ENUM) PROGRAM_PART_COUNT };
#undef PROGRAM_PART_ENUM

typedef struct {
    cl_platform_id platform;
    cl_device_id device;
    cl_context context;
    cl_command_queue queue; /* in order, with profiling enabled */
    /* The program's parts (PROGRAM_PARTS), each built when first needed; a program built whole
     * (tests' programs with kernels of their own, PT_PROGRAM_PARTS=0) is programs[0] alone. */
    cl_program programs[PROGRAM_PART_COUNT];
    bool whole_program;
    char *source;    /* the program's text, kept for the parts built later */
    char *options;   /* its options (features included), likewise */
    bool announced;  /* the first-time build was announced (one line a device) */
    cl_device_type type;
    cl_ulong max_alloc;  /* CL_DEVICE_MAX_MEM_ALLOC_SIZE */
    cl_ulong global_mem; /* CL_DEVICE_GLOBAL_MEM_SIZE */
    size_t max_work_group;
    cl_uint compute_units;
    bool is_nvidia;
    int bvh_width;       /* BVH layout the kernels walk (bvh_wide.h): 2 on GPUs, 8 on CPUs, or
                          * PT_BVH_WIDTH */
    bool bvh_quantized;  /* 2-wide: 32-byte nodes (bvh_quantized.h); PT_BVH_QUANTIZED=0/1 */
    size_t local_size;   /* work-group size of launches that name none: 64, or PT_LOCAL_SIZE */
    char build_options[512]; /* see device_build_options (the features come with device_build) */
    int platform_index, device_index;
    char name[256];
    char platform_name[256];
    char driver_version[128];
    double build_seconds; /* time to get the program's parts built so far: compile, or load from
                           * the kernel cache */
    bool use_cache;       /* set before device_build; device_open sets it unless PT_NO_CACHE=1 */
    bool cache_hit;       /* every part built so far came from the kernel cache */
    ProgramFeatures features; /* what the program was built for (device_build) */
    struct BackgroundBuild *background; /* a part building on a thread of its own
                                         * (device_build_in_background), else NULL */
    unsigned parts_failed; /* 1 << part for each part whose background build failed */
} Device;

/* Prints every platform and device (name, type, compute units, memory, max allocation, OpenCL C
 * version). Returns false with ERR_NO_PLATFORM when there is none. */
bool device_list(FILE *out, Error *err);

/* Opens a device. spec: NULL or "" (first GPU, else first CPU), "gpu", "cpu", or "P:D" (platform
 * and device index as `pt devices` prints them). ERR_DEVICE_UNKNOWN names the spec. */
bool device_open(Device *dev, const char *spec, Error *err);

/* Several devices in one render: `all` (every GPU of every platform, or every CPU device where
 * there is no GPU: mixing GPUs and CPUs is asked for by naming them) or a list "P:D,P:D" (each
 * entry anything device_open takes). Each is resolved to "P:D"; a device named twice is an error. */
#define DEVICE_LIST_MAX 16
typedef struct {
    int count;
    char spec[DEVICE_LIST_MAX][16];
} DeviceSpecList;
bool device_spec_is_list(const char *spec); /* "all" or a list with a comma */
bool device_spec_list(const char *spec, DeviceSpecList *list, Error *err);

/* Builds the program from the embedded cl/ sources followed by extra_source (may be NULL; tests add
 * their kernels this way), specialised for `features` (a set of FEATURE_* bits, cl/shared/features.h;
 * PROGRAM_FEATURES_ALL keeps every feature): the kernel cache keys on them with the options. Without
 * extra_source only the CORE part is built now, the others by device_kernel when a kernel of
 * theirs is first asked for. On failure prints the full build log and returns ERR_KERNEL_BUILD. */
/* Whether device_build announces a compile the kernel cache does not spare, on stderr (default
 * on; pt --quiet turns it off). */
void device_set_build_notice(bool on);
bool device_build(Device *dev, ProgramFeatures features, const char *extra_source,
                  const char *extra_name, Error *err);

/* The device's build options, in one place: logged with every build (followed by the features'). */
const char *device_build_options(const Device *dev);

/* The options that specialise a program for `features` (program_features.c): -DPT_FEATURES_GIVEN
 * and -DPT_FEATURE_<NAME>=0/1 for every feature of the list, each after a space. */
#define PT_FEATURE_OPTION_LENGTH(name, word) +sizeof(" -DPT_FEATURE_" #name "=0") - 1
#define PROGRAM_FEATURE_OPTIONS_SIZE                                                               \
    (sizeof(" -DPT_FEATURES_GIVEN") PROGRAM_FEATURES(PT_FEATURE_OPTION_LENGTH))
void program_features_options(ProgramFeatures features, char out[PROGRAM_FEATURE_OPTIONS_SIZE]);

/* The set in words for people: "all", "none" or its features' words, comma-separated
 * ("env, mix, instances"). */
#define PT_FEATURE_WORD_LENGTH(name, word) +sizeof(word) + 1
#define PROGRAM_FEATURE_SUMMARY_SIZE (sizeof("none") PROGRAM_FEATURES(PT_FEATURE_WORD_LENGTH))
void program_features_summary(ProgramFeatures features, char out[PROGRAM_FEATURE_SUMMARY_SIZE]);

/* The kernel called name, building its part first if it is not yet built (a failed build of a
 * part prints its log and ends the process, as a kernel that is not there does). */
cl_kernel device_kernel(Device *dev, const char *name);
/* The kernel, or NULL where the program's options compiled it out (#if around the kernel). */
cl_kernel device_kernel_if_built(Device *dev, const char *name);
/* For a kernel a render can do without until it is there: builds its part on a thread of its own
 * (one at a time; at once when the kernel cache has it, or no thread can be had), so that the
 * render goes on meanwhile. device_kernel_ready gives the kernel once its part is built, NULL
 * before, without waiting; device_kernel, device_finish_background_build and device_close wait for
 * it (the last two with a line on stderr, under the build notice, when it is still compiling: a
 * first render shorter than the compile waits for it once, so that the next renders have it), and
 * so does the process's exit. A failed background build is a warning when it is taken in, and
 * device_kernel_ready offers that part no more. */
void device_build_in_background(Device *dev, const char *name);
cl_kernel device_kernel_ready(Device *dev, const char *name);
void device_finish_background_build(Device *dev);

/* Allocates a buffer named for error messages; a size above CL_DEVICE_MAX_MEM_ALLOC_SIZE is
 * ERR_ALLOC_TOO_LARGE naming the buffer, its size and the limit. host may be NULL. A zero size
 * allocates a small dummy buffer so kernels always get a valid argument. */
cl_mem device_buffer(Device *dev, const char *name, cl_mem_flags flags, size_t size,
                     const void *host, Error *err);

/* Host memory the device can copy into at full speed (page-locked where the driver does that:
 * NVIDIA reads a film into it several times faster than into malloc'd memory): a buffer of
 * CL_MEM_ALLOC_HOST_PTR mapped once for good. NULL with err set when it cannot be had. */
void *device_pinned_alloc(Device *dev, const char *name, size_t size, cl_mem *buffer, Error *err);
void device_pinned_free(Device *dev, cl_mem buffer, void *p);

/* Blocking transfers. */
void device_read(Device *dev, cl_mem buf, size_t offset, size_t size, void *dst);
void device_write(Device *dev, cl_mem buf, size_t offset, size_t size, const void *src);

/* Fills size bytes of buf from offset with copies of pattern (pattern_size bytes: 1, 2, 4, ...,
 * 128; offset and size multiples of it), enqueued without waiting, like a launch. profile_ms as
 * device_run's. */
void device_fill(Device *dev, cl_mem buf, const void *pattern, size_t pattern_size, size_t offset,
                 size_t size, double *profile_ms);
/* Waits for everything enqueued on the device's queue. */
void device_finish(Device *dev);

/* Releases what device_buffer, device_kernel or device_kernel_if_built returned. */
void device_release_buffer(cl_mem buf);
void device_release_kernel(cl_kernel kernel);
/* CL_KERNEL_WORK_GROUP_SIZE: the largest work-group the kernel allows on the device (registers,
 * local memory). */
size_t device_kernel_work_group_size(const Device *dev, cl_kernel kernel);

/* Sets one kernel argument from an lvalue: KERNEL_ARG(k, 0, buffer); */
#define KERNEL_ARG(kernel, index, value) \
    CL_CHECK(clSetKernelArg((kernel), (index), sizeof(value), &(value)))

/* One kernel argument: KARG(lvalue) takes its size and address. */
typedef struct {
    size_t size;
    const void *value;
} KernelArg;
#define KARG(value) ((KernelArg){sizeof(value), &(value)})
/* A local-memory argument of `bytes`. */
#define KARG_LOCAL(bytes) ((KernelArg){(bytes), NULL})

/* Sets arguments first .. first + n - 1 from args[] in order; returns first + n, the index of the
 * next argument. KERNEL_ARGS(k, first, KARG(a), KARG(b), ...) counts them itself, so no call site
 * numbers arguments by hand. */
cl_uint kernel_set_args(cl_kernel kernel, cl_uint first, size_t n, const KernelArg *args);
#define KERNEL_ARGS(kernel, first, ...)                                                            \
    kernel_set_args((kernel), (first), sizeof((KernelArg[]){__VA_ARGS__}) / sizeof(KernelArg),     \
                    (KernelArg[]){__VA_ARGS__})

/* Device time of an enqueued command in ms (from profiling events: the queue has them on); waits
 * for it and releases the event. */
double device_event_ms(cl_event event);

/* Launches a 1-D kernel over n items (global size rounded up to the work-group size `local`, or
 * to 64 when local is 0; kernels check their id against n). Returns the kernel's time in ms
 * when profile_ms is not NULL (waits for it). */
void device_run(Device *dev, cl_kernel kernel, size_t n, size_t local, double *profile_ms);

void device_close(Device *dev);

/* CL_DEVICE_LOCAL_MEM_SIZE: the local memory a work-group may use, in bytes. */
cl_ulong device_local_mem_bytes(const Device *dev);

#endif
