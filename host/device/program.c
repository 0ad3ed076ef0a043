// SPDX-License-Identifier: MIT
/* program.c: the one program of a device: its build options (with the BVH layout the kernels are
 * compiled for), the source assembled from the embedded cl/ files, the build or the load from the
 * kernel cache (device/kernel_cache.c), the build log of a failure, and its kernels. */
#include "device/device_internal.h"

#include "device/kernel_cache.h"
#include "base/clock.h"
#include "base/env.h"

#include <ctype.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

extern const unsigned char pt_kernel_source[];
extern const size_t pt_kernel_source_length;

/* Room in Device.build_options for PT_CL_OPTIONS next to the options pt always adds. */
#define MAX_CL_OPTIONS_LENGTH 160

/* The program's build options for this device. Conservative maths: no fast-relaxed-math, which
 * would let the compiler drop the Inf/NaN handling that the traversal and the film guard depend
 * on. Correctly rounded division where the device offers it: NVIDIA's default division is off by
 * up to 2 ulp, enough to flip watertight edge tests against the host's (and PoCL's) results and
 * so to make images differ across devices; measured on the H100, it costs no traversal speed.
 * PT_CL_OPTIONS replaces the maths options (for experiments; the vendor switch stays). */
static bool choose_build_options(Device *dev, Error *err)
{
    cl_device_fp_config fp = 0;
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_SINGLE_FP_CONFIG, sizeof fp, &fp, NULL));
    const char *maths = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT)
                            ? "-cl-mad-enable -cl-no-signed-zeros -cl-fp32-correctly-rounded-divide-sqrt"
                            : "-cl-mad-enable -cl-no-signed-zeros";
    if (!env_text("PT_CL_OPTIONS", MAX_CL_OPTIONS_LENGTH, maths, &maths, err))
        return false;
    snprintf(dev->build_options, sizeof dev->build_options, "-cl-std=CL1.2 %s -DBVH_WIDTH=%d%s%s",
             maths, dev->bvh_width, dev->bvh_quantized ? " -DBVH_QUANTIZED=1" : "",
             dev->is_nvidia ? " -DPT_VENDOR_NVIDIA=1" : "");
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

/* The parts: each one's -DPT_PARTS bit and the kernels only it has. */
typedef struct {
    const char *name;
    unsigned bit;
    const char *kernels;
} ProgramPart;

#define PROGRAM_PART_ROW(id, kernel_list) {#id, PT_PART_BIT_##id, kernel_list},
static const ProgramPart program_parts[PROGRAM_PART_COUNT] = {PROGRAM_PARTS(PROGRAM_PART_ROW)};
#undef PROGRAM_PART_ROW

/* The part that has kernel `name`: the one whose list names it, else CORE. */
static int part_of_kernel(const char *name)
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

/* Prints the build log of a failed build and records the error. */
static bool build_failed(Device *dev, cl_program program, const char *options, cl_int status,
                         Error *err)
{
    /* No abort here, whatever fails: a part's build may run on a thread of its own. */
    size_t log_size = 0;
    char *log = NULL;
    if (clGetProgramBuildInfo(program, dev->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &log_size) ==
            CL_SUCCESS &&
        (log = malloc(log_size + 1)) != NULL &&
        clGetProgramBuildInfo(program, dev->device, CL_PROGRAM_BUILD_LOG, log_size, log, NULL) ==
            CL_SUCCESS) {
        log[log_size] = '\0';
        fprintf(stderr, "pt: kernel build log (%s, options %s):\n%s\n", dev->name, options, log);
    }
    free(log);
    clReleaseProgram(program);
    error_set(err, ERR_KERNEL_BUILD, NULL, 0, "kernel build failed on %s (%s): see the log above",
              dev->name, cl_error_name(status));
    return false;
}

/* A program from a cached binary; NULL when the entry is missing or unusable. */
static cl_program build_from_cache(Device *dev, const char *options, uint64_t key)
{
    unsigned char *binary = NULL;
    size_t size = 0;
    if (!kernel_cache_load(key, &binary, &size))
        return NULL;
    cl_int status, binary_status;
    const unsigned char *binaries[1] = {binary};
    cl_program program = clCreateProgramWithBinary(dev->context, 1, &dev->device, &size, binaries,
                                                   &binary_status, &status);
    free(binary);
    if (status != CL_SUCCESS || binary_status != CL_SUCCESS) {
        if (status == CL_SUCCESS)
            clReleaseProgram(program);
        warn("the driver refused the cached kernels (%s): rebuilding",
             cl_error_name(status != CL_SUCCESS ? status : binary_status));
        return NULL;
    }
    if (clBuildProgram(program, 1, &dev->device, options, NULL, NULL) != CL_SUCCESS) {
        warn("the cached kernels do not build on %s: rebuilding", dev->name);
        clReleaseProgram(program);
        return NULL;
    }
    return program;
}

