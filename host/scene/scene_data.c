// SPDX-License-Identifier: MIT
#include "scene/scene_data.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/fs.h"
#include "scene/vertex_normals.h"

/* Triangles that use the default material carry this id until scene_data_finish appends the one
 * default material of the scene and patches them. */
#define DEFAULT_MATERIAL_PENDING 0xffffffffu

void scene_data_init(SceneData *data)
{
    memset(data, 0, sizeof *data);
}

void scene_data_free(SceneData *data)
{
    free(data->positions);
    free(data->normals);
    free(data->uvs);
    free(data->triangles);
    free(data->material_ids);
    free(data->materials);
    texture_set_free(&data->textures);
    environment_free(&data->environment);
    free(data->emissive_triangles);
    free(data->analytic_lights);
    free(data->meshes);
    free(data->instances);
    free(data->media);
    free(data->grid_bricks);
    free(data->grid_values);
    free(data->grid_majorants);
    memset(data, 0, sizeof *data);
}

/* ---- Vertex unification --------------------------------------------------------------------- */

/* Open-addressing hash map from a corner's (position, texcoord, normal) indices to its unified
 * vertex. Sized to at least twice the corner count, so probes stay short; slot.vertex 0 = empty. */
typedef struct {
    int32_t p, t, n;
    uint32_t vertex; /* unified index + 1 */
} CornerSlot;

typedef struct {
    CornerSlot *slots;
    size_t mask;
} CornerMap;

static bool corner_map_init(CornerMap *map, size_t corners)
{
    size_t size = 16;
    while (size < 2 * corners)
        size *= 2;
    map->slots = calloc(size, sizeof *map->slots);
    map->mask = size - 1;
    return map->slots != NULL;
}

static size_t corner_hash(int32_t p, int32_t t, int32_t n)
{
    uint64_t h = (uint64_t)(uint32_t)p * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t)(uint32_t)t * 0xC2B2AE3D27D4EB4Full;
    h ^= (uint64_t)(uint32_t)n * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    return (size_t)h;
}

/* Returns the slot for the key: either holding it, or empty (where it goes). */
static CornerSlot *corner_map_find(CornerMap *map, const int32_t key[3])
{
    size_t i = corner_hash(key[0], key[1], key[2]) & map->mask;
    for (;;) {
        CornerSlot *s = &map->slots[i];
        if (!s->vertex || (s->p == key[0] && s->t == key[1] && s->n == key[2]))
            return s;
        i = (i + 1) & map->mask;
    }
}

size_t scene_data_grown_capacity(size_t capacity, size_t needed)
{
    if (needed <= capacity)
        return capacity;
    return needed > 2 * capacity ? needed : 2 * capacity;
}

static bool grow(void **array, size_t count, size_t element_size)
{
    void *grown = realloc(*array, (count ? count : 1) * element_size);
    if (grown)
        *array = grown;
    return grown != NULL;
}

/* Checks one corner's indices against the mesh (obj_load already does; this guards the flattener). */
static bool corner_valid(const Mesh *mesh, const int32_t c[3])
{
    return c[0] >= 0 && (size_t)c[0] < mesh->num_positions && c[1] < (int64_t)mesh->num_texcoords &&
           c[2] < (int64_t)mesh->num_normals;
}

/* Whether every corner's texcoord and normal index is its position index (or every one absent),
 * as in glTF and PLY meshes: then the position alone keys a unified vertex. */
static bool keyed_by_position(const Mesh *mesh)
{
    size_t corners = 3 * mesh->num_triangles;
    if (corners == 0)
        return false;
    const int32_t *c = mesh->corners;
    bool t_same = c[1] == c[0], n_same = c[2] == c[0];
    if ((!t_same && c[1] != -1) || (!n_same && c[2] != -1))
        return false;
    for (size_t i = 0; i < corners; i++, c += 3)
        if (c[1] != (t_same ? c[0] : -1) || c[2] != (n_same ? c[0] : -1))
            return false;
    return true;
}

/* Writes the mesh's triangles (vertex indices offset by the vertices already present) and records,
 * for each new unified vertex, the corner that first used it. A mesh keyed by position uses an
 * array over positions instead of the hash map: the same vertices in the same order, 3x faster
 * on a 1M-triangle glTF. */
