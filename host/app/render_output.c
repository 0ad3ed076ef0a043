// SPDX-License-Identifier: MIT
#include "app/render_output.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/version.h"
#include "io/image_io.h"
#include "render/aov.h"
#include "viewer/camera_controls.h"

/* The AOV pass's samples per pixel: a quarter of the beauty's, at most 16. An AOV sample (the
 * camera ray, plus the mirror and glass segments followed) costs about an eighth of a beauty
 * sample on PoCL (Cornell box, 256x256, 64 spp in 11.3 to 13.9 s, 16 AOV spp in 0.30 to 0.46 s),
 * so a quarter keeps the pass near 3% of the render, within issue 19's 5% (all of the samples
 * would cost about 12%); 16 jittered samples anti-alias the edges well enough for denoisers, and
 * past that the pass's share only falls. */
#define AOV_PASS_MAX_SPP 16
#define AOV_PASS_SPP_DIVISOR 4

typedef struct {
    const char *name, *channels;
    int count;
} LayerInfo;

static const LayerInfo layer_info[AOV_LAYER_COUNT] = {
#define AOV_LAYER_INFO(e, name, channels, n) {name, channels, n},
    AOV_LAYERS(AOV_LAYER_INFO)
#undef AOV_LAYER_INFO
};

bool render_images_alloc(RenderImages *images, unsigned mask, size_t num_pixels)
{
    memset(images, 0, sizeof *images);
    images->mask = mask;
    images->rgb = malloc(num_pixels * 3 * sizeof *images->rgb);
    images->alpha = calloc(num_pixels, sizeof *images->alpha);
    bool ok = images->rgb != NULL && images->alpha != NULL;
    for (int l = 0; l < AOV_LAYER_COUNT; l++) {
        if (!(mask & AOV_MASK(l)))
            continue;
        images->layer[l] = calloc(num_pixels * (size_t)layer_info[l].count, sizeof(float));
        ok = ok && images->layer[l];
    }
    if (!ok)
        render_images_free(images);
    return ok;
}

void render_images_free(RenderImages *images)
{
    free(images->rgb);
    free(images->alpha);
    free(images->noisy);
    for (int l = 0; l < AOV_LAYER_COUNT; l++)
        free(images->layer[l]);
    memset(images, 0, sizeof *images);
}

void render_images_read_film(RenderImages *images, Wavefront *w)
{
    if (images->layer[AOV_LAYER_SPP])
        wavefront_read_spp(w, images->layer[AOV_LAYER_SPP]);
    if (images->layer[AOV_LAYER_VARIANCE] &&
        !wavefront_read_variance(w, images->layer[AOV_LAYER_VARIANCE]))
        fprintf(stderr, "pt: warning: the film has no variance estimate: the variance layer is 0\n");
}

int aov_pass_spp(int spp_done)
{
    int spp = spp_done / AOV_PASS_SPP_DIVISOR;
    return spp < 1 ? 1 : spp < AOV_PASS_MAX_SPP ? spp : AOV_PASS_MAX_SPP;
}

bool render_images_aov_pass(RenderImages *images, Session *session, const RenderSettings *settings,
                            int aov_spp, Error *err)
{
    AovImages aovs = {.albedo = images->layer[AOV_LAYER_ALBEDO],
                      .normal = images->layer[AOV_LAYER_NORMAL],
                      .depth = images->layer[AOV_LAYER_DEPTH],
                      .coverage = images->alpha};
    if (!aovs.coverage && !aovs.albedo && !aovs.normal && !aovs.depth)
        return true;
    images->guide_spp = aov_spp;
    /* The coverage alone needs only the camera rays' first hits. */
    bool walk = aovs.albedo || aovs.normal || aovs.depth;
    AovSettings aov = {.spp = aov_spp,
                       .max_depth = walk ? settings->max_depth : 1,
                       .seed = settings->seed,
                       .first_sample = settings->first_sample};
    return aov_render_layers(&session->dev, &session->scene, &session->buffers, &aov, &aovs, err);
}

/* The header attributes only a denoised image has (the last of render_write_exr's list). */
#define DENOISE_ATTRIBUTES 4

/* The camera as the JSON object `pt render --camera` takes (the viewer's C key prints it). */
static void camera_json(const CameraDesc *camera, char *out, size_t size)
{
    char line[1024];
    viewer_camera_format(camera, line, sizeof line);
    const char *object = strchr(line, '{');
    snprintf(out, size, "%s", object ? object : line);
}

bool render_write_exr(const char *path, const RenderImages *images, const Session *session,
                      const RenderRecord *record, Error *err)
{
    const SceneDesc *desc = &session->scene.desc;
    ImageLayer layers[AOV_LAYER_COUNT + 1];
    int layer_count = 0;
    for (int l = 0; l < AOV_LAYER_COUNT; l++)
        if (images->layer[l] && (images->mask & AOV_MASK(l)))
            layers[layer_count++] = (ImageLayer){layer_info[l].name, layer_info[l].channels,
                                                 images->layer[l]};
    if (images->noisy)
        layers[layer_count++] = (ImageLayer){"noisy", "RGB", images->noisy};
    char seed[16], devices[600], camera[1024];
    snprintf(seed, sizeof seed, "%u", record->seed);
    snprintf(devices, sizeof devices, "%s (%s)", session->dev.name, session->dev.platform_name);
    camera_json(&desc->camera, camera, sizeof camera);
    char guides[96];
    snprintf(guides, sizeof guides, "albedo, normal: %d spp of the image's camera samples, "
             "prefiltered", images->guide_spp);
    const ImageAttribute attributes[] = {
        {.name = "spp", .type = IMAGE_ATTR_INT, .int_value = record->spp_done},
        {.name = "spp_requested", .type = IMAGE_ATTR_INT, .int_value = record->spp_requested},
        {.name = "seed", .type = IMAGE_ATTR_STRING, .string_value = seed},
        {.name = "render_time", .type = IMAGE_ATTR_FLOAT, .float_value = (float)record->render_seconds},
        {.name = "devices", .type = IMAGE_ATTR_STRING, .string_value = devices},
        {.name = "pt_version", .type = IMAGE_ATTR_STRING, .string_value = PT_VERSION},
        {.name = "scene", .type = IMAGE_ATTR_STRING, .string_value = record->scene},
        {.name = "camera", .type = IMAGE_ATTR_STRING, .string_value = camera},
        {.name = "partial", .type = IMAGE_ATTR_INT, .int_value = record->partial ? 1 : 0},
        /* --denoise: written only when the image was denoised (the attribute count drops them) */
        {.name = "denoised", .type = IMAGE_ATTR_INT, .int_value = 1},
        {.name = "denoiser", .type = IMAGE_ATTR_STRING, .string_value = images->denoiser},
        {.name = "denoise_device", .type = IMAGE_ATTR_STRING, .string_value = images->denoise_device},
        {.name = "denoise_guides", .type = IMAGE_ATTR_STRING, .string_value = guides},
    };
    int attribute_count = (int)(sizeof attributes / sizeof attributes[0]);
    if (!images->noisy)
        attribute_count -= DENOISE_ATTRIBUTES;
    ExrImage image = {.rgb = images->rgb,
                      .alpha = images->alpha,
                      .width = desc->width,
                      .height = desc->height,
                      .layers = layers,
                      .layer_count = layer_count,
                      .attributes = attributes,
                      .attribute_count = attribute_count};
    return image_write_exr_layers(path, &image, err);
}
