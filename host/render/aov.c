// SPDX-License-Identifier: MIT
#include "render/aov.h"

#include <stdlib.h>

/* aov_render's walk through mirrors and glass (the viewer's probe only reads the depth). */
#define AOV_LEGACY_MAX_DEPTH 8

static RenderParams aov_params(const Scene *scene, const SceneBuffers *buffers,
                               const AovSettings *s)
{
    RenderParams params = render_params_for_scene(&scene->desc, buffers);
    params.seed = s->seed;
    params.max_depth = (uint)s->max_depth;
    params.sample_index = s->first_sample;
    return params;
}

bool aov_render_layers(Device *dev, const Scene *scene, const SceneBuffers *buffers,
                       const AovSettings *settings, const AovImages *out, Error *err)
{
    const SceneDesc *desc = &scene->desc;
    size_t num_pixels = (size_t)desc->width * (size_t)desc->height;
    RenderParams params = aov_params(scene, buffers, settings);
    cl_mem params_buf = device_buffer(dev, "params", CL_MEM_READ_ONLY,
                                      sizeof params, &params, err);
    cl_mem albedo_buf = device_buffer(dev, "albedo AOV", CL_MEM_WRITE_ONLY,
                                      num_pixels * sizeof(cl_float4), NULL, err);
    cl_mem normal_buf = device_buffer(dev, "normal AOV", CL_MEM_WRITE_ONLY,
                                      num_pixels * sizeof(cl_float4), NULL, err);
    cl_float4 *albedo = malloc(num_pixels * sizeof *albedo);
    cl_float4 *normal = malloc(num_pixels * sizeof *normal);
    bool ok = !error_is_set(err) && albedo && normal;
    if (ok) {
        /* The alpha and depth need only the first hits: render_coverage, whose part of the
         * program builds in a fraction of render_aov's time. */
        bool shaded = out->albedo || out->normal;
        cl_kernel kernel = device_kernel(dev, shaded ? "render_aov" : "render_coverage");
        cl_uint spp = (cl_uint)(settings->spp > 0 ? settings->spp : 1);
        cl_uint i = KERNEL_ARGS(kernel, 0, KARG(params_buf));
        i = scene_buffers_set_args(buffers, kernel, i);
        KERNEL_ARGS(kernel, i, KARG(spp), KARG(albedo_buf), KARG(normal_buf));
        device_run(dev, kernel, num_pixels, 0, NULL);
        device_read(dev, albedo_buf, 0, num_pixels * sizeof *albedo, albedo);
        device_read(dev, normal_buf, 0, num_pixels * sizeof *normal, normal);
        device_release_kernel(kernel);
        for (size_t p = 0; p < num_pixels; p++) {
            for (int c = 0; c < 3; c++) {
                if (out->albedo)
                    out->albedo[3 * p + c] = albedo[p].s[c];
                if (out->normal)
                    out->normal[3 * p + c] = normal[p].s[c];
            }
            if (out->depth)
                out->depth[p] = normal[p].s[3] > 0.0f ? albedo[p].s[3] : AOV_DEPTH_MISS;
            if (out->coverage)
                out->coverage[p] = normal[p].s[3];
        }
    } else if (!error_is_set(err)) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for the AOVs of a %dx%d film",
                  desc->width, desc->height);
    }
    free(albedo);
    free(normal);
    cl_mem buffers_made[] = {params_buf, albedo_buf, normal_buf};
    for (int b = 0; b < 3; b++)
        if (buffers_made[b])
            device_release_buffer(buffers_made[b]);
    return ok;
}

void aov_render(Device *dev, const Scene *scene, const SceneBuffers *buffers, unsigned aov, int spp,
                unsigned seed, float *rgb)
{
    const SceneDesc *desc = &scene->desc;
    size_t num_pixels = (size_t)desc->width * (size_t)desc->height;
    float *layer = malloc(num_pixels * 3 * sizeof *layer);
    if (!layer)
        die("out of memory for a %dx%d AOV", desc->width, desc->height);
    AovSettings settings = {.spp = spp, .max_depth = AOV_LEGACY_MAX_DEPTH, .seed = seed};
    AovImages images = {0};
    if (aov == AOV_ALBEDO)
        images.albedo = layer;
    else if (aov == AOV_NORMAL)
        images.normal = layer;
    else
        images.depth = layer;
    Error err = {0};
    if (!aov_render_layers(dev, scene, buffers, &settings, &images, &err))
        die("%s", err.message);
    for (size_t p = 0; p < num_pixels; p++)
        for (int c = 0; c < 3; c++)
            rgb[3 * p + c] = images.depth ? (layer[p] < AOV_DEPTH_MISS ? layer[p] : 0.0f)
                                          : layer[3 * p + c];
    free(layer);
}

