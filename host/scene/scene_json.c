// SPDX-License-Identifier: MIT
/* scene_json.c: the sections of the scene format (shared/DESIGN.md). Each section checks its keys,
 * reads them with json.h's typed readers and checks the values' ranges; "textures" and
 * "materials" are read by texture_json.c and material_json.c. */
#include "scene/scene_json.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/analytic_lights.h"
#include "scene/black_holes.h"
#include "scene/camera_json.h"
#include "scene/gltf_scene.h"
#include "scene/sampler.h"
#include "scene/transform_json.h"

static bool parse_positive_int(JsonParser *p, const cJSON *obj, const char *name, const char *key,
                               int min, int max, int *out)
{
    const cJSON *item = json_member(obj, name);
    if (!item)
        return true;
    if (!json_read_int(p, item, key, out))
        return false;
    if (*out < min || *out > max)
        return json_fail(p, ERR_JSON_VALUE, key, "%d is out of range [%d, %d]", *out, min, max);
    return true;
}

static bool parse_film(JsonParser *p, const cJSON *obj, SceneDesc *d)
{
    static const char *const keys[] = {"width", "height", NULL};
    return json_check_object(p, obj, "film", keys) &&
           parse_positive_int(p, obj, "width", "film.width", 1, FILM_SIZE_LIMIT, &d->width) &&
           parse_positive_int(p, obj, "height", "film.height", 1, FILM_SIZE_LIMIT, &d->height);
}

static bool parse_render(JsonParser *p, const cJSON *obj, SceneDesc *d)
{
    static const char *const keys[] = {"spp",     "max_depth", "noise_threshold", "min_spp",
                                       "denoise", "sampler",   NULL};
    if (!json_check_object(p, obj, "render", keys) ||
        !parse_positive_int(p, obj, "spp", "render.spp", 1, INT_MAX, &d->spp) ||
        !parse_positive_int(p, obj, "max_depth", "render.max_depth", 1, MAX_DEPTH_LIMIT,
                            &d->max_depth) ||
        !parse_positive_int(p, obj, "min_spp", "render.min_spp", 1, INT_MAX, &d->min_spp))
        return false;
    /* Adaptive sampling (render/wavefront.h); min_spp against the final spp is checked there,
     * after the command line's overrides. */
    const cJSON *item = json_member(obj, "noise_threshold");
    if (item && !json_read_float(p, item, "render.noise_threshold", &d->noise_threshold))
        return false;
    if (item && !(d->noise_threshold > 0.0f))
        return json_fail(p, ERR_JSON_VALUE, "render.noise_threshold", "%g must be > 0",
                         d->noise_threshold);
    item = json_member(obj, "denoise");
    if (item && !cJSON_IsBool(item))
        return json_fail(p, ERR_JSON_TYPE, "render.denoise", "expected true or false");
    d->denoise = item && cJSON_IsTrue(item);
    item = json_member(obj, "sampler");
    if (item && !(cJSON_IsString(item) && sampler_from_name(item->valuestring, &d->sampler)))
        return json_fail(p, cJSON_IsString(item) ? ERR_JSON_VALUE : ERR_JSON_TYPE, "render.sampler",
                         "expected \"sobol\" or \"independent\"");
    return true;
}

/* objects[i].smooth (default false: a mesh without vn is shaded flat), objects[i].material (a
 * JSON material's name, given to every triangle of the object) and the media it bounds
 * (objects[i].interior / .exterior, names in "media"). */
static bool parse_object_options(JsonParser *p, const cJSON *e, int i, SceneDesc *d, ObjectOptions *o)
{
    o->material = NO_MATERIAL;
    o->json_object = i;
    char key[64];
    snprintf(key, sizeof key, "objects[%d].interior", i);
    if (!media_read_slot(p, json_member(e, "interior"), key, d->media, d->num_media, &o->interior))
        return false;
    snprintf(key, sizeof key, "objects[%d].exterior", i);
    if (!media_read_slot(p, json_member(e, "exterior"), key, d->media, d->num_media, &o->exterior))
        return false;
    const cJSON *item = json_member(e, "smooth");
    if (item) {
        snprintf(key, sizeof key, "objects[%d].smooth", i);
        if (!cJSON_IsBool(item))
            return json_fail(p, ERR_JSON_TYPE, key, "expected true or false");
        o->smooth = cJSON_IsTrue(item);
    }
    item = json_member(e, "material");
    if (!item)
        return true;
    snprintf(key, sizeof key, "objects[%d].material", i);
    if (!cJSON_IsString(item))
        return json_fail(p, ERR_JSON_TYPE, key, "expected a material name (string)");
    int index = material_desc_find(d->materials, d->num_materials, item->valuestring);
    if (index < 0)
        return json_fail(p, ERR_JSON_VALUE, key, "unknown material \"%s\" (not in \"materials\")",
                         item->valuestring);
    o->material = (uint32_t)index;
    return true;
}

