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
    KERNEL_ARG(kernel, 0, params_buf);
    KERNEL_ARG(kernel, 1, buffers->bvh_nodes);
    KERNEL_ARG(kernel, 2, buffers->bvh_tris);
    KERNEL_ARG(kernel, 3, buffers->positions);
    KERNEL_ARG(kernel, 4, buffers->normals);
    KERNEL_ARG(kernel, 5, buffers->uvs);
    KERNEL_ARG(kernel, 6, buffers->triangles);
    KERNEL_ARG(kernel, 7, buffers->material_ids);
    KERNEL_ARG(kernel, 8, buffers->materials);
    KERNEL_ARG(kernel, 9, buffers->texels);
    KERNEL_ARG(kernel, 10, buffers->textures);
    KERNEL_ARG(kernel, 11, spp_arg);
    KERNEL_ARG(kernel, 12, film);
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
