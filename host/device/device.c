// SPDX-License-Identifier: MIT
#include "device/device.h"

#include "device/kernel_cache.h"
#include "base/env.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

extern const unsigned char pt_kernel_source[];
extern const size_t pt_kernel_source_length;

#define MAX_PLATFORMS 16
#define MAX_DEVICES 32
/* Room in Device.build_options for PT_CL_OPTIONS next to the options pt always adds. */
#define MAX_CL_OPTIONS_LENGTH 160
/* The wavefront kernels' work-group size unless PT_LOCAL_SIZE says otherwise. */
#define DEFAULT_LOCAL_SIZE 64

static const char no_platform_help[] =
    "no OpenCL platform found. The ICD loader finds drivers through the files in "
    "/etc/OpenCL/vendors (or the folder named by OCL_ICD_VENDORS). For the CPU, install "
    "pocl-opencl-icd; for an NVIDIA GPU, register its driver: mkdir -p /tmp/icd && echo "
    "libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && export OCL_ICD_VENDORS=/tmp/icd";

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static cl_uint get_platforms(cl_platform_id *platforms)
{
    kernel_cache_prepare(); /* before PoCL reads its cache folder */
    cl_uint count = 0;
    cl_int status = clGetPlatformIDs(MAX_PLATFORMS, platforms, &count);
    /* The ICD loader reports "no platform" as CL_PLATFORM_NOT_FOUND_KHR (-1001): not a bug. */
    if (status != CL_SUCCESS)
        return 0;
    return count;
}

static cl_uint get_devices(cl_platform_id platform, cl_device_id *devices)
{
    cl_uint count = 0;
    cl_int status = clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, MAX_DEVICES, devices, &count);
    if (status == CL_DEVICE_NOT_FOUND)
        return 0;
    CL_CHECK_ERR(status, "clGetDeviceIDs(CL_DEVICE_TYPE_ALL)");
    return count;
}

static void device_string(cl_device_id device, cl_device_info what, char *out, size_t size)
{
    CL_CHECK(clGetDeviceInfo(device, what, size, out, NULL));
}

static const char *type_name(cl_device_type type)
{
    if (type & CL_DEVICE_TYPE_GPU)
        return "GPU";
    if (type & CL_DEVICE_TYPE_CPU)
        return "CPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR)
        return "accelerator";
    return "other";
}

bool device_list(FILE *out, Error *err)
{
    cl_platform_id platforms[MAX_PLATFORMS];
    cl_uint num_platforms = get_platforms(platforms);
    if (num_platforms == 0) {
        error_set(err, ERR_NO_PLATFORM, NULL, 0, "%s", no_platform_help);
        return false;
    }
    bool any_gpu = false;
    for (cl_uint p = 0; p < num_platforms; p++) {
        char pname[256], pversion[256];
        CL_CHECK(clGetPlatformInfo(platforms[p], CL_PLATFORM_NAME, sizeof pname, pname, NULL));
        CL_CHECK(clGetPlatformInfo(platforms[p], CL_PLATFORM_VERSION, sizeof pversion, pversion,
                                   NULL));
        fprintf(out, "platform %u: %s (%s)\n", p, pname, pversion);
        cl_device_id devices[MAX_DEVICES];
        cl_uint num_devices = get_devices(platforms[p], devices);
        for (cl_uint d = 0; d < num_devices; d++) {
            char name[256], clc[128], driver[128];
            cl_device_type type;
            cl_uint units;
            cl_ulong mem, alloc;
            device_string(devices[d], CL_DEVICE_NAME, name, sizeof name);
            device_string(devices[d], CL_DEVICE_OPENCL_C_VERSION, clc, sizeof clc);
            device_string(devices[d], CL_DRIVER_VERSION, driver, sizeof driver);
            CL_CHECK(clGetDeviceInfo(devices[d], CL_DEVICE_TYPE, sizeof type, &type, NULL));
            CL_CHECK(clGetDeviceInfo(devices[d], CL_DEVICE_MAX_COMPUTE_UNITS, sizeof units, &units,
                                     NULL));
            CL_CHECK(clGetDeviceInfo(devices[d], CL_DEVICE_GLOBAL_MEM_SIZE, sizeof mem, &mem, NULL));
            CL_CHECK(clGetDeviceInfo(devices[d], CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof alloc, &alloc,
                                     NULL));
            any_gpu |= (type & CL_DEVICE_TYPE_GPU) != 0;
            fprintf(out,
                    "  %u:%u  %-40s %-4s %3u compute units, %7.2f GiB global, max allocation "
                    "%.2f GiB, %s, driver %s\n",
                    p, d, name, type_name(type), units, (double)mem / (1 << 30),
                    (double)alloc / (1 << 30), clc, driver);
        }
    }
    if (!any_gpu)
        fprintf(out,
                "no GPU found. For an NVIDIA GPU whose driver is installed but not registered: "
                "mkdir -p /tmp/icd && echo libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp "
                "/etc/OpenCL/vendors/*.icd /tmp/icd/ && export OCL_ICD_VENDORS=/tmp/icd\n");
    return true;
}

