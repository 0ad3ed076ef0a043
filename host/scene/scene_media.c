/* SPDX-License-Identifier: MIT */
/* scene_media.c: SceneData's media (scene_media.h). */
#include "scene/scene_media.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Appends the n elements of size `size` at *items to *array (count *count): an empty array takes
 * *items over (and *items becomes NULL: the grid's values are never in memory twice), else it
 * grows; false when out of memory or past 2^32 entries (Medium's offsets are 32-bit). */
static bool append(void **array, size_t *count, void **items, size_t n, size_t size,
                   const char *what, Error *err)
{
    if (n == 0)
        return true;
    if (*count + n > UINT32_MAX) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "%s: the grid media hold more than 2^32 entries", what);
        return false;
    }
    if (!*array) {
        /* Taken over, without the spare capacity the grid's reader grew it with. */
        void *exact = realloc(*items, n * size);
        *array = exact ? exact : *items, *items = NULL;
        *count = n;
        return true;
    }
    void *grown = realloc(*array, (*count + n) * size);
    if (!grown) {
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "%s: out of memory for the grid media", what);
        return false;
    }
    memcpy((char *)grown + *count * size, *items, n * size);
    *array = grown;
    *count += n;
    return true;
}

static bool positive(const float4 *c)
{
    return c->s[0] > 0.0f || c->s[1] > 0.0f || c->s[2] > 0.0f;
}

/* m->to_index: the inverse of (object_to_world x grid's index_to_object). */
static bool grid_to_index(Medium *m, const VolumeGrid *grid, const Affine *object_to_world,
                          Error *err)
{
    Affine index_to_object, index_to_world, world_to_index;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            index_to_object.m[r][c] = grid->index_to_object[4 * r + c];
    index_to_world = affine_mul(object_to_world, &index_to_object);
    if (!affine_invert(&index_to_world, &world_to_index)) {
        error_set(err, ERR_JSON_VALUE, NULL, 0, "grid medium: its transform is singular");
        return false;
    }
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            m->to_index[r].s[c] = (float)world_to_index.m[r][c];
    return true;
}

uint32_t scene_data_add_medium(SceneData *data, const Medium *m, VolumeGrid *grid,
                               const Affine *object_to_world, Error *err)
{
    if (data->num_media >= MEDIUM_COUNT_LIMIT) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "a scene may have at most %u media", MEDIUM_COUNT_LIMIT);
        return 0;
    }
    Medium medium = *m;
    medium.flags = (positive(&m->sigma_s) ? MEDIUM_FLAG_SCATTERS : 0u) |
                   (positive(&m->emission) && positive(&m->sigma_a) ? MEDIUM_FLAG_EMITS : 0u);
    medium.sigma_s.s[3] = 1.0f;
    if (m->type == MEDIUM_GRID) {
        if (!grid_to_index(&medium, grid, object_to_world, err))
            return 0;
        medium.res_x = grid->res[0], medium.res_y = grid->res[1], medium.res_z = grid->res[2];
        medium.bricks_x = grid->bricks[0], medium.bricks_y = grid->bricks[1];
        medium.bricks_z = grid->bricks[2];
        medium.sigma_s.s[3] = grid->max_value;
        size_t table = (size_t)grid->bricks[0] * grid->bricks[1] * grid->bricks[2];
        medium.brick_table = (uint32_t)data->num_grid_bricks;
        medium.values = (uint32_t)data->num_grid_values;
        medium.majorants = (uint32_t)data->num_grid_majorants;
        /* A grid whose values all lie in one brick's neighbourhood of zero still tracks: the
         * flags say scattering when the coefficients do, whatever the density. */
        if (!append((void **)&data->grid_bricks, &data->num_grid_bricks,
                    (void **)&grid->brick_table, table, sizeof(uint32_t), "grid medium", err) ||
            !append((void **)&data->grid_values, &data->num_grid_values, (void **)&grid->values,
                    (size_t)grid->num_bricks * MEDIUM_BRICK_VOXELS, sizeof(float), "grid medium",
                    err) ||
            !append((void **)&data->grid_majorants, &data->num_grid_majorants,
                    (void **)&grid->majorants, table, sizeof(float), "grid medium", err))
            return 0;
    }
    Medium *grown = realloc(data->media, (data->num_media + 1) * sizeof *grown);
    if (!grown) {
        error_set(err, ERR_OUT_OF_MEMORY, NULL, 0, "out of memory for the media");
        return 0;
    }
    data->media = grown;
    data->media[data->num_media++] = medium;
    return data->num_media;
}

