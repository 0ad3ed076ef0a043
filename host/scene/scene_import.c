// SPDX-License-Identifier: MIT
/* scene_import.c: the in-memory meshes of an imported scene (scene/scene_import.h). */
#include "scene/scene_import.h"

#include <stdlib.h>
#include <string.h>

static unsigned name_hash(const char *name)
{
    unsigned h = 2166136261u; /* FNV-1a */
    for (const unsigned char *c = (const unsigned char *)name; *c; c++)
        h = (h ^ *c) * 16777619u;
    return h;
}

/* The slot of name in the index: where it is, or the empty slot where it would go. */
static int index_slot(const ImportedScene *s, const char *name)
{
    unsigned mask = (unsigned)s->name_index_size - 1u, slot = name_hash(name) & mask;
    while (s->name_index[slot] >= 0 && strcmp(s->meshes[s->name_index[slot]].name, name) != 0)
        slot = (slot + 1u) & mask;
    return (int)slot;
}

int imported_scene_find_mesh(const ImportedScene *s, const char *name)
{
    if (!s->name_index)
        return -1;
    return s->name_index[index_slot(s, name)];
}

/* Keeps the index at most half full: rebuilt twice as large when it would be fuller. */
static bool index_reserve(ImportedScene *s)
{
    if (2 * (s->num_meshes + 1) <= s->name_index_size)
        return true;
    int size = s->name_index_size ? 2 * s->name_index_size : 64;
    int *index = malloc((size_t)size * sizeof *index);
    if (!index)
        return false;
    free(s->name_index);
    s->name_index = index;
    s->name_index_size = size;
    for (int i = 0; i < size; i++)
        index[i] = -1;
    for (int i = 0; i < s->num_meshes; i++)
        index[index_slot(s, s->meshes[i].name)] = i;
    return true;
}

bool imported_scene_add_mesh(ImportedScene *s, const char *name, Mesh *mesh, Error *err)
{
    if (strlen(name) >= SCENE_NAME_LIMIT) {
        error_set(err, ERR_TOO_LARGE, "", 0, "mesh name \"%.40s...\" is too long", name);
    } else if (imported_scene_find_mesh(s, name) >= 0) {
        error_set(err, ERR_JSON_VALUE, "", 0, "two meshes named \"%s\"", name);
    } else {
        /* Capacity doubles at powers of two: a scene of many shapes (pbrt, Mitsuba) adds them one
         * by one, and growing by one copied the array each time (quadratic). */
        size_t n = (size_t)s->num_meshes, capacity = n < 8 ? 8 : (n & (n - 1)) == 0 ? 2 * n : n + 1;
        bool full = n < 8 ? n == 0 : (n & (n - 1)) == 0;
        ImportedMesh *grown = full ? realloc(s->meshes, capacity * sizeof *grown) : s->meshes;
        if (grown)
            s->meshes = grown;
        if (grown && index_reserve(s)) {
            ImportedMesh *m = &s->meshes[s->num_meshes];
            memset(m, 0, sizeof *m);
            strcpy(m->name, name);
            s->name_index[index_slot(s, name)] = s->num_meshes++;
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
    free(s->name_index);
    memset(s, 0, sizeof *s);
}