static bool unify_corners(SceneData *data, const Mesh *mesh, const char *mesh_path,
                          const uint32_t *mesh_to_scene, uint32_t object_material,
                          uint32_t *first_corner, uint32_t *num_new, Error *err)
{
    CornerMap map = {NULL, 0};
    bool direct = keyed_by_position(mesh);
    uint32_t *by_position = direct ? calloc(mesh->num_positions ? mesh->num_positions : 1,
                                            sizeof *by_position) : NULL;
    if (direct ? !by_position : !corner_map_init(&map, 3 * mesh->num_triangles)) {
        error_set(err, ERR_TOO_LARGE, mesh_path, 0, "%s: out of memory", mesh_path);
        return false;
    }
    uint32_t base = data->num_vertices, count = 0;
    for (size_t tri = 0; tri < mesh->num_triangles; tri++) {
        uint32_t v[3], flags = TRIANGLE_HAS_NORMALS | TRIANGLE_HAS_UVS;
        for (int k = 0; k < 3; k++) {
            const int32_t *key = &mesh->corners[9 * tri + 3 * k];
            if (!corner_valid(mesh, key)) {
                free(by_position);
                free(map.slots);
                error_set(err, ERR_OBJ_INDEX, mesh_path, 0, "%s: triangle %zu has an index out of range",
                          mesh_path, tri);
                return false;
            }
            uint32_t *vertex = direct ? &by_position[key[0]] : NULL;
            if (!direct) {
                CornerSlot *slot = corner_map_find(&map, key);
                if (!slot->vertex)
                    *slot = (CornerSlot){key[0], key[1], key[2], 0};
                vertex = &slot->vertex;
            }
            if (!*vertex) {
                *vertex = ++count;
                first_corner[count - 1] = (uint32_t)(3 * tri + (size_t)k);
            }
            v[k] = base + *vertex - 1;
            if (key[1] < 0)
                flags &= ~TRIANGLE_HAS_UVS;
            if (key[2] < 0)
                flags &= ~TRIANGLE_HAS_NORMALS;
        }
        size_t t = data->num_triangles + tri;
        data->triangles[t].v = (uint4){{v[0], v[1], v[2], flags}};
        int32_t m = mesh->material_ids[tri];
        bool has_material = m >= 0 && (size_t)m < mesh->num_materials;
        data->material_ids[t] = object_material != NO_MATERIAL ? object_material
                                : has_material               ? mesh_to_scene[m]
                                                             : DEFAULT_MATERIAL_PENDING;
    }
    free(by_position);
    free(map.slots);
    *num_new = count;
    return true;
}

/* Fills the new vertices' attributes from the corners that created them. Returns false (error set)
 * for a non-finite position. Normals that are non-finite or zero are stored as zero, and clear
 * *normals_ok so the caller drops TRIANGLE_HAS_NORMALS where they are used. */
static bool fill_vertices(SceneData *data, const Mesh *mesh, const char *mesh_path,
                          const uint32_t *first_corner, uint32_t num_new, bool *normals_ok, Error *err)
{
    *normals_ok = true;
    for (uint32_t i = 0; i < num_new; i++) {
        const int32_t *c = &mesh->corners[3 * (size_t)first_corner[i]];
        const float *p = &mesh->positions[3 * (size_t)c[0]];
        if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
            error_set(err, ERR_OBJ_NONFINITE, mesh_path, 0, "%s: vertex %d is not finite", mesh_path,
                      c[0] + 1);
            return false;
        }
        uint32_t v = data->num_vertices + i;
        data->positions[v] = (float4){{p[0], p[1], p[2], 0.0f}};
        float4 normal = {{0.0f, 0.0f, 0.0f, 0.0f}};
        if (c[2] >= 0) {
            const float *n = &mesh->normals[3 * (size_t)c[2]];
            float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
            if (isfinite(len2) && len2 > 0.0f)
                normal = (float4){{n[0], n[1], n[2], 0.0f}};
            else
                *normals_ok = false;
        }
        data->normals[v] = normal;
        float2 uv = {{0.0f, 0.0f}};
        if (c[1] >= 0) {
            const float *t = &mesh->texcoords[2 * (size_t)c[1]];
            if (isfinite(t[0]) && isfinite(t[1]))
                uv = (float2){{t[0], t[1]}};
        }
        data->uvs[v] = uv;
    }
    return true;
}

static bool is_zero(float4 v) { return v.s[0] == 0.0f && v.s[1] == 0.0f && v.s[2] == 0.0f; }

/* A corner whose normal was unusable has a zero normal: shade those triangles flat. */
static void drop_bad_normals(SceneData *data, uint32_t first_triangle)
{
    for (uint32_t t = first_triangle; t < data->num_triangles; t++) {
        uint4 *v = &data->triangles[t].v;
        if (is_zero(data->normals[v->s[0]]) || is_zero(data->normals[v->s[1]]) ||
            is_zero(data->normals[v->s[2]]))
            v->s[3] &= ~TRIANGLE_HAS_NORMALS;
    }
}

