// SPDX-License-Identifier: MIT
/* object_media.c: see object_media.h. */
#include "scene/object_media.h"

#include <stdio.h>
#include <stdlib.h>

#include "scene/scene_media.h"

#define DEFAULT_MATERIAL_PENDING 0xffffffffu /* scene_data.c's: the default material, not yet added */

/* ---- Closed surfaces ------------------------------------------------------------------------ */

typedef struct {
    float p[3];
    uint32_t corner;
} WeldCorner;

static int compare_positions(const void *pa, const void *pb)
{
    const WeldCorner *a = pa, *b = pb;
    for (int i = 0; i < 3; i++)
        if (a->p[i] != b->p[i])
            return a->p[i] < b->p[i] ? -1 : 1;
    return 0;
}

static int compare_edges(const void *pa, const void *pb)
{
    const uint64_t *a = pa, *b = pb;
    return *a < *b ? -1 : *a > *b;
}

bool mesh_open_edges(const SceneData *data, uint32_t first, uint32_t end, uint64_t *one_face,
                     uint64_t *many_faces)
{
    *one_face = *many_faces = 0;
    size_t n = end > first ? end - first : 0, corners = 3 * n;
    WeldCorner *weld = malloc((corners ? corners : 1) * sizeof *weld);
    uint32_t *id = malloc((corners ? corners : 1) * sizeof *id);
    uint64_t *edges = malloc((corners ? corners : 1) * sizeof *edges);
    if (!weld || !id || !edges) {
        free(weld), free(id), free(edges);
        return false;
    }
    /* Positions welded by value: a mesh split at its uv or normal seams has two vertices at one
     * position there (scene_data.c unifies corners by position, uv and normal), yet is closed. */
    for (size_t c = 0; c < corners; c++) {
        const float *p = data->positions[data->triangles[first + c / 3].v.s[c % 3]].s;
        weld[c] = (WeldCorner){{p[0], p[1], p[2]}, (uint32_t)c};
    }
    qsort(weld, corners, sizeof *weld, compare_positions);
    uint32_t next = 0;
    for (size_t c = 0; c < corners; c++) {
        if (c > 0 && compare_positions(&weld[c], &weld[c - 1]) != 0)
            next++;
        id[weld[c].corner] = next;
    }
    size_t count = 0;
    for (size_t t = 0; t < n; t++) {
        const uint32_t *v = &id[3 * t];
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
            continue; /* degenerate: no face, whatever its edges */
        for (int k = 0; k < 3; k++) {
            uint64_t a = v[k], b = v[(k + 1) % 3];
            edges[count++] = a < b ? a << 32 | b : b << 32 | a;
        }
    }
    qsort(edges, count, sizeof *edges, compare_edges);
    for (size_t e = 0; e < count;) {
        size_t run = e + 1;
        while (run < count && edges[run] == edges[e])
            run++;
        *one_face += run - e == 1;
        *many_faces += run - e > 2;
        e = run;
    }
    free(weld), free(id), free(edges);
    return true;
}

/* ---- Derived materials ---------------------------------------------------------------------- */

/* Whether material `index` (a mix: any of its leaves) has subsurface: a medium inside. */
static bool holds_subsurface(const SceneData *data, uint32_t index, unsigned depth)
{
    if (index >= data->num_materials || depth > MATERIAL_MIX_DEPTH_LIMIT)
        return false;
    const Material *m = &data->materials[index];
    if (m->type == MATERIAL_MIX)
        return holds_subsurface(data, m->mix_a, depth + 1) ||
               holds_subsurface(data, m->mix_b, depth + 1);
    return m->type == MATERIAL_PRINCIPLED && m->subsurface > 0.0f;
}

static bool append_material(SceneData *data, const Material *m, uint32_t *index, Error *err)
{
    Material *grown = realloc(data->materials, ((size_t)data->num_materials + 1) * sizeof *grown);
    if (!grown) {
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for materials");
        return false;
    }
    data->materials = grown;
    *index = data->num_materials;
    data->materials[data->num_materials++] = *m;
    return true;
}

/* The derived copy of `source` bounding (interior, exterior), made once. */
static bool derive(SceneData *data, DerivedMaterials *derived, uint32_t source, uint32_t interior,
                   uint32_t exterior, uint32_t *out, Error *err)
{
    for (uint32_t i = 0; i < derived->count; i++) {
        const uint32_t *k = derived->keys[i];
        if (k[0] == source && k[1] == interior && k[2] == exterior) {
            *out = k[3];
            return true;
        }
    }
    if (derived->count == derived->capacity) {
        uint32_t capacity = derived->capacity ? 2 * derived->capacity : 8;
        void *grown = realloc(derived->keys, capacity * sizeof *derived->keys);
        if (!grown) {
            error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for materials");
            return false;
        }
        derived->keys = grown;
        derived->capacity = capacity;
    }
    uint32_t asked = interior; /* the key: what objects ask for */
    Material m = source == DEFAULT_MATERIAL_PENDING ? material_default() : data->materials[source];
    /* A dielectric's absorption is its interior medium (scene_data_media_from_absorption, which
     * skips materials that bound media already): given only an exterior, the copy makes it. */
    if (interior == 0 && material_has_absorption(&m) &&
        !(m.flags & MATERIAL_FLAG_MEDIUM_INTERFACE) &&
        !(interior = scene_data_add_absorption_medium(data, &m.absorption, err)))
        return false;
    m.flags |= MATERIAL_FLAG_MEDIUM_INTERFACE;
    m.interior = interior;
    m.exterior = exterior;
    if (!append_material(data, &m, out, err))
        return false;
    uint32_t *k = derived->keys[derived->count++];
    k[0] = source, k[1] = asked, k[2] = exterior, k[3] = *out;
    return true;
}