bool material_has_absorption(const Material *m)
{
    return m->type == MATERIAL_DIELECTRIC && positive(&m->absorption);
}

uint32_t scene_data_add_absorption_medium(SceneData *data, const float4 *sigma, Error *err)
{
    Medium m = {0};
    m.type = MEDIUM_HOMOGENEOUS;
    for (int c = 0; c < 3; c++)
        m.sigma_a.s[c] = sigma->s[c];
    return scene_data_add_medium(data, &m, NULL, NULL, err);
}

bool scene_data_media_from_absorption(SceneData *data, Error *err)
{
    for (uint32_t i = 0; i < data->num_materials; i++) {
        Material *mat = &data->materials[i];
        if (!material_has_absorption(mat) || (mat->flags & MATERIAL_FLAG_MEDIUM_INTERFACE))
            continue;
        uint32_t slot = scene_data_add_absorption_medium(data, &mat->absorption, err);
        if (slot == 0)
            return false;
        mat = &data->materials[i]; /* add_medium does not move materials, but stay obvious */
        mat->interior = slot;
        mat->exterior = MEDIUM_SLOT_WORLD;
        mat->flags |= MATERIAL_FLAG_MEDIUM_INTERFACE;
    }
    return true;
}

/* Van de Hulst's inversion of the diffuse reflectance of a half-space of isotropic scatterers, as
 * Cycles uses it (src/kernel/integrator/subsurface_random_walk.h, subsurface_random_walk_remap,
 * blender/cycles 97dbe6f; d'Eon, "A Hitchhiker's Guide to Multiple Scattering", eq. 53.7):
 * s = 4.09712 + 4.20863 A - sqrt(9.59217 + 41.6808 A + 17.7126 A^2), alpha = (1 - s^2) / (1 - g s^2)
 * with g = 0, clamped to [0, 0.999999] as Cycles does (alpha 1 would walk forever without loss). */
float subsurface_albedo(float colour)
{
    double a = colour < 0.0f ? 0.0 : colour > 1.0f ? 1.0 : colour;
    double s = 4.09712 + 4.20863 * a - sqrt(9.59217 + 41.6808 * a + 17.7126 * a * a);
    double alpha = 1.0 - s * s;
    return (float)(alpha < 0.0 ? 0.0 : alpha > 0.999999 ? 0.999999 : alpha);
}

uint32_t scene_data_add_subsurface_medium(SceneData *data, uint32_t index, const float radius[3],
                                          Error *err)
{
    Medium m = {0};
    m.type = MEDIUM_HOMOGENEOUS;
    for (int c = 0; c < 3; c++) {
        float sigma_t = 1.0f / fmaxf(radius[c], 1e-16f); /* Cycles' floor; the reader wants > 0 */
        float alpha = subsurface_albedo(data->materials[index].base.s[c]);
        m.sigma_s.s[c] = alpha * sigma_t;
        m.sigma_a.s[c] = (1.0f - alpha) * sigma_t;
    }
    uint32_t slot = scene_data_add_medium(data, &m, NULL, NULL, err);
    if (slot == 0)
        return 0;
    Material *mat = &data->materials[index];
    mat->interior = slot;
    mat->exterior = MEDIUM_SLOT_WORLD;
    mat->flags |= MATERIAL_FLAG_MEDIUM_INTERFACE;
    return slot;
}

bool scene_data_media_track(const SceneData *data)
{
    for (uint32_t i = 0; i < data->num_media; i++)
        if (data->media[i].flags & (MEDIUM_FLAG_SCATTERS | MEDIUM_FLAG_EMITS))
            return true;
    for (uint32_t i = 0; i < data->num_materials; i++)
        if (data->materials[i].type == MATERIAL_INTERFACE)
            return true;
    return false;
}

bool scene_data_has_grid_media(const SceneData *data)
{
    for (uint32_t i = 0; i < data->num_media; i++)
        if (data->media[i].type == MEDIUM_GRID)
            return true;
    return false;
}