/* Best effort, like every store: a binary the driver will not give is not cached. */
static void store_in_cache(cl_program program, uint64_t key)
{
    size_t size = 0;
    if (clGetProgramInfo(program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, NULL) != CL_SUCCESS ||
        size == 0)
        return;
    unsigned char *binary = malloc(size);
    if (!binary)
        return;
    unsigned char *binaries[1] = {binary};
    if (clGetProgramInfo(program, CL_PROGRAM_BINARIES, sizeof binaries, binaries, NULL) == CL_SUCCESS)
        kernel_cache_store(key, binary, size);
    free(binary);
}

/* Whether the driver keeps each program it builds in a disk cache of its own, so that pt's cache
 * holds only a marker (below) instead of the binary. PoCL does ($POCL_CACHE_DIR, by default
 * $XDG_CACHE_HOME/pocl), and asking PoCL for a binary makes it compile every kernel of the
 * program for a generic work-group size, used or not, before the ones a render launches are
 * compiled again for their real size (bench/README.md, "Kernel builds on PoCL"). PT_CACHE_BINARIES=1
 * (or PoCL's POCL_KERNEL_CACHE=0) stores binaries anyway (the tests use it to keep that path
 * covered on PoCL). */
static bool driver_keeps_programs(const Device *dev, bool *keeps, Error *err)
{
    bool binaries;
    if (!env_flag("PT_CACHE_BINARIES", false, &binaries, err))
        return false;
    /* POCL_KERNEL_CACHE=0 turns PoCL's cache off: then only a binary spares the next compile. */
    const char *pocl_cache = getenv("POCL_KERNEL_CACHE");
    *keeps = !binaries && strstr(dev->platform_name, "Portable Computing Language") != NULL &&
             !(pocl_cache && strcmp(pocl_cache, "0") == 0);
    return true;
}

/* A driver-kept program's entry: this text instead of the binary. It records that the program was
 * built once with the driver's cache at the folder in the key (a cleared driver cache makes the
 * next build a silent compile, never a wrong program: the source is always given). */
static const char driver_marker[] = "pt: the driver keeps this program in its own cache\n";

static bool marker_in_cache(uint64_t key)
{
    unsigned char *data = NULL;
    size_t size = 0;
    if (!kernel_cache_load(key, &data, &size))
        return false;
    bool marker = size == sizeof driver_marker && memcmp(data, driver_marker, size) == 0;
    free(data);
    if (!marker)
        warn("kernel cache entry %016llx is not a driver-kept program's: rebuilding",
             (unsigned long long)key);
    return marker;
}

static bool build_notice = true;

void device_set_build_notice(bool on) { build_notice = on; }

/* Before a compile the kernel cache cannot spare: one line, so that a first run's wait is
 * explained before it starts, not after. The parts built later (a first megakernel, AOV or
 * ablation run) say which they are. */
static void announce_build(const Device *dev, int part)
{
    if (!build_notice)
        return;
    char summary[PROGRAM_FEATURE_SUMMARY_SIZE], which[64] = "";
    program_features_summary(dev->features, summary);
    bool later = false; /* another part came first: say which this one is */
    for (int i = 0; i < PROGRAM_PART_COUNT; i++)
        later = later || dev->programs[i];
    if (later) {
        snprintf(which, sizeof which, " of the %s part", program_parts[part].name);
        for (char *c = which; *c; c++)
            *c = (char)tolower((unsigned char)*c);
    }
    const char *dir = kernel_cache_dir();
    if (dev->use_cache && dir[0])
        fprintf(stderr, "pt: compiling kernels%s for this scene's features (%s) on %s, first time "
                "only (then from the kernel cache, %s) ...\n", which, summary, dev->name, dir);
    else
        fprintf(stderr, "pt: compiling kernels%s for this scene's features (%s) on %s (no kernel "
                "cache) ...\n", which, summary, dev->name);
    fflush(stderr);
}