/* An object naming a mesh of an imported scene (scene/scene_import.h) by its "mesh" key: the mesh
 * is in memory, keyed "<file>#<name>" so that objects naming it share it. */
static bool parse_imported_object(JsonParser *p, const cJSON *e, const cJSON *mesh, int i,
                                  bool has_shutter, SceneDesc *d)
{
    char key[64];
    snprintf(key, sizeof key, "objects[%d].mesh", i);
    if (!cJSON_IsString(mesh))
        return json_fail(p, ERR_JSON_TYPE, key, "expected a mesh name (string)");
    int m = imported_scene_find_mesh(&d->imported, mesh->valuestring);
    if (m < 0)
        return json_fail(p, ERR_JSON_VALUE, key,
                         "no mesh named \"%s\" (the key names meshes of imported scene files)",
                         mesh->valuestring);
    ObjectOptions options = {0};
    ObjectTransform transform = {0};
    if (!parse_object_options(p, e, i, d, &options) ||
        !object_transform_from_json(p, e, i, has_shutter, &transform))
        return false;
    if (!scene_desc_reserve_objects(d, 1))
        return json_fail(p, ERR_TOO_LARGE, "objects", "out of memory");
    int k = d->num_objects;
    int n = snprintf(d->objects[k], sizeof d->objects[k], "%s#%s", d->path, mesh->valuestring);
    if (n < 0 || (size_t)n >= sizeof d->objects[k])
        return json_fail(p, ERR_TOO_LARGE, key, "file and mesh name too long");
    d->object_formats[k] = MESH_IMPORTED;
    d->object_options[k] = options;
    d->object_transforms[k] = transform;
    d->object_meshes[k] = &d->imported.meshes[m].mesh;
    d->num_objects = k + 1;
    return true;
}

