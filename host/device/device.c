// SPDX-License-Identifier: MIT
/* device.c: finding OpenCL platforms and devices: `pt devices`, opening the one a --device spec
 * names (and saying which exist when it names none), and closing it. */
#include "device/device_internal.h"

#include "device/kernel_cache.h"
#include "base/env.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_PLATFORMS 16
#define MAX_DEVICES 32

static const char no_platform_help[] =
    "no OpenCL platform found. The ICD loader finds drivers through the files in "
    "/etc/OpenCL/vendors (or the folder named by OCL_ICD_VENDORS). For the CPU, install "
    "pocl-opencl-icd; for an NVIDIA GPU, register its driver: mkdir -p /tmp/icd && echo "
    "libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && export OCL_ICD_VENDORS=/tmp/icd";

/* What `pt devices` and --device gpu say when the machine shows no GPU: the driver is often
 * installed but not registered with the ICD loader (containers). */
static const char no_gpu_hint[] =
    "For an NVIDIA GPU whose driver is installed but not registered: mkdir -p /tmp/icd && echo "
    "libnvidia-opencl.so.1 > /tmp/icd/nvidia.icd && cp /etc/OpenCL/vendors/*.icd /tmp/icd/ && "
    "export OCL_ICD_VENDORS=/tmp/icd";

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

/* The platforms; 0 with ERR_NO_PLATFORM (and the help on installing one) when there is none. */
static cl_uint get_platforms_or_fail(cl_platform_id *platforms, Error *err)
{
    cl_uint n = get_platforms(platforms);
    if (n == 0)
        error_set(err, ERR_NO_PLATFORM, NULL, 0, "%s", no_platform_help);
    return n;
}

bool device_list(FILE *out, Error *err)
{
    cl_platform_id platforms[MAX_PLATFORMS];
    cl_uint num_platforms = get_platforms_or_fail(platforms, err);
    if (num_platforms == 0)
        return false;
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
        fprintf(out, "no GPU found. %s\n", no_gpu_hint);
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
    if (gpu)
        error_set(err, ERR_DEVICE_UNKNOWN, NULL, 0,
                  "--device gpu: this machine has no GPU OpenCL device, only: %s. %s", devices,
                  no_gpu_hint);
    else if (cpu || !spec || !*spec)
        error_set(err, ERR_DEVICE_UNKNOWN, NULL, 0,
                  "--device %s: there is no %s OpenCL device; the devices are: %s (see 'pt devices')",
                  spec && *spec ? spec : "(default)", gpu ? "GPU" : cpu ? "CPU" : "GPU or CPU",
                  devices);
    else
        error_set(err, ERR_DEVICE_UNKNOWN, NULL, 0,
                  "--device %s: no such device; use gpu, cpu or P:D, one of: %s (see 'pt devices')",
                  spec, devices);
}

bool device_spec_is_list(const char *spec)
{
    return spec && (strcmp(spec, "all") == 0 || strchr(spec, ','));
}

/* Appends device (p, d) to the list as "P:D"; a device already there is an error naming it. */
static bool list_add(DeviceSpecList *list, const char *given, int p, int d, Error *err)
{
    char spec[sizeof list->spec[0]];
    snprintf(spec, sizeof spec, "%d:%d", p, d);
    for (int i = 0; i < list->count; i++)
        if (strcmp(list->spec[i], spec) == 0) {
            error_set(err, ERR_USAGE, NULL, 0, "--device %s: device %s is listed twice", given, spec);
            return false;
        }
    if (list->count == DEVICE_LIST_MAX) {
        error_set(err, ERR_USAGE, NULL, 0, "--device %s: more than %d devices", given, DEVICE_LIST_MAX);
        return false;
    }
    memcpy(list->spec[list->count++], spec, sizeof spec);
    return true;
}

bool device_spec_list(const char *spec, DeviceSpecList *list, Error *err)
{
    memset(list, 0, sizeof *list);
    cl_platform_id platforms[MAX_PLATFORMS];
    cl_uint num_platforms = get_platforms_or_fail(platforms, err);
    if (num_platforms == 0)
        return false;
    if (spec && strcmp(spec, "all") == 0) {
        /* Every GPU; every CPU only where there is no GPU (mixing is asked for by a list). */
        for (int pass = 0; pass < 2 && list->count == 0; pass++)
            for (cl_uint p = 0; p < num_platforms; p++) {
                cl_device_id devices[MAX_DEVICES];
                cl_uint num_devices = get_devices(platforms[p], devices);
                for (cl_uint d = 0; d < num_devices; d++) {
                    cl_device_type type;
                    CL_CHECK(clGetDeviceInfo(devices[d], CL_DEVICE_TYPE, sizeof type, &type, NULL));
                    if ((type & (pass == 0 ? CL_DEVICE_TYPE_GPU : CL_DEVICE_TYPE_CPU)) &&
                        !list_add(list, spec, (int)p, (int)d, err))
                        return false;
                }
            }
        if (list->count == 0) {
            char devices[512];
            describe_devices(platforms, num_platforms, devices, sizeof devices);
            error_set(err, ERR_DEVICE_UNKNOWN, NULL, 0,
                      "--device all: no GPU or CPU OpenCL device (the devices: %s)", devices);
            return false;
        }
        return true;
    }
    const char *item = spec ? spec : "";
    for (;;) {
        const char *comma = strchr(item, ',');
        size_t len = comma ? (size_t)(comma - item) : strlen(item);
        char one[64];
        if (len == 0 || len >= sizeof one) {
            error_set(err, ERR_USAGE, NULL, 0,
                      "--device %s: an empty or overlong entry in the list (use P:D,P:D, gpu, cpu "
                      "or all)", spec ? spec : "");
            return false;
        }
        memcpy(one, item, len);
        one[len] = '\0';
        int p, d;
        cl_device_id device;
        if (!find_device(one, platforms, num_platforms, &p, &d, &device)) {
            report_missing_device(one, platforms, num_platforms, err);
            return false;
        }
        if (!list_add(list, spec ? spec : "", p, d, err))
            return false;
        if (!comma)
            return true;
        item = comma + 1;
    }
}

bool device_open(Device *dev, const char *spec, Error *err)
{
    memset(dev, 0, sizeof *dev);
    cl_platform_id platforms[MAX_PLATFORMS];
    cl_uint num_platforms = get_platforms_or_fail(platforms, err);
    if (num_platforms == 0)
        return false;
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
    if (!device_choose_program_options(dev, err))
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

void device_close(Device *dev)
{
    device_finish_background_build(dev);
    for (int i = 0; i < PROGRAM_PART_COUNT; i++)
        if (dev->programs[i])
            clReleaseProgram(dev->programs[i]);
    free(dev->source);
    free(dev->options);
    if (dev->queue)
        clReleaseCommandQueue(dev->queue);
    if (dev->context)
        clReleaseContext(dev->context);
    memset(dev, 0, sizeof *dev);
}