/* Finds the device named by spec; returns false when it does not exist. */
static bool find_device(const char *spec, cl_platform_id *platforms, cl_uint num_platforms,
                        int *out_p, int *out_d, cl_device_id *out_device)
{
    if (spec && strchr(spec, ':')) {
        char *end;
        long p = strtol(spec, &end, 10);
        if (end == spec || *end != ':')
            return false;
        const char *dspec = end + 1;
        long d = strtol(dspec, &end, 10);
        if (end == dspec || *end != '\0' || p < 0 || d < 0 || p >= (long)num_platforms)
            return false;
        cl_device_id devices[MAX_DEVICES];
        cl_uint num_devices = get_devices(platforms[p], devices);
        if (d >= (long)num_devices)
            return false;
        *out_p = (int)p, *out_d = (int)d, *out_device = devices[d];
        return true;
    }
    bool want_gpu = !spec || !*spec || strcmp(spec, "gpu") == 0;
    bool want_cpu = !spec || !*spec || strcmp(spec, "cpu") == 0;
    if (!want_gpu && !want_cpu)
        return false;
    /* Default: first GPU of any platform, else the first CPU. */
    cl_device_type order[2] = {CL_DEVICE_TYPE_GPU, CL_DEVICE_TYPE_CPU};
    for (int pass = 0; pass < 2; pass++) {
        if ((pass == 0 && !want_gpu) || (pass == 1 && !want_cpu))
            continue;
        for (cl_uint p = 0; p < num_platforms; p++) {
            cl_device_id devices[MAX_DEVICES];
            cl_uint num_devices = get_devices(platforms[p], devices);
            for (cl_uint d = 0; d < num_devices; d++) {
                cl_device_type type;
                CL_CHECK(clGetDeviceInfo(devices[d], CL_DEVICE_TYPE, sizeof type, &type, NULL));
                if (type & order[pass]) {
                    *out_p = (int)p, *out_d = (int)d, *out_device = devices[d];
                    return true;
                }
            }
        }
    }
    return false;
}

/* "0:0 NAME (CPU), 1:0 NAME (GPU)": every device, for messages about a device that is not there. */
static void describe_devices(cl_platform_id *platforms, cl_uint num_platforms, char *out,
                             size_t size)
{
    size_t used = 0;
    out[0] = '\0';
    for (cl_uint p = 0; p < num_platforms; p++) {
        cl_device_id devices[MAX_DEVICES];
        cl_uint num_devices = get_devices(platforms[p], devices);
        for (cl_uint d = 0; d < num_devices && used < size; d++) {
            char name[256];
            cl_device_type type;
            device_string(devices[d], CL_DEVICE_NAME, name, sizeof name);
            CL_CHECK(clGetDeviceInfo(devices[d], CL_DEVICE_TYPE, sizeof type, &type, NULL));
            int n = snprintf(out + used, size - used, "%s%u:%u %s (%s)", used ? ", " : "", p, d,
                             name, type_name(type));
            used += n > 0 ? (size_t)n : 0;
        }
    }
    if (used == 0)
        snprintf(out, size, "none");
}

