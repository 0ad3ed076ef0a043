// SPDX-License-Identifier: MIT
/* scene_import.c: the in-memory meshes of an imported scene (scene/scene_import.h). */
#include "scene/scene_import.h"

#include <stdlib.h>
#include <string.h>

int imported_scene_find_mesh(const ImportedScene *s, const char *name)
{
    for (int i = 0; i < s->num_meshes; i++)
        if (strcmp(s->meshes[i].name, name) == 0)
            return i;
    return -1;
}

bool imported_scene_add_mesh(ImportedScene *s, const char *name, Mesh *mesh, Error *err)
{
    if (strlen(name) >= SCENE_NAME_LIMIT) {
        error_set(err, ERR_TOO_LARGE, "", 0, "mesh name \"%.40s...\" is too long", name);
    } else if (imported_scene_find_mesh(s, name) >= 0) {
        error_set(err, ERR_JSON_VALUE, "", 0, "two meshes named \"%s\"", name);
    } else {
        ImportedMesh *grown = realloc(s->meshes, (size_t)(s->num_meshes + 1) * sizeof *grown);
        if (grown) {
            s->meshes = grown;
            ImportedMesh *m = &s->meshes[s->num_meshes++];
            memset(m, 0, sizeof *m);
            strcpy(m->name, name);
            m->mesh = *mesh;
            memset(mesh, 0, sizeof *mesh);
            return true;
        }
        error_set(err, ERR_OUT_OF_MEMORY, "", 0, "out of memory for mesh \"%s\"", name);
    }
    mesh_free(mesh);
    return false;
}

void imported_scene_free(ImportedScene *s)
{
    cJSON_Delete(s->root);
    for (int i = 0; i < s->num_meshes; i++)
        mesh_free(&s->meshes[i].mesh);
    free(s->meshes);
    memset(s, 0, sizeof *s);
}