/* Remembers why the first OBJ without triangles has none, for scene_data_finish's message. */
static void note_faceless(SceneData *data, const Mesh *mesh, const char *mesh_path)
{
    if (mesh->num_triangles > 0 || data->faceless_mesh[0])
        return;
    struct stat st;
    snprintf(data->faceless_mesh, sizeof data->faceless_mesh, "%s", mesh_path);
    if (mesh->num_faces > 0)
        snprintf(data->faceless_reason, sizeof data->faceless_reason,
                 "all %zu faces are degenerate", mesh->num_faces);
    else if (stat(mesh_path, &st) == 0 && st.st_size == 0)
        snprintf(data->faceless_reason, sizeof data->faceless_reason, "the file is empty");
    else if (fs_has_suffix(mesh_path, ".ply") && mesh->num_positions) /* PLY's words, not OBJ's */
        snprintf(data->faceless_reason, sizeof data->faceless_reason, "a point cloud: %zu vertices "
                 "and no face or tristrips element; pt renders triangles", mesh->num_positions);
    else if (fs_has_suffix(mesh_path, ".ply"))
        snprintf(data->faceless_reason, sizeof data->faceless_reason, "no vertices and no faces");
    else if (mesh->num_positions == 0)
        snprintf(data->faceless_reason, sizeof data->faceless_reason, "no 'v' or 'f' records");
    else
        snprintf(data->faceless_reason, sizeof data->faceless_reason,
                 "'v' records but no 'f' records");
}

bool scene_data_append_mesh(SceneData *data, const Mesh *mesh, const char *mesh_path, Error *err)
{
    ObjectOptions defaults = {.material = NO_MATERIAL};
    return scene_data_append_object(data, mesh, mesh_path, &defaults, NULL, err);
}

bool scene_data_append_object(SceneData *data, const Mesh *mesh, const char *mesh_path,
                              const ObjectOptions *options, const NamedMaterials *named, Error *err)
{
    note_faceless(data, mesh, mesh_path);
    /* Every corner may become a vertex: both counts must stay below 2^32 - 1 for uint indices. */
    size_t max_new_vertices = 3 * mesh->num_triangles;
    if (mesh->num_triangles > UINT32_MAX - 1 - (size_t)data->num_triangles ||
        max_new_vertices > UINT32_MAX - 1 - (size_t)data->num_vertices) {
        error_set(err, ERR_TOO_LARGE, mesh_path, 0, "%s: %zu triangles exceed the 2^32 limit",
                  mesh_path, mesh->num_triangles);
        return false;
    }
    /* An object given one material does not load its MTL materials (nor their textures). */
    uint32_t *mesh_to_scene = calloc(mesh->num_materials ? mesh->num_materials : 1, sizeof(uint32_t));
    if (!mesh_to_scene) {
        error_set(err, ERR_TOO_LARGE, mesh_path, 0, "%s: out of memory", mesh_path);
        return false;
    }
    if (options->material == NO_MATERIAL &&
        !materials_append_obj(&data->materials, &data->num_materials, &data->textures, mesh,
                              mesh_path, named, mesh_to_scene, err)) {
        free(mesh_to_scene);
        return false;
    }
    size_t num_triangles = data->num_triangles + mesh->num_triangles;
    uint32_t *first_corner = malloc((max_new_vertices ? max_new_vertices : 1) * sizeof *first_corner);
    size_t triangle_capacity = scene_data_grown_capacity(data->triangle_capacity, num_triangles);
    if (!first_corner || (triangle_capacity != data->triangle_capacity &&
                          (!grow((void **)&data->triangles, triangle_capacity, sizeof(Triangle)) ||
                           !grow((void **)&data->material_ids, triangle_capacity, sizeof(uint32_t))))) {
        free(first_corner);
        free(mesh_to_scene);
        error_set(err, ERR_TOO_LARGE, mesh_path, 0, "%s: out of memory", mesh_path);
        return false;
    }
    data->triangle_capacity = triangle_capacity;
    uint32_t num_new = 0;
    bool normals_ok = true;
    bool ok = unify_corners(data, mesh, mesh_path, mesh_to_scene, options->material, first_corner,
                            &num_new, err);
    free(mesh_to_scene);
    size_t num_vertices = (size_t)data->num_vertices + num_new;
    size_t vertex_capacity = scene_data_grown_capacity(data->vertex_capacity, num_vertices);
    if (ok && vertex_capacity != data->vertex_capacity &&
        !(grow((void **)&data->positions, vertex_capacity, sizeof(float4)) &&
          grow((void **)&data->normals, vertex_capacity, sizeof(float4)) &&
          grow((void **)&data->uvs, vertex_capacity, sizeof(float2)))) {
        error_set(err, ERR_TOO_LARGE, mesh_path, 0, "%s: out of memory", mesh_path);
        ok = false;
    }
    if (ok)
        data->vertex_capacity = vertex_capacity;
    ok = ok && fill_vertices(data, mesh, mesh_path, first_corner, num_new, &normals_ok, err);
    uint32_t first_triangle = data->num_triangles, first_vertex = data->num_vertices;
    if (ok) {
        data->num_vertices = (uint32_t)num_vertices;
        data->num_triangles = (uint32_t)num_triangles;
        if (!normals_ok)
            drop_bad_normals(data, first_triangle);
        ok = !options->smooth ||
             vertex_normals_smooth(mesh, data->positions, data->normals, data->triangles,
                                   first_triangle, data->num_triangles, first_vertex, first_corner,
                                   err);
    }
    free(first_corner);
    return ok;
}