/* Why find_device found nothing: a kind of device the machine lacks, or a spec that names none. */
static void report_missing_device(const char *spec, cl_platform_id *platforms,
                                  cl_uint num_platforms, Error *err)
{
    char devices[512];
    describe_devices(platforms, num_platforms, devices, sizeof devices);
    bool gpu = spec && !strcmp(spec, "gpu"), cpu = spec && !strcmp(spec, "cpu");
    if (gpu || cpu || !spec || !*spec)
        error_set(err, ERR_DEVICE_UNKNOWN, NULL, 0,
                  "--device %s: there is no %s OpenCL device; the devices are: %s (see 'pt devices')",
                  spec && *spec ? spec : "(default)", gpu ? "GPU" : cpu ? "CPU" : "GPU or CPU",
                  devices);
    else
        error_set(err, ERR_DEVICE_UNKNOWN, NULL, 0,
                  "--device %s: no such device; use gpu, cpu or P:D, one of: %s (see 'pt devices')",
                  spec, devices);
}

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
        error_set(err, ERR_USAGE, NULL, 0,
                  "environment variable PT_BVH_WIDTH=%ld: the BVH layouts are 2, 4 and 8 wide",
                  width);
        return false;
    }
    dev->bvh_width = (int)width;
    if (!env_flag("PT_BVH_QUANTIZED", false, &dev->bvh_quantized, err))
        return false;
    if (dev->bvh_quantized && dev->bvh_width != 2) {
        error_set(err, ERR_USAGE, NULL, 0,
                  "environment variable PT_BVH_QUANTIZED=1: quantised nodes are a 2-wide layout, "
                  "and this device walks the %d-wide one (PT_BVH_WIDTH=2 selects it)",
                  dev->bvh_width);
        return false;
    }
    return true;
}

bool device_open(Device *dev, const char *spec, Error *err)
{
    memset(dev, 0, sizeof *dev);
    cl_platform_id platforms[MAX_PLATFORMS];
    cl_uint num_platforms = get_platforms(platforms);
    if (num_platforms == 0) {
        error_set(err, ERR_NO_PLATFORM, NULL, 0, "%s", no_platform_help);
        return false;
    }
    if (!find_device(spec, platforms, num_platforms, &dev->platform_index, &dev->device_index,
                     &dev->device)) {
        report_missing_device(spec, platforms, num_platforms, err);
        return false;
    }
    dev->platform = platforms[dev->platform_index];
    device_string(dev->device, CL_DEVICE_NAME, dev->name, sizeof dev->name);
    device_string(dev->device, CL_DRIVER_VERSION, dev->driver_version, sizeof dev->driver_version);
    CL_CHECK(clGetPlatformInfo(dev->platform, CL_PLATFORM_NAME, sizeof dev->platform_name,
                               dev->platform_name, NULL));
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_TYPE, sizeof dev->type, &dev->type, NULL));
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof dev->max_alloc,
                             &dev->max_alloc, NULL));
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof dev->global_mem,
                             &dev->global_mem, NULL));
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof dev->max_work_group,
                             &dev->max_work_group, NULL));
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof dev->compute_units,
                             &dev->compute_units, NULL));
    dev->is_nvidia = strstr(dev->platform_name, "NVIDIA") != NULL;
    if (!choose_bvh_width(dev, err) || !choose_build_options(dev, err))
        return false;
    bool no_cache;
    long local_size;
    if (!env_flag("PT_NO_CACHE", false, &no_cache, err) ||
        !env_int("PT_LOCAL_SIZE", 1, (long)dev->max_work_group, DEFAULT_LOCAL_SIZE, &local_size, err))
        return false;
    dev->use_cache = !no_cache;
    dev->local_size = (size_t)local_size;

    cl_int status;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)dev->platform, 0};
    dev->context = clCreateContext(props, 1, &dev->device, NULL, NULL, &status);
    CL_CHECK_ERR(status, "clCreateContext");
    dev->queue = clCreateCommandQueue(dev->context, dev->device, CL_QUEUE_PROFILING_ENABLE, &status);
    CL_CHECK_ERR(status, "clCreateCommandQueue");
    return true;
}

const char *device_build_options(const Device *dev) { return dev->build_options; }


