// SPDX-License-Identifier: MIT
/* program_build.c: one part of a device's program (program.c) built: from the kernel cache (a
 * binary, or the marker of a program the driver keeps in a cache of its own, PoCL's) or from the
 * source, with a line before a compile the cache cannot spare and the full log of a failure. */
#include "device/device_internal.h"

#include "device/kernel_cache.h"
#include "base/clock.h"
#include "base/env.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Prints the build log of a failed build and records the error. */
static bool build_failed(const Device *dev, cl_program program, const char *options, cl_int status,
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
static cl_program build_from_cache(const Device *dev, const char *options, uint64_t key)
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
bool program_build_notice(void) { return build_notice; }

void program_part_word(int part, char out[PROGRAM_PART_WORD_SIZE])
{
    snprintf(out, PROGRAM_PART_WORD_SIZE, "%s", program_parts[part].name);
    for (char *c = out; *c; c++)
        *c = (char)tolower((unsigned char)*c);
}

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
        char word[PROGRAM_PART_WORD_SIZE];
        program_part_word(part, word);
        snprintf(which, sizeof which, " of the %s part", word);
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
    unsigned cap = dev->is_nvidia && !dev->whole_program ? program_parts[part].nv_registers : 0u;
    if (dev->whole_program)
        snprintf(options, size, "%s", dev->options);
    else if (cap)
        snprintf(options, size, "%s -DPT_PARTS=%uu -cl-nv-maxrregcount=%u", dev->options,
                 program_parts[part].bit, cap);
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

#define PART_OPTIONS_SIZE (sizeof ((Device *)0)->build_options + PROGRAM_FEATURE_OPTIONS_SIZE + 64)

bool program_build_part_program(const Device *dev, int part, bool announce, cl_program *out,
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

bool program_build_part(Device *dev, int part, Error *err)
{
    double start = seconds_now();
    bool compiled;
    if (!program_build_part_program(dev, part, true, &dev->programs[part], &compiled, err))
        return false;
    if (compiled)
        dev->cache_hit = false;
    dev->build_seconds += seconds_now() - start;
    return true;
}

/* A whole load, read again by the build: the price of checking the entry, so that a damaged one
 * is rebuilt on the thread rather than on the render's. */
bool program_part_cached(const Device *dev, int part)
{
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
    return cached;
}