/* "objects[2]" for messages ("the object" for one that is no JSON object's). */
static void object_name(const ObjectOptions *o, char out[32])
{
    if (o->json_object >= 0)
        snprintf(out, 32, "objects[%d]", o->json_object);
    else
        snprintf(out, 32, "the model");
}

/* Six times the signed volume a closed mesh encloses (the divergence theorem over its triangles):
 * negative when its fronts (counter-clockwise sides) face inward. */
static double signed_volume6(const SceneData *data, uint32_t first, uint32_t end)
{
    double sum = 0.0;
    for (uint32_t t = first; t < end; t++) {
        const float *a = data->positions[data->triangles[t].v.s[0]].s,
                    *b = data->positions[data->triangles[t].v.s[1]].s,
                    *c = data->positions[data->triangles[t].v.s[2]].s;
        sum += (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) -
               (double)a[1] * ((double)b[0] * c[2] - (double)b[2] * c[0]) +
               (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
    }
    return sum;
}

static bool check_closed(const SceneData *data, uint32_t first, const ObjectOptions *o,
                         const char *what, const char *scene_path, Error *err)
{
    uint64_t one = 0, many = 0;
    char name[32];
    object_name(o, name);
    if (!mesh_open_edges(data, first, data->num_triangles, &one, &many)) {
        error_set(err, ERR_OUT_OF_MEMORY, scene_path, 0, "%s: %s: out of memory", scene_path, name);
        return false;
    }
    if (one == 0 && many == 0) {
        /* The interior is behind the fronts (DESIGN "Media"): an inside-out mesh holds its
         * medium everywhere else. Legal, so only said. */
        if (signed_volume6(data, first, data->num_triangles) < 0.0)
            warn("%s: %s%s: the mesh faces inward (its triangles' counter-clockwise fronts point "
                 "inside): its interior medium fills the space around it", scene_path, name, what);
        return true;
    }
    if (one > 0)
        error_set(err, ERR_JSON_VALUE, scene_path, 0,
                  "%s: %s%s: the mesh is not closed (%llu edge%s with one face); a medium needs a "
                  "closed surface", scene_path, name, what, (unsigned long long)one,
                  one == 1 ? "" : "s");
    else
        error_set(err, ERR_JSON_VALUE, scene_path, 0,
                  "%s: %s%s: the mesh is not closed (%llu edge%s shared by more than two faces); a "
                  "medium needs a closed surface", scene_path, name, what,
                  (unsigned long long)many, many == 1 ? "" : "s");
    return false;
}

bool object_media_apply(SceneData *data, uint32_t first_triangle, const ObjectOptions *o,
                        DerivedMaterials *derived, const char *scene_path, Error *err)
{
    char name[32];
    object_name(o, name);
    bool subsurface = false;
    for (uint32_t t = first_triangle; t < data->num_triangles && !subsurface; t++)
        subsurface = holds_subsurface(data, data->material_ids[t], 0);
    /* The same medium on both sides (a floor in a fog-filled world, as Mitsuba scenes say it:
     * Mitsuba has no world medium) changes nothing where it is crossed: any surface will do. */
    uint32_t outside = o->exterior ? o->exterior : data->world_medium;
    if (o->interior && o->interior != outside &&
        !check_closed(data, first_triangle, o, ".interior", scene_path, err))
        return false;
    if (subsurface && !check_closed(data, first_triangle, o, " (a material with subsurface)",
                                    scene_path, err))
        return false;
    if (!o->interior && !o->exterior)
        return true;
    for (uint32_t t = first_triangle; t < data->num_triangles; t++) {
        uint32_t source = data->material_ids[t];
        const Material *m = source == DEFAULT_MATERIAL_PENDING ? NULL : &data->materials[source];
        bool bounds = m && (m->flags & MATERIAL_FLAG_MEDIUM_INTERFACE);
        /* The object's interior replaces no other: a subsurface material's walk medium, or a
         * dielectric's absorption (its interior medium), would be silently dropped. */
        if (o->interior && m && (bounds || m->subsurface > 0.0f || material_has_absorption(m))) {
            error_set(err, ERR_JSON_VALUE, scene_path, 0,
                      "%s: %s.interior: its material already fills the inside (%s); give one or "
                      "the other", scene_path, name,
                      m->subsurface > 0.0f ? "subsurface" : bounds ? "a medium" : "absorption");
            return false;
        }
        uint32_t interior = o->interior ? o->interior : bounds ? m->interior : 0;
        uint32_t exterior = o->exterior ? o->exterior : bounds ? m->exterior : MEDIUM_SLOT_WORLD;
        if (!derive(data, derived, source, interior, exterior, &data->material_ids[t], err))
            return false;
    }
    return true;
}

void derived_materials_free(DerivedMaterials *derived)
{
    free(derived->keys);
    *derived = (DerivedMaterials){0};
}