/* Part `part`'s options (or the whole program's: dev->whole_program) and kernel cache key. */
static bool part_options_and_key(const Device *dev, int part, char *options, size_t size,
                                 bool *driver_keeps, uint64_t *key, Error *err)
{
    if (dev->whole_program)
        snprintf(options, size, "%s", dev->options);
    else
        snprintf(options, size, "%s -DPT_PARTS=%uu", dev->options, program_parts[part].bit);
    if (!driver_keeps_programs(dev, driver_keeps, err))
        return false;
    /* A driver-kept program's marker is only as good as the driver's cache it speaks for. */
    const char *driver_cache = getenv("POCL_CACHE_DIR");
    const char *key_parts[] = {dev->source, options, dev->name, dev->platform_name,
                               dev->driver_version,
                               *driver_keeps ? (driver_cache ? driver_cache : "default") : "binary"};
    *key = kernel_cache_key(key_parts, sizeof key_parts / sizeof key_parts[0]);
    return true;
}

#define PART_OPTIONS_SIZE (sizeof ((Device *)0)->build_options + PROGRAM_FEATURE_OPTIONS_SIZE + 32)

/* Part `part` from the kernel cache or the source into *out, without touching dev (so that a
 * thread of its own can run it: device_build_in_background); *compiled: the cache could not spare
 * the compile, which is announced first when `announce`. */
static bool build_part_program(Device *dev, int part, bool announce, cl_program *out,
                               bool *compiled, Error *err)
{
    char options[PART_OPTIONS_SIZE];
    bool driver_keeps;
    uint64_t key;
    if (!part_options_and_key(dev, part, options, sizeof options, &driver_keeps, &key, err))
        return false;
    cl_program program = NULL;
    bool hit = false;
    if (dev->use_cache && driver_keeps)
        hit = marker_in_cache(key);
    else if (dev->use_cache)
        hit = (program = build_from_cache(dev, options, key)) != NULL;
    *compiled = false;
    if (!program) {
        if (!hit) {
            *compiled = true;
            if (announce)
                announce_build(dev, part);
        }
        cl_int status;
        const char *sources[1] = {dev->source};
        program = clCreateProgramWithSource(dev->context, 1, sources, NULL, &status);
        if (status != CL_SUCCESS) {
            error_set(err, ERR_KERNEL_BUILD, NULL, 0, "clCreateProgramWithSource failed on %s: %s",
                      dev->name, cl_error_name(status));
            return false;
        }
        status = clBuildProgram(program, 1, &dev->device, options, NULL, NULL);
        if (status == CL_BUILD_PROGRAM_FAILURE || status == CL_INVALID_BUILD_OPTIONS)
            return build_failed(dev, program, options, status, err);
        if (status != CL_SUCCESS) {
            clReleaseProgram(program);
            error_set(err, ERR_KERNEL_BUILD, NULL, 0, "clBuildProgram failed on %s: %s", dev->name,
                      cl_error_name(status));
            return false;
        }
        if (dev->use_cache && !hit) {
            if (driver_keeps)
                kernel_cache_store(key, (const unsigned char *)driver_marker, sizeof driver_marker);
            else
                store_in_cache(program, key);
        }
    }
    *out = program;
    return true;
}

/* Builds part `part` (or the whole program: dev->whole_program) from the kernel cache or the
 * source into dev->programs[part], adding its time to dev->build_seconds. */
static bool build_part(Device *dev, int part, Error *err)
{
    double start = seconds_now();
    bool compiled;
    if (!build_part_program(dev, part, true, &dev->programs[part], &compiled, err))
        return false;
    if (compiled)
        dev->cache_hit = false;
    dev->build_seconds += seconds_now() - start;
    return true;
}

/* ---- A part built on a thread of its own ---------------------------------------------------- */

struct BackgroundBuild {
    pthread_t thread;
    Device *dev;
    int part;
    atomic_bool done;
    bool ok, compiled;
    cl_program program;
    double seconds;
    Error err;
};

static void *build_in_background(void *arg)
{
    BackgroundBuild *b = arg;
    double start = seconds_now();
    b->ok = build_part_program(b->dev, b->part, false, &b->program, &b->compiled, &b->err);
    b->seconds = seconds_now() - start;
    atomic_store(&b->done, true);
    return NULL;
}

/* The builds under way, joined at exit: a die() on the render's thread must not run the exit
 * handlers (the driver's among them) while a compile is inside the driver. */
#define MAX_BACKGROUND_BUILDS 64
static pthread_mutex_t background_lock = PTHREAD_MUTEX_INITIALIZER;
static BackgroundBuild *background_builds[MAX_BACKGROUND_BUILDS];

static void join_background_builds_at_exit(void)
{
    pthread_mutex_lock(&background_lock);
    for (int i = 0; i < MAX_BACKGROUND_BUILDS; i++)
        if (background_builds[i])
            pthread_join(background_builds[i]->thread, NULL), background_builds[i] = NULL;
    pthread_mutex_unlock(&background_lock);
}

/* Starts b's thread (with room on its stack for a compiler) and registers it; false when no
 * thread can be had. */
