/* SPDX-License-Identifier: MIT */
/* detail_fixture.h: scenes for the surface-detail tests (normal and bump maps, cut-outs, emission
 * textures). The geometry and lights come from a JSON scene; the materials' texture slots, flags
 * and the textures themselves (linear float RGBA, exact texel values) are set on the loaded scene
 * before the BVH and the upload, so a test states every value it depends on. */
#ifndef PT_DETAIL_FIXTURE_H
#define PT_DETAIL_FIXTURE_H

#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh_wide.h"
#include "scene/texture.h"
#include "support.h"

/* Appends a width x height TEXTURE_RGBA32F texture (rgba: 4 floats a texel, row 0 the image's
 * top) to set; returns its index. */
static inline uint32_t detail_add_texture(TextureSet *set, uint32_t width, uint32_t height,
                                          const float *rgba)
{
    size_t n = (size_t)width * height * 4;
    set->texels = realloc(set->texels, (set->num_texels + n) * sizeof *set->texels);
    set->infos = realloc(set->infos, (set->count + 1) * sizeof *set->infos);
    set->paths = realloc(set->paths, (set->count + 1) * sizeof *set->paths);
    cr_assert(set->texels && set->infos && set->paths);
    memcpy(set->texels + set->num_texels, rgba, n * sizeof(float));
    set->infos[set->count] = (TextureInfo){.offset = (uint32_t)set->num_texels, .width = width,
                                           .height = height, .format = TEXTURE_RGBA32F};
    set->paths[set->count] = strdup("(test texture)");
    set->num_texels += n;
    return set->count++;
}

/* The material of triangle t (every triangle of one usemtl group shares it). */
static inline Material *detail_material(Scene *scene, uint32_t t)
{
    cr_assert(t < scene->data.num_triangles);
    return &scene->data.materials[scene->data.material_ids[t]];
}

typedef void (*DetailPatch)(Scene *scene, void *ctx);

/* render_fixture_open with patch(scene, ctx) run on the loaded scene before the BVH and upload. */
static inline void detail_fixture_open(RenderFixture *f, const char *scene_path, DetailPatch patch,
                                       void *ctx)
{
    Error err = {0};
    f->dev = test_device();
    cr_assert(scene_load(scene_path, &f->scene, &err), "scene_load %s: %s", scene_path, err.message);
    patch(&f->scene, ctx);
    scene_accel_build(&f->bvh, &f->scene.data, f->dev, PT_TESTS_TWO_LEVEL);
    cr_assert(scene_buffers_upload(f->dev, &f->scene.data, &f->bvh, &f->buffers, &err), "%s",
              err.message);
}

#endif
