// SPDX-License-Identifier: MIT
#include "render/aov.h"

#include <stdlib.h>

#include "scene/camera.h"

void aov_render(Device *dev, const Scene *scene, const SceneBuffers *buffers, unsigned aov, int spp,
                unsigned seed, float *rgb)
{
    const SceneDesc *desc = &scene->desc;
    size_t num_pixels = (size_t)desc->width * (size_t)desc->height;
    RenderParams params = {
        .camera = camera_from_desc(&desc->camera, desc->width, desc->height),
        .width = (uint)desc->width,
        .height = (uint)desc->height,
        .seed = seed,
        .num_bvh_prims = buffers->num_bvh_prims,
        .aov = aov,
    };
    Error err = {0};
    cl_mem params_buf = device_buffer(dev, "params", CL_MEM_READ_ONLY, sizeof params, &params, &err);
    cl_mem film = device_buffer(dev, "film", CL_MEM_WRITE_ONLY, num_pixels * sizeof(float4), NULL, &err);
    if (error_is_set(&err))
        die("%s", err.message);
    cl_kernel kernel = device_kernel(dev, "render_aov");
    cl_uint spp_arg = (cl_uint)spp;
    cl_uint i = KERNEL_ARGS(kernel, 0, KARG(params_buf));
    i = scene_buffers_set_args(buffers, kernel, i);
    KERNEL_ARGS(kernel, i, KARG(spp_arg), KARG(film));
    device_run(dev, kernel, num_pixels, 0, NULL);
    float4 *pixels = malloc(num_pixels * sizeof *pixels);
    if (!pixels)
        die("out of memory for a %dx%d film", desc->width, desc->height);
    device_read(dev, film, 0, num_pixels * sizeof *pixels, pixels);
    for (size_t i = 0; i < num_pixels; i++)
        for (int c = 0; c < 3; c++)
            rgb[3 * i + c] = pixels[i].s[c];
    free(pixels);
    CL_CHECK(clReleaseKernel(kernel));
    CL_CHECK(clReleaseMemObject(film));
    CL_CHECK(clReleaseMemObject(params_buf));
}
