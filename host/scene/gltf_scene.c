// SPDX-License-Identifier: MIT
/* gltf_scene.c: see gltf_scene.h. Why objects and not a sub-scene: the description's objects are
 * what load_objects.c already groups into meshes and instances (dedup by key, the merged static mesh,
 * motion from transform_end), so a glTF node is placed exactly like a JSON object, and a JSON
 * object's transform composes with the nodes' matrices as one more parent. */
#define _DEFAULT_SOURCE /* realpath */
#include "scene/gltf_scene.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/analytic_lights.h"

static bool grow(void **array, size_t count, size_t size)
{
    void *grown = realloc(*array, (count ? count : 1) * size);
    if (grown)
        *array = grown;
    return grown != NULL;
}

bool scene_desc_reserve_objects(SceneDesc *d, int extra)
{
    size_t n = (size_t)d->num_objects + (size_t)extra;
    bool had_meshes = d->object_meshes != NULL;
    if (!grow((void **)&d->objects, n, sizeof *d->objects) ||
        !grow((void **)&d->object_formats, n, sizeof *d->object_formats) ||
        !grow((void **)&d->object_options, n, sizeof *d->object_options) ||
        !grow((void **)&d->object_transforms, n, sizeof *d->object_transforms) ||
        !grow((void **)&d->object_meshes, n, sizeof *d->object_meshes))
        return false;
    if (!had_meshes)
        memset(d->object_meshes, 0, n * sizeof *d->object_meshes);
    else
        memset(d->object_meshes + d->num_objects, 0, (size_t)extra * sizeof *d->object_meshes);
    return true;
}

static bool add_materials(SceneDesc *d, SceneGltf *g, int json_index, int *first, Error *err)
{
    GltfMaterial *materials = NULL;
    GltfImage *images = NULL;
    int count = 0, num_images = 0;
    if (!gltf_read_materials(&g->file, &materials, &count, &images, &num_images)) {
        free(materials);
        free(images);
        error_set(err, ERR_TOO_LARGE, g->file.path, 0, "%s: out of memory for materials", g->file.path);
        return false;
    }
    g->images = images;
    char prefix[64] = "";
    if (json_index >= 0)
        snprintf(prefix, sizeof prefix, "objects[%d].", json_index);
    *first = d->num_materials;
    bool ok = gltf_materials_append(materials, count, images, num_images, g->file.path, prefix,
                                    &d->materials, &d->num_materials, &d->textures,
                                    &d->num_textures, err);
    free(materials);
    return ok;
}

static bool add_lights(SceneDesc *d, const GltfFile *f, const ObjectTransform *t, Error *err)
{
    if (f->num_lights == 0)
        return true;
    if (!grow((void **)&d->lights, (size_t)(d->num_lights + f->num_lights), sizeof *d->lights)) {
        error_set(err, ERR_TOO_LARGE, f->path, 0, "%s: out of memory for lights", f->path);
        return false;
    }
    for (int i = 0; i < f->num_lights; i++) {
        const GltfLight *g = &f->lights[i];
        AnalyticLight *l = &d->lights[d->num_lights++];
        memset(l, 0, sizeof *l);
        double p[3], dir[3];
        affine_point(&t->transform, g->position, p);
        affine_vector(&t->transform, g->direction, dir);
        double len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
        float c[3];
        for (int k = 0; k < 3; k++)
            c[k] = (float)(g->color[k] * g->intensity / GLTF_LUMENS_PER_WATT);
        l->color = (float4){{c[0], c[1], c[2], 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]}};
        float4 unit_dir = {{(float)(dir[0] / len), (float)(dir[1] / len), (float)(dir[2] / len), 0.0f}};
        if (g->type == GLTF_LIGHT_DIRECTIONAL) {
            l->type = LIGHT_DIRECTIONAL;
            l->position = unit_dir; /* the direction the light travels */
            l->params.s[0] = 1.0f;  /* cos(half-angle 0): a delta light, as the JSON reader */
            continue;
        }
        l->position = (float4){{(float)p[0], (float)p[1], (float)p[2], 0.0f}};
        l->type = g->type == GLTF_LIGHT_SPOT ? LIGHT_SPOT : LIGHT_POINT;
        if (g->type == GLTF_LIGHT_SPOT) {
            l->axis = unit_dir;
            l->params.s[0] = g->outer_cone; /* pt's cone_angle */
            l->params.s[1] = g->inner_cone; /* pt's falloff_angle: full intensity inside */
        }
    }
    return true;
}

