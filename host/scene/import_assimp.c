// SPDX-License-Identifier: MIT
/* import_assimp.c: an Assimp-read file as a pt JSON scene plus meshes (scene/import_assimp.h). */
#include "scene/import_assimp.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/assimp_reader.h"
#include "scene/import_json.h"

#define FILM_WIDTH 640

/* The format's name for messages, from the extension. */
static const char *format_name(const char *path)
{
    const char *dot = strrchr(path, '.');
    static char upper[16];
    size_t n = 0;
    for (const char *s = dot ? dot + 1 : ""; *s && n + 1 < sizeof upper; s++)
        upper[n++] = (char)(*s >= 'a' && *s <= 'z' ? *s - 'a' + 'A' : *s);
    upper[n] = '\0';
    return n ? upper : "3-D";
}

static cJSON *light_json(const AssimpLight *l)
{
    cJSON *j = cJSON_CreateObject();
    if (!j)
        return NULL;
    if (l->type == ASSIMP_LIGHT_DIRECTIONAL) {
        cJSON_AddStringToObject(j, "type", "directional");
        cJSON_AddItemToObject(j, "direction", import_json_vec3(l->direction));
        cJSON_AddItemToObject(j, "irradiance", import_json_colour(l->color));
        return j;
    }
    cJSON_AddStringToObject(j, "type", l->type == ASSIMP_LIGHT_SPOT ? "spot" : "point");
    cJSON_AddItemToObject(j, "position", import_json_vec3(l->position));
    cJSON_AddItemToObject(j, "intensity", import_json_colour(l->color));
    if (l->type == ASSIMP_LIGHT_SPOT) {
        cJSON_AddItemToObject(j, "direction", import_json_vec3(l->direction));
        cJSON_AddNumberToObject(j, "cone_angle", l->cone_angle);
        cJSON_AddNumberToObject(j, "falloff_angle", l->falloff_angle);
    }
    return j;
}

static bool build(const char *path, AssimpScene *s, ImportedScene *out, Error *err)
{
    cJSON *root = out->root = cJSON_CreateObject();
    cJSON *objects = cJSON_AddArrayToObject(root, "objects");
    if (!root || !objects)
        goto out_of_memory;
    ImportBounds bounds = {0};
    for (int i = 0; i < s->num_meshes; i++) {
        char name[SCENE_NAME_LIMIT];
        snprintf(name, sizeof name, "mesh%d", i);
        bool used = false;
        for (int k = 0; k < s->num_instances && !used; k++)
            used = s->instances[k].mesh == i;
        if (used && s->meshes[i].num_triangles > 0 &&
            !imported_scene_add_mesh(out, name, &s->meshes[i], err))
            return false;
    }
    for (int k = 0; k < s->num_instances; k++) {
        char name[SCENE_NAME_LIMIT];
        snprintf(name, sizeof name, "mesh%d", s->instances[k].mesh);
        int m = imported_scene_find_mesh(out, name);
        if (m < 0)
            continue; /* a mesh of points or lines only */
        cJSON *o = cJSON_CreateObject();
        if (!o)
            goto out_of_memory;
        cJSON_AddStringToObject(o, "mesh", name);
        cJSON_AddItemToObject(o, "transform", import_json_matrix_transform(s->instances[k].world));
        cJSON_AddItemToArray(objects, o);
        import_bounds_add_mesh(&bounds, &out->meshes[m].mesh, s->instances[k].world);
    }
    if (s->num_lights > 0) {
        cJSON *lights = cJSON_AddArrayToObject(root, "lights");
        for (int i = 0; lights && i < s->num_lights; i++)
            cJSON_AddItemToArray(lights, light_json(&s->lights[i]));
    }
    cJSON *camera;
    if (s->has_camera) {
        camera = cJSON_CreateObject();
        if (camera) {
            cJSON_AddItemToObject(camera, "eye", import_json_vec3(s->camera.eye));
            cJSON_AddItemToObject(camera, "target", import_json_vec3(s->camera.target));
            cJSON_AddItemToObject(camera, "up", import_json_vec3(s->camera.up));
            cJSON_AddNumberToObject(camera, "fov_y", s->camera.fov_y);
        }
        if (s->camera.aspect > 0) {
            cJSON *film = cJSON_AddObjectToObject(root, "film");
            cJSON_AddNumberToObject(film, "width", FILM_WIDTH);
            cJSON_AddNumberToObject(film, "height", fmax(1.0, round(FILM_WIDTH / s->camera.aspect)));
        }
    } else {
        camera = import_json_framing_camera(&bounds, 40.0);
    }
    if (!camera)
        goto out_of_memory;
    cJSON_AddItemToObject(root, "camera", camera);
    return true;
out_of_memory:
    error_set(err, ERR_OUT_OF_MEMORY, path, 0, "%s: out of memory", path);
    return false;
}

bool import_assimp(const char *path, ImportedScene *out, Error *err)
{
    AssimpScene s;
    if (!assimp_read(path, format_name(path), &s, err))
        return false;
    bool ok = build(path, &s, out, err);
    assimp_scene_free(&s);
    return ok;
}
