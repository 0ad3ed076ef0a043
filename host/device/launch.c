// SPDX-License-Identifier: MIT
/* launch.c: what runs on an open device: buffers, fills and blocking transfers, kernel arguments,
 * 1-D launches sized to the kernel's work-group limit, and their profiled times. Code outside
 * device/ makes no OpenCL call of its own (tools/check-layers.sh). */
#include "device/device_internal.h"

cl_uint kernel_set_args(cl_kernel kernel, cl_uint first, size_t n, const KernelArg *args)
{
    for (size_t j = 0; j < n; j++)
        CL_CHECK(clSetKernelArg(kernel, first + (cl_uint)j, args[j].size, args[j].value));
    return first + (cl_uint)n;
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

void *device_pinned_alloc(Device *dev, const char *name, size_t size, cl_mem *buffer, Error *err)
{
    *buffer = device_buffer(dev, name, CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, size, NULL, err);
    if (!*buffer)
        return NULL;
    cl_int status;
    void *p = clEnqueueMapBuffer(dev->queue, *buffer, CL_TRUE, CL_MAP_READ | CL_MAP_WRITE, 0, size,
                                 0, NULL, NULL, &status);
    CL_CHECK_ERR(status, "clEnqueueMapBuffer");
    return p;
}

void device_pinned_free(Device *dev, cl_mem buffer, void *p)
{
    if (!buffer)
        return;
    CL_CHECK(clEnqueueUnmapMemObject(dev->queue, buffer, p, 0, NULL, NULL));
    CL_CHECK(clFinish(dev->queue));
    CL_CHECK(clReleaseMemObject(buffer));
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

void device_fill(Device *dev, cl_mem buf, const void *pattern, size_t pattern_size, size_t offset,
                 size_t size, double *profile_ms)
{
    cl_event event;
    CL_CHECK(clEnqueueFillBuffer(dev->queue, buf, pattern, pattern_size, offset, size, 0, NULL,
                                 profile_ms ? &event : NULL));
    if (profile_ms)
        *profile_ms = device_event_ms(event);
}

void device_finish(Device *dev)
{
    CL_CHECK(clFinish(dev->queue));
}

void device_release_buffer(cl_mem buf)
{
    CL_CHECK(clReleaseMemObject(buf));
}

void device_release_kernel(cl_kernel kernel)
{
    CL_CHECK(clReleaseKernel(kernel));
}

size_t device_kernel_work_group_size(const Device *dev, cl_kernel kernel)
{
    size_t size = 0;
    CL_CHECK(clGetKernelWorkGroupInfo(kernel, dev->device, CL_KERNEL_WORK_GROUP_SIZE, sizeof size,
                                      &size, NULL));
    return size;
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

cl_ulong device_local_mem_bytes(const Device *dev)
{
    cl_ulong bytes = 0;
    CL_CHECK(clGetDeviceInfo(dev->device, CL_DEVICE_LOCAL_MEM_SIZE, sizeof bytes, &bytes, NULL));
    return bytes;
}
