/* SPDX-License-Identifier: MIT */
/* texture_sampling.h: texture_sample (cl/material/texture.cl) run on the test device through the
 * sample_texture_at_uvs kernel (tests/cl/texture_test.cl), for the texture tests. Header-only so
 * that each test binary builds from its own .c alone. */
#ifndef PT_TESTS_TEXTURE_SAMPLING_H
#define PT_TESTS_TEXTURE_SAMPLING_H

#include <criterion/criterion.h>

#include "device/device.h"
#include "scene/texture.h"
#include "support.h"

/* Runs sample_texture_at_uvs for texture `index` of set at n uvs. */
static inline void sample_on_device(const TextureSet *set, uint32_t index, const float *uv,
                                    uint32_t n, cl_float4 *out)
{
    Device *dev = test_device();
    Error err = {0};
    cl_mem texels = device_buffer(dev, "texels", CL_MEM_READ_ONLY, set->num_texels * 4, set->texels, &err);
    cl_mem infos = device_buffer(dev, "textures", CL_MEM_READ_ONLY, set->count * sizeof(TextureInfo),
                                 set->infos, &err);
    cl_mem uvs = device_buffer(dev, "uvs", CL_MEM_READ_ONLY, n * sizeof(cl_float2), uv, &err);
    cl_mem result = device_buffer(dev, "out", CL_MEM_WRITE_ONLY, n * sizeof(cl_float4), NULL, &err);
    cr_assert_not(error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "sample_texture_at_uvs");
    KERNEL_ARG(kernel, 0, texels);
    KERNEL_ARG(kernel, 1, infos);
    KERNEL_ARG(kernel, 2, index);
    KERNEL_ARG(kernel, 3, uvs);
    KERNEL_ARG(kernel, 4, result);
    KERNEL_ARG(kernel, 5, n);
    device_run(dev, kernel, n, 0, NULL);
    device_read(dev, result, 0, n * sizeof(cl_float4), out);
    clReleaseKernel(kernel);
    cl_mem all[] = {texels, infos, uvs, result};
    for (int i = 0; i < 4; i++)
        clReleaseMemObject(all[i]);
    test_device_release(dev);
}

#endif