static bool start_background_build(BackgroundBuild *b)
{
    static atomic_bool registered;
    if (!atomic_exchange(&registered, true))
        atexit(join_background_builds_at_exit);
    pthread_mutex_lock(&background_lock);
    int slot = -1;
    for (int i = 0; i < MAX_BACKGROUND_BUILDS && slot < 0; i++)
        if (!background_builds[i])
            slot = i;
    bool started = false;
    pthread_attr_t attr;
    if (slot >= 0 && pthread_attr_init(&attr) == 0) {
        pthread_attr_setstacksize(&attr, 64u << 20);
        started = pthread_create(&b->thread, &attr, build_in_background, b) == 0;
        pthread_attr_destroy(&attr);
    }
    if (started)
        background_builds[slot] = b;
    pthread_mutex_unlock(&background_lock);
    return started;
}

/* Takes in the background build's part once it is done (at once when `wait`): then
 * dev->programs[part] is set; a failed build is a warning (the render goes on without the part,
 * which device_kernel_ready no longer offers; device_kernel builds it again, and fails there). */
static void take_background_build(Device *dev, bool wait)
{
    BackgroundBuild *b = dev->background;
    if (!b || (!wait && !atomic_load(&b->done)))
        return;
    pthread_mutex_lock(&background_lock);
    for (int i = 0; i < MAX_BACKGROUND_BUILDS; i++)
        if (background_builds[i] == b)
            background_builds[i] = NULL;
    pthread_join(b->thread, NULL);
    pthread_mutex_unlock(&background_lock);
    dev->background = NULL;
    if (b->ok) {
        dev->programs[b->part] = b->program;
        dev->build_seconds += b->seconds;
        if (b->compiled)
            dev->cache_hit = false;
    } else {
        dev->parts_failed |= 1u << b->part;
        warn("%s (the %s part, built beside the render: going on without it)", b->err.message,
             program_parts[b->part].name);
    }
    free(b);
}

void device_build_in_background(Device *dev, const char *name)
{
    int part = dev->whole_program ? 0 : part_of_kernel(name);
    if (dev->programs[part] || dev->background || (dev->parts_failed & 1u << part))
        return;
    /* A part the kernel cache has loads in milliseconds: then now, so that the render has it from
     * its first window. */
    char options[PART_OPTIONS_SIZE];
    bool driver_keeps;
    uint64_t key;
    Error err = {0};
    unsigned char *entry = NULL;
    size_t size;
    bool cached = dev->use_cache &&
                  part_options_and_key(dev, part, options, sizeof options, &driver_keeps, &key, &err) &&
                  kernel_cache_load(key, &entry, &size);
    free(entry);
    BackgroundBuild *b = cached ? NULL : calloc(1, sizeof *b);
    if (b) {
        b->dev = dev, b->part = part;
        atomic_init(&b->done, false);
        if (start_background_build(b)) {
            dev->background = b;
            return;
        }
        free(b);
    }
    if (!build_part(dev, part, &err)) /* cached, or no thread could be had */
        die("%s", err.message);
}

cl_kernel device_kernel_ready(Device *dev, const char *name)
{
    take_background_build(dev, false);
    int part = dev->whole_program ? 0 : part_of_kernel(name);
    if (!dev->programs[part] || (dev->parts_failed & 1u << part))
        return NULL;
    return device_kernel(dev, name);
}

void device_finish_background_build(Device *dev)
{
    BackgroundBuild *b = dev->background;
    /* A first render shorter than the build waits for it here, once: say why. */
    if (b && build_notice && !atomic_load(&b->done)) {
        char part[32];
        snprintf(part, sizeof part, "%s", program_parts[b->part].name);
        for (char *c = part; *c; c++)
            *c = (char)tolower((unsigned char)*c);
        fprintf(stderr, "pt: finishing the kernels of the %s part for the next renders (first time "
                "only) ...\n", part);
        fflush(stderr);
    }
    take_background_build(dev, true);
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
    return build_part(dev, megakernel && !dev->whole_program ? PROGRAM_PART_MEGAKERNEL
                                                             : PROGRAM_PART_CORE, err);
}

/* Kernel `name` from the parts already built (a kernel in no part's list may be in several), else
 * from its own part, built first; *status as clCreateKernel's. */
static cl_kernel create_kernel(Device *dev, const char *name, cl_int *status)
{
    int part = dev->whole_program ? 0 : part_of_kernel(name);
    if (dev->background && dev->background->part == part)
        take_background_build(dev, true); /* rather than build it a second time */
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
        if (!build_part(dev, part, &err))
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
