/* SPDX-License-Identifier: MIT */
/* texture_sampling.h: the texture lookups (cl/material/texture.cl) run on the test device through
 * the kernels of tests/cl/texture_test.cl, for the texture tests. Header-only so
 * that each test binary builds from its own .c alone. */
#ifndef PT_TESTS_TEXTURE_SAMPLING_H
#define PT_TESTS_TEXTURE_SAMPLING_H

#include <criterion/criterion.h>

#include "device/device.h"
#include "scene/texture.h"
#include "support.h"

/* Runs a texture test kernel (tests/cl/texture_test.cl: kernel(texels, infos, srgb_decode, index,
 * inputs, out, n)) for texture `index` over n inputs of input_bytes / n bytes each; out gets n float4. */
static inline void run_texture_kernel(const char *kernel_name, const uint32_t *texel_words,
                                      size_t texel_bytes, const TextureInfo *texture_infos,
                                      uint32_t texture_count, uint32_t index, const void *inputs,
                                      size_t input_bytes, uint32_t n, cl_float4 *out)
{
    Device *dev = test_device();
    Error err = {0};
    cl_mem texels = device_buffer(dev, "texels", CL_MEM_READ_ONLY, texel_bytes, (void *)texel_words,
                                  &err);
    cl_mem infos = device_buffer(dev, "textures", CL_MEM_READ_ONLY,
                                 texture_count * sizeof(TextureInfo), (void *)texture_infos, &err);
    cl_mem srgb = device_buffer(dev, "srgb_decode", CL_MEM_READ_ONLY,
                                TEXTURE_SRGB_CODES * sizeof(float),
                                (void *)texture_srgb_decode_table(), &err);
    cl_mem in = device_buffer(dev, "inputs", CL_MEM_READ_ONLY, input_bytes, (void *)inputs, &err);
    cl_mem result = device_buffer(dev, "out", CL_MEM_WRITE_ONLY, n * sizeof(cl_float4), NULL, &err);
    cr_assert_not(error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, kernel_name);
    KERNEL_ARGS(kernel, 0, KARG(texels), KARG(infos), KARG(srgb), KARG(index), KARG(in), KARG(result),
                KARG(n));
    device_run(dev, kernel, n, 0, NULL);
    device_read(dev, result, 0, n * sizeof(cl_float4), out);
    clReleaseKernel(kernel);
    cl_mem all[] = {texels, infos, srgb, in, result};
    for (int i = 0; i < 5; i++)
        clReleaseMemObject(all[i]);
    test_device_release(dev);
}

/* Runs sample_texture_at_uvs for texture `index` of set at n uvs. */
static inline void sample_on_device(const TextureSet *set, uint32_t index, const float *uv,
                                    uint32_t n, cl_float4 *out)
{
    run_texture_kernel("sample_texture_at_uvs", set->texels, set->num_texels * 4, set->infos,
                       set->count, index, uv, n * sizeof(cl_float2), n, out);
}

#endif