static void take_camera(SceneDesc *d, const GltfFile *f, const ObjectTransform *t)
{
    if (d->camera_given || !f->camera.present)
        return;
    double eye[3], forward[3], up[3];
    affine_point(&t->transform, f->camera.eye, eye);
    affine_vector(&t->transform, f->camera.forward, forward);
    affine_vector(&t->transform, f->camera.up, up);
    double len = sqrt(forward[0] * forward[0] + forward[1] * forward[1] + forward[2] * forward[2]);
    if (!(len > 0.0))
        return;
    for (int k = 0; k < 3; k++) {
        d->camera.eye[k] = (float)eye[k];
        d->camera.target[k] = (float)(eye[k] + forward[k] / len);
        d->camera.up[k] = (float)up[k];
    }
    d->camera.fov_y = (float)(f->camera.yfov * 180.0 / M_PI);
    d->camera_given = true;
}

bool gltf_scene_add(SceneDesc *d, const char *path, const ObjectOptions *options,
                    const ObjectTransform *transform, int json_index, Error *err)
{
    if (!grow((void **)&d->gltf_files, (size_t)d->num_gltf_files + 1, sizeof *d->gltf_files)) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory", path);
        return false;
    }
    SceneGltf *g = &d->gltf_files[d->num_gltf_files];
    memset(g, 0, sizeof *g);
    if (!gltf_load(path, &g->file, err))
        return false;
    d->num_gltf_files++;
    const GltfFile *f = &g->file;
    int first_material;
    if (!add_materials(d, g, json_index, &first_material, err))
        return false;
    int default_material = d->num_materials - 1; /* gltf_read_materials's last */
    int count = 0;
    for (int i = 0; i < f->num_placements; i++)
        count += f->mesh_first[f->placements[i].mesh + 1] - f->mesh_first[f->placements[i].mesh];
    if (!scene_desc_reserve_objects(d, count)) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory for %d objects", path, count);
        return false;
    }
    char canonical[PATH_MAX];
    if (!realpath(path, canonical))
        snprintf(canonical, sizeof canonical, "%s", path);
    for (int i = 0; i < f->num_placements; i++) {
        const GltfPlacement *pl = &f->placements[i];
        for (int p = f->mesh_first[pl->mesh]; p < f->mesh_first[pl->mesh + 1]; p++) {
            const GltfPrimitive *prim = &f->primitives[p];
            if (prim->skipped) /* POINTS or LINES: gltf_load warned */
                continue;
            int o = d->num_objects++;
            snprintf(d->objects[o], sizeof d->objects[o], "%.900s#meshes[%d].primitives[%d]",
                     canonical, prim->mesh_index, prim->primitive_index);
            d->object_formats[o] = MESH_GLTF;
            d->object_meshes[o] = &prim->mesh;
            d->object_options[o] = *options;
            if (prim->material >= default_material - first_material) {
                error_set(err, ERR_OBJ_PARSE, path, 0, "%s: meshes[%d].primitives[%d].material: "
                          "materials[%d] does not exist (%d materials)", path, prim->mesh_index,
                          prim->primitive_index, prim->material, default_material - first_material);
                return false;
            }
            if (options->material == NO_MATERIAL)
                d->object_options[o].material =
                    (uint32_t)(prim->material >= 0 ? first_material + prim->material : default_material);
            ObjectTransform *t = &d->object_transforms[o];
            t->transform = affine_mul(&transform->transform, &pl->world);
            t->transform_end = affine_mul(&transform->transform_end, &pl->world);
            t->has_end = transform->has_end;
        }
    }
    if (!add_lights(d, f, transform, err))
        return false;
    take_camera(d, f, transform);
    return true;
}