/* ---- Finishing ------------------------------------------------------------------------------ */

/* Appends the default material once if any triangle needs it, and points those triangles at it. */
static bool resolve_default_material(SceneData *data, Error *err)
{
    uint32_t index = data->num_materials;
    bool needed = false;
    for (uint32_t t = 0; t < data->num_triangles; t++) {
        if (data->material_ids[t] == DEFAULT_MATERIAL_PENDING) {
            data->material_ids[t] = index;
            needed = true;
        }
    }
    if (!needed)
        return true;
    if (!grow((void **)&data->materials, (size_t)index + 1, sizeof(Material))) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for materials");
        return false;
    }
    data->materials[data->num_materials++] = material_default();
    return true;
}

static float triangle_area2(const SceneData *data, const Triangle *tri)
{
    const float *a = data->positions[tri->v.s[0]].s, *b = data->positions[tri->v.s[1]].s,
                *c = data->positions[tri->v.s[2]].s;
    float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                  e1[0] * e2[1] - e1[1] * e2[0]};
    return n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
}

/* Lights are the triangles whose material emits. Zero-area ones are left out: they emit nothing and
 * would make an area pdf infinite. */
static bool build_emissive_table(SceneData *data, Error *err)
{
    uint32_t count = 0;
    for (uint32_t t = 0; t < data->num_triangles; t++)
        if (data->materials[data->material_ids[t]].emission.s[3] > 0.0f &&
            triangle_area2(data, &data->triangles[t]) > 0.0f)
            count++;
    free(data->emissive_triangles);
    data->emissive_triangles = malloc((count ? count : 1) * sizeof(uint32_t));
    if (!data->emissive_triangles) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for the light table");
        return false;
    }
    data->num_emissive = 0;
    for (uint32_t t = 0; t < data->num_triangles; t++)
        if (data->materials[data->material_ids[t]].emission.s[3] > 0.0f &&
            triangle_area2(data, &data->triangles[t]) > 0.0f)
            data->emissive_triangles[data->num_emissive++] = t;
    return true;
}

bool scene_data_finish(SceneData *data, const char *scene_path, Error *err)
{
    if (data->num_triangles == 0) {
        if (!data->faceless_mesh[0])
            error_set(err, ERR_NO_TRIANGLES, scene_path, 0, "%s: the scene has no triangles",
                      scene_path);
        else if (strcmp(data->faceless_mesh, scene_path) == 0)
            error_set(err, ERR_NO_TRIANGLES, scene_path, 0,
                      "%s: no faces (%s): the scene has no triangles", scene_path,
                      data->faceless_reason);
        else
            error_set(err, ERR_NO_TRIANGLES, scene_path, 0,
                      "%s: the scene has no triangles (%s: no faces, %s)", scene_path,
                      data->faceless_mesh, data->faceless_reason);
        return false;
    }
    if (!resolve_default_material(data, err) || !build_emissive_table(data, err))
        return false;
    /* A scene built by appending objects alone (bare OBJs, the tests) is one world-space mesh. */
    if (data->num_meshes == 0 && !scene_data_add_mesh(data, 0, 0, err))
        return false;
    if (data->num_instances == 0) {
        SceneInstance whole = {.mesh = 0, .object = -1, .to_world = affine_identity()};
        if (!scene_data_add_instance(data, &whole, err))
            return false;
    }
    scene_data_finish_instances(data);
    return true;
}