/* Prints the build log of a failed build and records the error. */
static bool build_failed(Device *dev, cl_int status, Error *err)
{
    size_t log_size = 0;
    CL_CHECK(clGetProgramBuildInfo(dev->program, dev->device, CL_PROGRAM_BUILD_LOG, 0, NULL, &log_size));
    char *log = malloc(log_size + 1);
    if (!log)
        die("out of memory");
    CL_CHECK(clGetProgramBuildInfo(dev->program, dev->device, CL_PROGRAM_BUILD_LOG, log_size, log, NULL));
    log[log_size] = '\0';
    fprintf(stderr, "pt: kernel build log (%s, options %s):\n%s\n", dev->name,
            device_build_options(dev), log);
    free(log);
    error_set(err, ERR_KERNEL_BUILD, NULL, 0, "kernel build failed on %s (%s): see the log above",
              dev->name, cl_error_name(status));
    return false;
}

/* A program from a cached binary; false (and nothing kept) when the entry is missing or unusable. */
static bool build_from_cache(Device *dev, uint64_t key)
{
    unsigned char *binary = NULL;
    size_t size = 0;
    if (!kernel_cache_load(key, &binary, &size))
        return false;
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
        return false;
    }
    if (clBuildProgram(program, 1, &dev->device, device_build_options(dev), NULL, NULL) != CL_SUCCESS) {
        warn("the cached kernels do not build on %s: rebuilding", dev->name);
        clReleaseProgram(program);
        return false;
    }
    dev->program = program;
    return true;
}

static void store_in_cache(Device *dev, uint64_t key)
{
    size_t size = 0;
    CL_CHECK(clGetProgramInfo(dev->program, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, NULL));
    if (size == 0)
        return;
    unsigned char *binary = malloc(size);
    if (!binary)
        return;
    unsigned char *binaries[1] = {binary};
    CL_CHECK(clGetProgramInfo(dev->program, CL_PROGRAM_BINARIES, sizeof binaries, binaries, NULL));
    kernel_cache_store(key, binary, size);
    free(binary);
}

bool device_build(Device *dev, const char *extra_source, const char *extra_name, Error *err)
{
    char *source = malloc(pt_kernel_source_length + (extra_source ? strlen(extra_source) : 0) + 600);
    if (!source)
        die("out of memory");
    memcpy(source, pt_kernel_source, pt_kernel_source_length + 1);
    if (extra_source)
        sprintf(source + pt_kernel_source_length, "\n#line 1 \"%.500s\"\n%s",
                extra_name ? extra_name : "extra", extra_source);

    double start = now_seconds();
    const char *key_parts[] = {source, device_build_options(dev), dev->name, dev->platform_name,
                               dev->driver_version};
    uint64_t key = kernel_cache_key(key_parts, sizeof key_parts / sizeof key_parts[0]);
    dev->cache_hit = dev->use_cache && build_from_cache(dev, key);
    if (!dev->cache_hit) {
        cl_int status;
        const char *sources[1] = {source};
        dev->program = clCreateProgramWithSource(dev->context, 1, sources, NULL, &status);
        CL_CHECK_ERR(status, "clCreateProgramWithSource");
        status = clBuildProgram(dev->program, 1, &dev->device, device_build_options(dev), NULL, NULL);
        if (status == CL_BUILD_PROGRAM_FAILURE || status == CL_INVALID_BUILD_OPTIONS) {
            free(source);
            return build_failed(dev, status, err);
        }
        CL_CHECK_ERR(status, "clBuildProgram");
        if (dev->use_cache)
            store_in_cache(dev, key);
    }
    dev->build_seconds = now_seconds() - start;
    free(source);
    return true;
}

cl_uint kernel_set_args(cl_kernel kernel, cl_uint first, size_t n, const KernelArg *args)
{
    for (size_t j = 0; j < n; j++)
        CL_CHECK(clSetKernelArg(kernel, first + (cl_uint)j, args[j].size, args[j].value));
    return first + (cl_uint)n;
}

cl_kernel device_kernel(Device *dev, const char *name)
{
    cl_int status;
    cl_kernel kernel = clCreateKernel(dev->program, name, &status);
    if (status != CL_SUCCESS) {
        fprintf(stderr, "pt: kernel '%s' not found\n", name);
        cl_fail(status, "clCreateKernel", __FILE__, __LINE__);
    }
    return kernel;
}

