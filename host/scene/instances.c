// SPDX-License-Identifier: MIT
/* instances.c: see instances.h; also the meshes and instances of SceneData (scene_data.h:
 * scene_data_add_mesh, scene_data_add_instance, scene_data_finish_instances). */
#define _DEFAULT_SOURCE /* realpath */
#include "scene/instances.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/obj_loader.h"
#include "io/ply_reader.h"

#define NO_MESH 0xffffffffu

static bool grow_array(void **array, size_t count, size_t element_size)
{
    void *grown = realloc(*array, (count ? count : 1) * element_size);
    if (grown)
        *array = grown;
    return grown != NULL;
}

/* An object's mesh key: the file (by its canonical path where it exists; a glTF primitive's
 * "<canonical file>#meshes[m].primitives[p]", which realpath leaves as it is), the material
 * override and smoothing. Objects with equal keys share one mesh. */
typedef struct {
    const char *path;
    uint32_t material;
    bool smooth;
    int object;
} MeshKey;

static int compare_keys(const void *pa, const void *pb)
{
    const MeshKey *a = pa, *b = pb;
    int c = strcmp(a->path, b->path);
    if (c)
        return c;
    if (a->material != b->material)
        return a->material < b->material ? -1 : 1;
    if (a->smooth != b->smooth)
        return a->smooth ? 1 : -1;
    return a->object - b->object;
}

/* first_use[i]: the first object with object i's key; uses[i]: how many objects have it. Sorting
 * keeps this O(n log n) for forests of 10^5 objects; realpath runs once per distinct file name. */
static bool group_meshes(const SceneDesc *d, MeshKey *keys, char **canonical, char **owned,
                         int *first_use, int *uses, Error *err)
{
    int n = d->num_objects;
    for (int i = 0; i < n; i++)
        keys[i] = (MeshKey){d->objects[i], 0, false, i};
    qsort(keys, (size_t)n, sizeof *keys, compare_keys);
    for (int k = 0; k < n; k++) {
        int i = keys[k].object;
        if (k > 0 && strcmp(keys[k].path, keys[k - 1].path) == 0) {
            canonical[i] = canonical[keys[k - 1].object];
            continue;
        }
        char resolved[PATH_MAX];
        canonical[i] = *owned++ = strdup(realpath(d->objects[i], resolved) ? resolved : d->objects[i]);
        if (!canonical[i]) {
            error_set(err, ERR_TOO_LARGE, d->path, 0, "%s: out of memory", d->path);
            return false;
        }
    }
    for (int i = 0; i < n; i++)
        keys[i] = (MeshKey){canonical[i], d->object_options[i].material,
                            d->object_options[i].smooth, i};
    qsort(keys, (size_t)n, sizeof *keys, compare_keys);
    for (int k = 0; k < n;) {
        int end = k + 1;
        while (end < n && keys[end].material == keys[k].material &&
               keys[end].smooth == keys[k].smooth && strcmp(keys[end].path, keys[k].path) == 0)
            end++;
        for (int j = k; j < end; j++) {
            first_use[keys[j].object] = keys[k].object; /* sorted by object within the group */
            uses[keys[j].object] = end - k;
        }
        k = end;
    }
    return true;
}

/* An object moves when it has a transform_end that differs from its transform and the shutter
 * opens (the JSON reader warned about a transform_end without a shutter interval). */
static bool object_moves(const SceneDesc *d, int i)
{
    const ObjectTransform *t = &d->object_transforms[i];
    return t->has_end && d->camera.shutter_open < d->camera.shutter_close &&
           !affine_equal(&t->transform, &t->transform_end);
}

