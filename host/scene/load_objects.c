// SPDX-License-Identifier: MIT
/* load_objects.c: see load_objects.h. The meshes and instances it adds are SceneData's
 * (scene_data_instances.c). */
#define _DEFAULT_SOURCE /* realpath */
#include "scene/load_objects.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/obj_loader.h"
#include "io/ply_reader.h"
#include "scene/object_media.h"

#define NO_MESH 0xffffffffu

/* An object's mesh key: the file (by its canonical path where it exists; a glTF primitive's
 * "<canonical file>#meshes[m].primitives[p]", which realpath leaves as it is), the material
 * override, smoothing and the media it bounds (its triangles' materials carry them). Objects with
 * equal keys share one mesh. */
typedef struct {
    const char *path;
    uint32_t material;
    bool smooth;
    uint32_t interior, exterior;
    int object;
} MeshKey;

/* Whether a and b differ in what their triangles hold besides the file. */
static int compare_options(const MeshKey *a, const MeshKey *b)
{
    if (a->material != b->material)
        return a->material < b->material ? -1 : 1;
    if (a->smooth != b->smooth)
        return a->smooth ? 1 : -1;
    if (a->interior != b->interior)
        return a->interior < b->interior ? -1 : 1;
    if (a->exterior != b->exterior)
        return a->exterior < b->exterior ? -1 : 1;
    return 0;
}

static int compare_keys(const void *pa, const void *pb)
{
    const MeshKey *a = pa, *b = pb;
    int c = strcmp(a->path, b->path);
    if (c)
        return c;
    c = compare_options(a, b);
    return c ? c : a->object - b->object;
}

/* first_use[i]: the first object with object i's key; uses[i]: how many objects have it. Sorting
 * keeps this O(n log n) for forests of 10^5 objects; realpath runs once per distinct file name. */
static bool group_meshes(const SceneDesc *d, MeshKey *keys, char **canonical, char **owned,
                         int *first_use, int *uses, Error *err)
{
    int n = d->num_objects;
    for (int i = 0; i < n; i++)
        keys[i] = (MeshKey){d->objects[i], 0, false, 0, 0, i};
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
    for (int i = 0; i < n; i++) {
        const ObjectOptions *o = &d->object_options[i];
        keys[i] = (MeshKey){canonical[i], o->material, o->smooth, o->interior, o->exterior, i};
    }
    qsort(keys, (size_t)n, sizeof *keys, compare_keys);
    for (int k = 0; k < n;) {
        int end = k + 1;
        while (end < n && compare_options(&keys[end], &keys[k]) == 0 &&
               strcmp(keys[end].path, keys[k].path) == 0)
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

/* Appends object i's triangles, their materials given the media the object bounds. */
static bool load_object(SceneData *data, const SceneDesc *d, int i, const NamedMaterials *named,
                        DerivedMaterials *derived, Error *err)
{
    Mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    uint32_t first_triangle = data->num_triangles;
    bool ok;
    if (d->object_meshes && d->object_meshes[i]) { /* a glTF primitive, decoded in memory */
        ok = scene_data_append_object(data, d->object_meshes[i], d->objects[i],
                                      &d->object_options[i], named, err);
    } else {
        bool ply = d->object_formats && d->object_formats[i] == MESH_PLY;
        ok = (ply ? ply_load(d->objects[i], &mesh, err) : obj_load(d->objects[i], &mesh, err)) &&
             scene_data_append_object(data, &mesh, d->objects[i], &d->object_options[i], named,
                                      err);
        mesh_free(&mesh);
    }
    return ok && object_media_apply(data, first_triangle, &d->object_options[i], derived, d->path,
                                    err);
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
                     bool *merged, uint32_t *mesh_of, DerivedMaterials *derived, Error *err)
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
        if (!load_object(data, d, i, named, derived, err))
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
        if (!load_object(data, d, i, named, derived, err))
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
    DerivedMaterials derived = {0};
    data->keep_two_levels = mode == INSTANCING_ALWAYS;
    ok = ok && group_meshes(d, keys, canonical, owned, first_use, uses, err) &&
         load_all(data, d, mode, named, first_use, uses, merged, mesh_of, &derived, err);
    derived_materials_free(&derived);
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
