// SPDX-License-Identifier: MIT
/* scene_data_instances.c: the meshes and instances of SceneData (scene_data.h), beside their data
 * so that the flattener (scene_data.c) and the object loader (load_objects.c) both call down into
 * one place instead of into each other. */
#include "scene/scene_data.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static bool grow_array(void **array, size_t count, size_t element_size)
{
    void *grown = realloc(*array, (count ? count : 1) * element_size);
    if (grown)
        *array = grown;
    return grown != NULL;
}

void scene_data_bake_transform(SceneData *data, uint32_t first_triangle, uint32_t first_vertex,
                               const Affine *m)
{
    Affine inverse;
    if (!affine_invert(m, &inverse))
        die("scene_data_bake_transform: singular transform (the scene reader refuses these)");
    for (uint32_t v = first_vertex; v < data->num_vertices; v++) {
        double p[3] = {data->positions[v].s[0], data->positions[v].s[1], data->positions[v].s[2]};
        affine_point(m, p, p);
        double n[3] = {data->normals[v].s[0], data->normals[v].s[1], data->normals[v].s[2]};
        affine_normal(&inverse, n, n);
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) {
            data->positions[v].s[k] = (float)p[k];
            /* A zero normal (none given) stays zero. */
            data->normals[v].s[k] = len > 0.0 ? (float)(n[k] / len) : 0.0f;
        }
    }
    if (affine_det(m) < 0.0)
        for (uint32_t t = first_triangle; t < data->num_triangles; t++) {
            uint32_t swap = data->triangles[t].v.s[1];
            data->triangles[t].v.s[1] = data->triangles[t].v.s[2];
            data->triangles[t].v.s[2] = swap;
        }
}

bool scene_data_add_mesh(SceneData *data, uint32_t first_triangle, uint32_t first_vertex,
                         Error *err)
{
    size_t capacity = scene_data_grown_capacity(data->mesh_capacity, (size_t)data->num_meshes + 1);
    if (capacity != data->mesh_capacity &&
        !grow_array((void **)&data->meshes, capacity, sizeof *data->meshes)) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for meshes");
        return false;
    }
    data->mesh_capacity = capacity;
    SceneMesh *m = &data->meshes[data->num_meshes++];
    memset(m, 0, sizeof *m);
    m->first_triangle = first_triangle;
    m->num_triangles = data->num_triangles - first_triangle;
    m->first_vertex = first_vertex;
    m->num_vertices = data->num_vertices - first_vertex;
    for (int i = 0; i < 3; i++) {
        m->bounds_min[i] = INFINITY;
        m->bounds_max[i] = -INFINITY;
    }
    /* Every stored vertex comes from a triangle corner, so these are the bounds of used vertices. */
    for (uint32_t v = first_vertex; v < data->num_vertices; v++) {
        for (int i = 0; i < 3; i++) {
            m->bounds_min[i] = fminf(m->bounds_min[i], data->positions[v].s[i]);
            m->bounds_max[i] = fmaxf(m->bounds_max[i], data->positions[v].s[i]);
        }
    }
    return true;
}

bool scene_data_add_instance(SceneData *data, const SceneInstance *instance, Error *err)
{
    size_t capacity = scene_data_grown_capacity(data->instance_capacity, (size_t)data->num_instances + 1);
    if (capacity != data->instance_capacity &&
        !grow_array((void **)&data->instances, capacity, sizeof *data->instances)) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for instances");
        return false;
    }
    data->instance_capacity = capacity;
    data->instances[data->num_instances++] = *instance;
    return true;
}

void scene_data_finish_instances(SceneData *data)
{
    /* Each mesh's emissive triangles: emissive_triangles is ascending, meshes are ranges. */
    uint32_t e = 0;
    for (uint32_t m = 0; m < data->num_meshes; m++) {
        SceneMesh *mesh = &data->meshes[m];
        while (e < data->num_emissive && data->emissive_triangles[e] < mesh->first_triangle)
            e++;
        mesh->first_emissive = e;
        while (e < data->num_emissive &&
               data->emissive_triangles[e] < mesh->first_triangle + mesh->num_triangles)
            e++;
        mesh->num_emissive = e - mesh->first_emissive;
    }
    for (int i = 0; i < 3; i++) {
        data->bounds_min[i] = INFINITY;
        data->bounds_max[i] = -INFINITY;
    }
    data->num_moving = 0;
    data->two_level = data->num_instances != 1 || data->instances[0].mesh != 0 ||
                      data->num_meshes != 1 || !affine_is_identity(&data->instances[0].to_world);
    for (uint32_t i = 0; i < data->num_instances; i++) {
        SceneInstance *inst = &data->instances[i];
        const SceneMesh *mesh = &data->meshes[inst->mesh];
        if (inst->moving) {
            data->num_moving++;
            data->two_level = true;
            trs_align(&inst->motion[0], &inst->motion[1]);
            trs_swept_box(&inst->motion[0], &inst->motion[1], mesh->bounds_min, mesh->bounds_max,
                          inst->bounds_min, inst->bounds_max);
        } else if (affine_is_identity(&inst->to_world)) {
            memcpy(inst->bounds_min, mesh->bounds_min, sizeof inst->bounds_min);
            memcpy(inst->bounds_max, mesh->bounds_max, sizeof inst->bounds_max);
        } else {
            affine_box(&inst->to_world, mesh->bounds_min, mesh->bounds_max, inst->bounds_min,
                       inst->bounds_max);
        }
        for (int k = 0; k < 3; k++) {
            data->bounds_min[k] = fminf(data->bounds_min[k], inst->bounds_min[k]);
            data->bounds_max[k] = fmaxf(data->bounds_max[k], inst->bounds_max[k]);
        }
    }
}