static bool load_object(SceneData *data, const SceneDesc *d, int i, const NamedMaterials *named,
                        Error *err)
{
    ObjMesh mesh;
    memset(&mesh, 0, sizeof mesh);
    if (d->object_meshes && d->object_meshes[i]) /* a glTF primitive, decoded in memory */
        return scene_data_append_object(data, d->object_meshes[i], d->objects[i],
                                        &d->object_options[i], named, err);
    bool ply = d->object_formats && d->object_formats[i] == MESH_PLY;
    bool ok = (ply ? ply_load(d->objects[i], &mesh, err) : obj_load(d->objects[i], &mesh, err)) &&
              scene_data_append_object(data, &mesh, d->objects[i], &d->object_options[i], named,
                                       err);
    obj_free(&mesh);
    return ok;
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

/* Instance of object i of mesh m. */
static bool add_object_instance(SceneData *data, const SceneDesc *d, int i, uint32_t mesh,
                                Error *err)
{
    const ObjectTransform *t = &d->object_transforms[i];
    SceneInstance inst = {.mesh = mesh, .object = i, .to_world = t->transform};
    if (object_moves(d, i)) {
        inst.moving = true;
        if (!trs_decompose(&t->transform, &inst.motion[0]) ||
            !trs_decompose(&t->transform_end, &inst.motion[1])) {
            error_set(err, ERR_JSON_VALUE, d->path, 0,
                      "%s: objects[%d]: transform or transform_end cannot be decomposed into "
                      "translation, rotation and scale (singular)", d->path, i);
            return false;
        }
    }
    return scene_data_add_instance(data, &inst, err);
}

static bool load_all(SceneData *data, const SceneDesc *d, InstancingMode mode,
                     const NamedMaterials *named, const int *first_use, const int *uses,
                     bool *merged, uint32_t *mesh_of, Error *err)
{
    int n = d->num_objects;
    for (int i = 0; i < n; i++) {
        bool identity = affine_is_identity(&d->object_transforms[i].transform);
        merged[i] = !object_moves(d, i) && mode != INSTANCING_ALWAYS &&
                    (mode == INSTANCING_NEVER || (identity && uses[i] == 1));
    }
    /* The merged mesh first (mesh 0, instance 0), in the objects' order, as v1 flattened them. */
    for (int i = 0; i < n; i++) {
        if (!merged[i])
            continue;
        uint32_t first_triangle = data->num_triangles, first_vertex = data->num_vertices;
        if (!load_object(data, d, i, named, err))
            return false;
        if (!affine_is_identity(&d->object_transforms[i].transform))
            scene_data_bake_transform(data, first_triangle, first_vertex,
                                      &d->object_transforms[i].transform);
    }
    if (data->num_triangles > 0) {
        SceneInstance whole = {.mesh = 0, .object = -1, .to_world = affine_identity()};
        if (!scene_data_add_mesh(data, 0, 0, err) || !scene_data_add_instance(data, &whole, err))
            return false;
    }
    /* Every other distinct mesh once, then the instances in the objects' order. */
    for (int i = 0; i < n; i++) {
        mesh_of[i] = NO_MESH;
        if (merged[i] || first_use[i] != i)
            continue;
        uint32_t first_triangle = data->num_triangles, first_vertex = data->num_vertices;
        if (!load_object(data, d, i, named, err))
            return false;
        if (data->num_triangles > first_triangle) { /* a file without faces adds nothing */
            if (!scene_data_add_mesh(data, first_triangle, first_vertex, err))
                return false;
            mesh_of[i] = data->num_meshes - 1;
        }
    }
    for (int i = 0; i < n; i++)
        if (!merged[i] && mesh_of[first_use[i]] != NO_MESH &&
            !add_object_instance(data, d, i, mesh_of[first_use[i]], err))
            return false;
    return true;
}

bool scene_load_objects(SceneData *data, const SceneDesc *d, InstancingMode mode,
                        const NamedMaterials *named, Error *err)
{
    size_t n = d->num_objects > 0 ? (size_t)d->num_objects : 1;
    MeshKey *keys = malloc(n * sizeof *keys);
    char **canonical = calloc(n, sizeof *canonical), **owned = calloc(n, sizeof *owned);
    int *first_use = malloc(n * sizeof *first_use), *uses = malloc(n * sizeof *uses);
    bool *merged = malloc(n * sizeof *merged);
    uint32_t *mesh_of = malloc(n * sizeof *mesh_of);
    bool ok = keys && canonical && owned && first_use && uses && merged && mesh_of;
    if (!ok)
        error_set(err, ERR_TOO_LARGE, d->path, 0, "%s: out of memory for %d objects", d->path,
                  d->num_objects);
    ok = ok && group_meshes(d, keys, canonical, owned, first_use, uses, err) &&
         load_all(data, d, mode, named, first_use, uses, merged, mesh_of, err);
    /* Objects of one file name share its canonical string: owned[] has each once. */
    for (size_t i = 0; owned && i < n && owned[i]; i++)
        free(owned[i]);
    free(owned);
    free(keys);
    free(canonical);
    free(first_use);
    free(uses);
    free(merged);
    free(mesh_of);
    return ok;
}

/* ---- Meshes and instances of SceneData (scene_data.h) ------------------------------------ */

bool scene_data_add_mesh(SceneData *data, uint32_t first_triangle, uint32_t first_vertex,
                         Error *err)
{
    if (!grow_array((void **)&data->meshes, (size_t)data->num_meshes + 1, sizeof *data->meshes)) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for meshes");
        return false;
    }
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
    if (!grow_array((void **)&data->instances, (size_t)data->num_instances + 1, sizeof *data->instances)) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for instances");
        return false;
    }
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
