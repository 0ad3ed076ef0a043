// SPDX-License-Identifier: MIT
#include "render/session.h"

#include <stdio.h>
#include <sys/resource.h>
#include <string.h>

#include "base/clock.h"
#include "base/error.h"
#include "scene/camera_json.h"
#include "scene/sampler.h"
#include "scene/scene_media.h"

static bool apply_overrides(const RenderDesc *o, Scene *scene, Error *err)
{
    SceneDesc *d = &scene->desc;
    if (o->width) d->width = o->width;
    if (o->height) d->height = o->height;
    /* A camera the file does not give (or --frame) is framed for the film's aspect as it is now,
     * before the rig's ground joins the bounds. */
    if (!d->camera_given || o->frame)
        scene_frame_camera(scene, (UpAxis)o->up_axis);
    /* --camera: the keys it has replace the scene's (or the framed default camera's), read by
     * the scene's own camera reader, so a render with it equals one of a scene file with it. */
    if (o->camera_json) {
        if (!camera_desc_parse_option(o->camera_json, &d->camera, err))
            return false;
        d->camera_given = true;
    }
    if (o->spp) d->spp = o->spp;
    if (o->max_depth) d->max_depth = o->max_depth;
    /* Pixel indices are 32-bit in the kernels. */
    if ((uint64_t)d->width * (uint64_t)d->height > (1ull << 31)) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "film %dx%d is too large (at most 2^31 pixels)", d->width,
                  d->height);
        return false;
    }
    return true;
}

/* The features the scene uses (cl/shared/features.h): the program is built for exactly these, so
 * the code of the others leaves the kernels. The kernel cache keys on them, so each combination is
 * its own entry. FEATURE_INSTANCES and FEATURE_TLAS are not optional: they must match the levels
 * that scene_accel_build builds (a two-level walk over a one-level tree reads past its arrays). */
static ProgramFeatures scene_program_features(const SceneData *data, bool black_holes)
{
    /* Cut-out materials (cl/material/surface_detail.cl) add a material read per hit to both
     * intersect stages: only scenes that have one pay for it. */
    bool cutout = false;
    for (uint32_t i = 0; i < data->num_materials && !cutout; i++)
        cutout = (data->materials[i].flags & MATERIAL_FLAG_CUTOUT) != 0;
    ProgramFeatures f = material_features(data->materials, data->num_materials, &data->textures);
    f |= data->environment.width > 0 ? FEATURE_ENV : 0u;
    f |= data->num_analytic > 0 ? FEATURE_ANALYTIC : 0u;
    f |= cutout ? FEATURE_CUTOUT : 0u;
    f |= BVH_LEVELS_FEATURES(scene_accel_levels(data));
    f |= data->num_moving > 0 ? FEATURE_MOTION : 0u;
    f |= black_holes ? FEATURE_BLACK_HOLES : 0u;
    /* Pure absorbers (and dielectrics' absorption) need only Beer-Lambert; tracking is for media
     * that scatter or emit. */
    f |= data->num_media > 0 ? FEATURE_ABSORPTION : 0u;
    f |= scene_data_media_track(data) ? FEATURE_MEDIA : 0u;
    f |= scene_data_has_grid_media(data) ? FEATURE_GRID_MEDIA | FEATURE_MEDIA : 0u;
    return f;
}

/* Opens the device named by spec with the program built for the scene, lays the BVH out for it
 * (2-wide on GPUs, 8-wide on CPUs) and uploads the scene's buffers; on failure everything opened is
 * closed again. */
static bool open_on_device(Device *dev, SceneBvh *bvh, SceneBuffers *buffers, const Scene *scene,
                           const char *spec, bool no_cache, double *bvh_seconds, Error *err)
{
    bool opened = device_open(dev, spec, err);
    if (opened && no_cache)
        dev->use_cache = false;
    if (!opened ||
        !device_build(dev, scene_program_features(&scene->data, scene->desc.num_black_holes > 0),
                      NULL, NULL, err)) {
        if (dev->context)
            device_close(dev);
        return false;
    }
    double t1 = seconds_now();
    scene_accel_build(bvh, &scene->data, dev, scene_accel_levels(&scene->data));
    *bvh_seconds = seconds_now() - t1;
    /* A walk over the wrong levels reads past the BVH's arrays: never launch one. */
    ProgramFeatures walk = dev->features & (ProgramFeatures)(FEATURE_INSTANCES | FEATURE_TLAS);
    if (walk != BVH_LEVELS_FEATURES(bvh->levels))
        die("the program's traversal features (%#x) do not match the BVH's levels (%d)", walk,
            (int)bvh->levels);
    if (!scene_buffers_upload(dev, &scene->data, bvh, buffers, err)) {
        scene_buffers_release(buffers);
        scene_bvh_free(bvh);
        device_close(dev);
        return false;
    }
    /* The device has the nodes and triangles now; keep only the BVH's counts and times. */
    scene_bvh_drop_arrays(bvh);
    return true;
}

bool session_device_open(SessionDevice *d, const Scene *scene, const char *spec, bool no_cache,
                         Error *err)
{
    memset(d, 0, sizeof *d);
    double bvh_seconds;
    return open_on_device(&d->dev, &d->bvh, &d->buffers, scene, spec, no_cache, &bvh_seconds, err);
}

void session_device_close(SessionDevice *d)
{
    scene_buffers_release(&d->buffers);
    scene_bvh_free(&d->bvh);
    if (d->dev.context)
        device_close(&d->dev);
    memset(d, 0, sizeof *d);
}