static bool parse_objects(JsonParser *p, const cJSON *array, SceneDesc *d)
{
    static const char *const keys[] = {"obj",       "ply",           "gltf", "mesh", "material",
                                       "smooth",    "transform",     "transform_end",
                                       "interior",  "exterior",      NULL};
    if (!array)
        return json_fail(p, ERR_JSON_VALUE, "objects", "empty: the scene needs at least one object");
    if (!cJSON_IsArray(array))
        return json_fail(p, ERR_JSON_TYPE, "objects", "expected an array of objects");
    int count = cJSON_GetArraySize(array);
    if (count == 0)
        return json_fail(p, ERR_JSON_VALUE, "objects", "empty: the scene needs at least one object");
    d->objects = calloc((size_t)count, sizeof *d->objects);
    d->object_formats = calloc((size_t)count, sizeof *d->object_formats);
    d->object_options = calloc((size_t)count, sizeof *d->object_options);
    d->object_transforms = calloc((size_t)count, sizeof *d->object_transforms);
    if (!d->objects || !d->object_formats || !d->object_options || !d->object_transforms)
        return json_fail(p, ERR_TOO_LARGE, "objects", "out of memory");
    /* The camera is read before the objects: a transform_end needs its shutter interval. */
    bool has_shutter = d->camera.shutter_close > d->camera.shutter_open;
    int i = 0;
    for (const cJSON *e = array->child; e; e = e->next, i++) {
        char key[64];
        snprintf(key, sizeof key, "objects[%d]", i);
        if (!json_check_object(p, e, key, keys))
            return false;
        /* Exactly one of "obj", "ply" and "gltf" names the mesh; the key, not the extension,
         * says how to read it. */
        const cJSON *obj = json_member(e, "obj"), *ply = json_member(e, "ply"),
                    *gltf = json_member(e, "gltf"), *mesh = json_member(e, "mesh");
        if (!!obj + !!ply + !!gltf + !!mesh > 1) {
            const char *named[4], **n = named;
            if (obj)
                *n++ = "obj";
            if (ply)
                *n++ = "ply";
            if (gltf)
                *n++ = "gltf";
            if (mesh)
                *n++ = "mesh";
            return json_fail(p, ERR_JSON_VALUE, key, "has both \"%s\" and \"%s\" (give one)",
                             named[0], named[1]);
        }
        if (mesh) {
            if (!parse_imported_object(p, e, mesh, i, has_shutter, d))
                return false;
            continue;
        }
        if (!obj && !ply && !gltf) {
            snprintf(key, sizeof key, "objects[%d].obj", i);
            return json_fail(p, ERR_JSON_VALUE, key, "missing (or \"ply\", \"gltf\": the mesh file)");
        }
        const char *format = gltf ? "gltf" : ply ? "ply" : "obj";
        obj = gltf ? gltf : ply ? ply : obj;
        snprintf(key, sizeof key, "objects[%d].%s", i, format);
        if (!cJSON_IsString(obj))
            return json_fail(p, ERR_JSON_TYPE, key, "expected a file name (string)");
        if (!obj->valuestring[0])
            return json_fail(p, ERR_JSON_VALUE, key, "empty file name");
        /* A glTF expands into one object per placed primitive (scene/gltf_scene.h): the
         * description's objects then outnumber the JSON's, so slot k may differ from i. */
        int k = d->num_objects;
        char file[1024];
        ObjectOptions options = {0};
        ObjectTransform transform = {0};
        if (!json_path_resolve(p, key, obj->valuestring, file) ||
            !parse_object_options(p, e, i, d, &options) ||
            !object_transform_from_json(p, e, i, has_shutter, &transform))
            return false;
        if (gltf) {
            if (!gltf_scene_add(d, file, &options, &transform, i, p->err))
                return false;
            continue;
        }
        if (d->object_meshes && !scene_desc_reserve_objects(d, 1))
            return json_fail(p, ERR_TOO_LARGE, "objects", "out of memory");
        memcpy(d->objects[k], file, sizeof file);
        d->object_formats[k] = ply ? MESH_PLY : MESH_OBJ;
        d->object_options[k] = options;
        d->object_transforms[k] = transform;
        if (d->object_meshes)
            d->object_meshes[k] = NULL;
        d->num_objects = k + 1;
    }
    return true;
}

static bool parse_background(JsonParser *p, const cJSON *item, float background[3])
{
    if (!json_read_vec3(p, item, "background", background))
        return false;
    for (int i = 0; i < 3; i++)
        if (background[i] < 0.0f)
            return json_fail(p, ERR_JSON_VALUE, "background", "[%g, %g, %g] has a negative radiance",
                             background[0], background[1], background[2]);
    return true;
}

static bool parse_environment(JsonParser *p, const cJSON *obj, SceneDesc *d)
{
    static const char *const keys[] = {"file", "scale", "rotation", NULL};
    if (!json_check_object(p, obj, "environment", keys))
        return false;
    const cJSON *file = json_member(obj, "file"), *item;
    if (!file)
        return json_fail(p, ERR_JSON_VALUE, "environment.file", "missing");
    if (!cJSON_IsString(file))
        return json_fail(p, ERR_JSON_TYPE, "environment.file", "expected a file name (string)");
    if (!file->valuestring[0])
        return json_fail(p, ERR_JSON_VALUE, "environment.file", "empty file name");
    if (!json_path_resolve(p, "environment.file", file->valuestring, d->environment))
        return false;
    if ((item = json_member(obj, "scale"))) {
        if (!json_read_float(p, item, "environment.scale", &d->environment_scale))
            return false;
        /* At most 1e9 (a sun-lit sky in physical units is about 1e5): 1e39 became inf in float
         * and a black image; the map's luminance sums must stay finite. */
        if (!(d->environment_scale >= 0.0f) || !(d->environment_scale <= 1e9f))
            return json_fail(p, ERR_JSON_VALUE, "environment.scale", "%g must be in [0, 1e9]",
                             d->environment_scale);
    }
    return !(item = json_member(obj, "rotation")) ||
           json_read_float(p, item, "environment.rotation", &d->environment_rotation);
}