cl_mem device_buffer(Device *dev, const char *name, cl_mem_flags flags, size_t size,
                     const void *host, Error *err)
{
    if ((cl_ulong)size > dev->max_alloc) {
        error_set(err, ERR_ALLOC_TOO_LARGE, NULL, 0,
                  "buffer '%s' needs %zu bytes (%.1f MiB), above the device's maximum allocation "
                  "of %llu bytes (%.1f MiB) on %s",
                  name, size, (double)size / (1 << 20), (unsigned long long)dev->max_alloc,
                  (double)dev->max_alloc / (1 << 20), dev->name);
        return NULL;
    }
    if (size == 0) {
        size = 16;
        host = NULL;
        flags &= ~(cl_mem_flags)(CL_MEM_COPY_HOST_PTR | CL_MEM_USE_HOST_PTR);
    }
    if (host)
        flags |= CL_MEM_COPY_HOST_PTR;
    cl_int status;
    cl_mem buffer = clCreateBuffer(dev->context, flags, size, (void *)host, &status);
    if (status == CL_MEM_OBJECT_ALLOCATION_FAILURE || status == CL_OUT_OF_RESOURCES ||
        status == CL_OUT_OF_HOST_MEMORY || status == CL_INVALID_BUFFER_SIZE) {
        error_set(err, ERR_ALLOC_TOO_LARGE, NULL, 0, "could not allocate buffer '%s' (%zu bytes) on %s: %s",
                  name, size, dev->name, cl_error_name(status));
        return NULL;
    }
    CL_CHECK_ERR(status, "clCreateBuffer");
    return buffer;
}

void device_read(Device *dev, cl_mem buf, size_t offset, size_t size, void *dst)
{
    if (size)
        CL_CHECK(clEnqueueReadBuffer(dev->queue, buf, CL_TRUE, offset, size, dst, 0, NULL, NULL));
}

void device_write(Device *dev, cl_mem buf, size_t offset, size_t size, const void *src)
{
    if (size)
        CL_CHECK(clEnqueueWriteBuffer(dev->queue, buf, CL_TRUE, offset, size, src, 0, NULL, NULL));
}

void device_run(Device *dev, cl_kernel kernel, size_t n, size_t local, double *profile_ms)
{
    if (n == 0) {
        if (profile_ms)
            *profile_ms = 0.0;
        return;
    }
    /* A kernel may allow less than the device (CL_KERNEL_WORK_GROUP_SIZE: registers, local
     * memory). The default size (PT_LOCAL_SIZE, checked against the device in device_open) is a
     * tuning choice and shrinks to fit; a size a caller asks for is one its local memory depends
     * on, so a kernel that cannot take it is a device the program does not support. */
    size_t kernel_max = 0;
    CL_CHECK(clGetKernelWorkGroupInfo(kernel, dev->device, CL_KERNEL_WORK_GROUP_SIZE,
                                      sizeof kernel_max, &kernel_max, NULL));
    if (local == 0) {
        local = dev->local_size ? dev->local_size : DEFAULT_LOCAL_SIZE;
        if (local > kernel_max)
            local = kernel_max;
    } else if (local > kernel_max) {
        die("a kernel needs work-groups of %zu, but %s allows at most %zu for it", local, dev->name,
            kernel_max);
    }
    size_t global = (n + local - 1) / local * local;
    cl_event event;
    CL_CHECK(clEnqueueNDRangeKernel(dev->queue, kernel, 1, NULL, &global, &local, 0, NULL,
                                    profile_ms ? &event : NULL));
    if (profile_ms)
        *profile_ms = device_event_ms(event);
}

double device_event_ms(cl_event event)
{
    cl_ulong start, end;
    CL_CHECK(clWaitForEvents(1, &event));
    CL_CHECK(clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_START, sizeof start, &start, NULL));
    CL_CHECK(clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_END, sizeof end, &end, NULL));
    CL_CHECK(clReleaseEvent(event));
    return (double)(end - start) * 1e-6;
}

void device_close(Device *dev)
{
    if (dev->program)
        clReleaseProgram(dev->program);
    if (dev->queue)
        clReleaseCommandQueue(dev->queue);
    if (dev->context)
        clReleaseContext(dev->context);
    memset(dev, 0, sizeof *dev);
}

cl_ulong device_local_mem_bytes(const Device *dev)
{
    cl_ulong bytes = 0;
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_LOCAL_MEM_SIZE, sizeof bytes, &bytes, NULL));
    return bytes;
}