bool session_open(Session *s, const RenderDesc *o, Error *err)
{
    memset(s, 0, sizeof *s);
    double t0 = seconds_now();
    if (!scene_load_with(o->scene, (InstancingMode)o->instancing, &s->scene, err))
        return false;
    RigOptions rig = {.up = (UpAxis)o->up_axis, .no_ground = o->no_ground};
    if (!apply_overrides(o, &s->scene, err) ||
        (!o->no_default_light && !scene_add_default_rig(&s->scene, &rig, err))) {
        scene_free(&s->scene);
        return false;
    }
    s->load_seconds = seconds_now() - t0;
    if (!open_on_device(&s->dev, &s->bvh, &s->buffers, &s->scene, o->device, o->no_cache,
                        &s->bvh_seconds, err)) {
        scene_free(&s->scene);
        return false;
    }
    return true;
}

/* The process's peak resident memory in MiB (Linux reports ru_maxrss in KiB). */
static double peak_rss_mib(void)
{
    struct rusage usage;
    return getrusage(RUSAGE_SELF, &usage) == 0 ? (double)usage.ru_maxrss / 1024.0 : 0.0;
}

void session_print_summary(const Session *s)
{
    const SceneData *d = &s->scene.data;
    char features[PROGRAM_FEATURE_SUMMARY_SIZE];
    program_features_summary(s->dev.features, features);
    fprintf(stderr,
            "pt: %s: %u triangles, %u materials, %u textures, %u emissive triangles; load %.2f s, "
            "BVH %.2f s, kernels %.2f s (%s; features: %s)\n",
            s->scene.desc.path, d->num_triangles, d->num_materials, d->textures.count,
            d->num_emissive, s->load_seconds, s->bvh_seconds, s->dev.build_seconds,
            s->dev.cache_hit ? "from the kernel cache" : "compiled", features);
    if (s->bvh.levels == BVH_TWO_LEVEL)
        fprintf(stderr,
                "pt: %u meshes, %u instances (%u moving): %.4g triangles rendered; two-level BVH "
                "(BLAS %.3f s, TLAS %.3f s)\n",
                d->num_meshes, d->num_instances, d->num_moving, (double)scene_traced_triangles(d),
                s->bvh.blas_seconds, s->bvh.tlas_seconds);
    else if (s->bvh.levels == BVH_FLAT)
        fprintf(stderr,
                "pt: %u meshes, %u instances: %.4g triangles rendered; one flat BVH over them "
                "(%.3f s; --instancing always keeps two levels)\n",
                d->num_meshes, d->num_instances, (double)scene_traced_triangles(d),
                s->bvh.blas_seconds);
    fprintf(stderr, "pt: device %s (%s, driver %s), %.1f MiB of scene buffers; host peak %.0f MiB\n",
            s->dev.name, s->dev.platform_name, s->dev.driver_version,
            (double)s->buffers.bytes / (1 << 20), peak_rss_mib());
}

void session_close(Session *s)
{
    scene_buffers_release(&s->buffers);
    scene_bvh_free(&s->bvh);
    if (s->dev.context)
        device_close(&s->dev);
    scene_free(&s->scene);
    memset(s, 0, sizeof *s);
}

/* A material's way through shading: its type and the features it uses (materials.h). The scene's
 * textures add only a bit that every material would share (a procedural texture in the set), so
 * they are left out: each material costs a constant. */
static uint32_t shading_kind(const Material *m)
{
    static const TextureSet no_textures;
    return (uint32_t)m->type << 24 | material_features(m, 1, &no_textures);
}

/* A diffuse material that scatters nothing (an OBJ lamp's Kd 0 beside its Ke): a path that
 * reaches it gathers what it emits and ends, whatever the other materials do. */
static bool scatters_nothing(const Material *m)
{
    return m->type == MATERIAL_DIFFUSE && m->tex[MATERIAL_TEX_BASE] == NO_TEXTURE &&
           m->base.s[0] == 0.0f && m->base.s[1] == 0.0f && m->base.s[2] == 0.0f;
}

/* Whether the scene's materials take more than one way through shading, those that scatter
 * nothing (lamps) left out: a room of normal-mapped walls under a lamp is one kind, where sorting
 * paths by material cannot make shading more coherent (it costs the plain Cornell box about a
 * quarter, the textured box a tenth, on the H200). */
static bool shading_diverges(const SceneData *d)
{
    bool found = false;
    uint32_t first = 0;
    for (uint32_t i = 0; i < d->num_materials; i++) {
        const Material *m = &d->materials[i];
        if (scatters_nothing(m))
            continue;
        uint32_t kind = shading_kind(m);
        if (found && kind != first)
            return true;
        found = true;
        first = kind;
    }
    return false;
}

bool session_sorts_materials(const SceneData *d, int request)
{
    if (request != SORT_MATERIALS_AUTO)
        return request == SORT_MATERIALS_ON;
    /* Refraction alone (a smooth dielectric) branches no more than Lambert does, and how texels
     * are stored and sampled does not change a material's way through shading. */
    uint32_t same_way = MATERIAL_FEATURE_REFRACTION | MATERIAL_FEATURE_TEXTURE |
                        MATERIAL_FEATURE_SRGB_TEXTURE | MATERIAL_FEATURE_FLOAT_TEXTURE |
                        MATERIAL_FEATURE_TEXTURE_SAMPLER;
    if (!(material_features(d->materials, d->num_materials, &d->textures) & ~same_way))
        return false;
    return shading_diverges(d);
}

void session_settle_settings(const Session *s, RenderSettings *settings, int sort_request)
{
    if (!settings->spp)
        settings->spp = s->scene.desc.spp;
    settings->max_depth = s->scene.desc.max_depth;
    settings->sampler = sampler_resolve(settings->sampler, s->scene.desc.sampler);
    settings->sort_materials = session_sorts_materials(&s->scene.data, sort_request);
}