/* The scene's camera: camera_json.c's keys (shared with --camera, which has no media to name)
 * and "medium", read here against the scene's media. */
static bool parse_camera(JsonParser *p, const cJSON *obj, SceneDesc *d)
{
    const cJSON *medium = cJSON_IsObject(obj) ? json_member(obj, "medium") : NULL;
    if (!medium)
        return camera_desc_from_json(p, obj, "camera", true, &d->camera);
    if (!media_read_slot(p, medium, "camera.medium", d->media, d->num_media, &d->camera_medium))
        return false;
    cJSON *rest = cJSON_Duplicate(obj, true);
    if (!rest)
        return json_fail(p, ERR_TOO_LARGE, "camera", "out of memory");
    cJSON_DeleteItemFromObjectCaseSensitive(rest, "medium");
    bool ok = camera_desc_from_json(p, rest, "camera", true, &d->camera);
    cJSON_Delete(rest);
    return ok;
}

/* The black holes' geodesic integrator does not track media (DESIGN "Media"): a scene with both is
 * refused rather than rendered as if the media were not there. */
static bool check_black_holes_without_media(JsonParser *p, const SceneDesc *d)
{
    if (d->num_black_holes == 0)
        return true;
    if (d->num_media > 0)
        return json_fail(p, ERR_JSON_VALUE, "black_holes",
                         "not rendered together with media (\"media\" defines %d; remove one or "
                         "the other)", d->num_media);
    for (int i = 0; i < d->num_materials; i++)
        if (d->materials[i].m.subsurface > 0.0f)
            return json_fail(p, ERR_JSON_VALUE, "black_holes",
                             "not rendered together with media (materials.%s.subsurface is one)",
                             d->materials[i].name);
    return true;
}

bool scene_json_read(JsonParser *p, const cJSON *root, SceneDesc *d)
{
    static const char *const keys[] = {"camera",      "film",   "render",   "objects",   "background",
                                       "environment", "lights", "textures", "materials",
                                       "black_holes", "media",  "medium",   NULL};
    if (!json_check_object(p, root, "", keys))
        return false;
    const cJSON *item;
    /* Media before the camera and the objects, which name them. */
    if ((item = json_member(root, "media")) && !media_from_json(p, item, &d->media, &d->num_media))
        return false;
    if (!media_read_slot(p, json_member(root, "medium"), "medium", d->media, d->num_media,
                         &d->world_medium))
        return false;
    d->camera_given = (item = json_member(root, "camera")) != NULL;
    if (item && !parse_camera(p, item, d))
        return false;
    if ((item = json_member(root, "film")) && !parse_film(p, item, d))
        return false;
    if ((item = json_member(root, "render")) && !parse_render(p, item, d))
        return false;
    if ((item = json_member(root, "background")) && !parse_background(p, item, d->background))
        return false;
    if ((item = json_member(root, "environment")) && !parse_environment(p, item, d))
        return false;
    if ((item = json_member(root, "lights")) &&
        !analytic_lights_from_json(p, item, &d->lights, &d->num_lights))
        return false;
    /* Black holes after the camera, which must not be inside a horizon. */
    if ((item = json_member(root, "black_holes")) &&
        (!black_holes_from_json(p, item, &d->black_holes, &d->num_black_holes) ||
         (d->camera_given &&
          !black_holes_check_camera(p, d->black_holes, d->num_black_holes, d->camera.eye))))
        return false;
    /* Textures before the materials that name them, materials before the objects that do. */
    if ((item = json_member(root, "textures")) &&
        !textures_from_json(p, item, &d->textures, &d->num_textures))
        return false;
    if ((item = json_member(root, "materials")) &&
        !materials_from_json(p, item, d->textures, d->num_textures, &d->materials, &d->num_materials))
        return false;
    if (!check_black_holes_without_media(p, d))
        return false;
    /* A sky alone (an environment, or a background that is not black) is a scene without
     * objects: it renders the sky (scene.c gives it a placeholder that no ray hits). */
    const cJSON *objects = json_member(root, "objects");
    bool sky = d->environment[0] || d->background[0] > 0.0f || d->background[1] > 0.0f ||
               d->background[2] > 0.0f;
    if (sky && (!objects || (cJSON_IsArray(objects) && cJSON_GetArraySize(objects) == 0)))
        return true;
    return parse_objects(p, objects, d);
}
