// SPDX-License-Identifier: MIT
/* media_load.c: see media_load.h. */
#include "scene/media_load.h"

#include "io/volume_grid.h"
#include "scene/scene_media.h"

/* A grid medium: its file's grid, placed by its transform. The reader's message names the file;
 * the key in front says which medium asked for it. */
static uint32_t add_grid_medium(SceneData *data, const SceneDesc *d, const MediumDesc *m,
                                Error *err)
{
    VolumeGrid grid = {0};
    Error inner = {0};
    uint32_t slot = 0;
    /* The key at fault: a grid name not in the file is "grid", a singular placement
     * "transform", anything else about reading it "file". */
    const char *key = "file";
    if (!volume_grid_read(m->file, m->grid, &grid, &inner))
        key = inner.code == ERR_JSON_VALUE ? "grid" : "file";
    else if (!(slot = scene_data_add_medium(data, &m->m, &grid, &m->transform, &inner)))
        key = inner.code == ERR_JSON_VALUE ? "transform" : "file";
    if (!slot)
        error_set(err, inner.code, d->path, 0, "%s: media.%s.%s: %s", d->path, m->name, key,
                  inner.message);
    volume_grid_free(&grid);
    return slot;
}

bool media_load(SceneData *data, const SceneDesc *d, Error *err)
{
    for (int i = 0; i < d->num_media; i++) {
        const MediumDesc *m = &d->media[i];
        Error inner = {0};
        uint32_t slot = m->m.type == MEDIUM_GRID ? add_grid_medium(data, d, m, err)
                                                 : scene_data_add_medium(data, &m->m, NULL, NULL,
                                                                         &inner);
        if (!slot && inner.code)
            error_set(err, inner.code, d->path, 0, "%s: media.%s: %s", d->path, m->name,
                      inner.message);
        if (!slot)
            return false;
    }
    data->world_medium = d->world_medium;
    data->camera_medium = d->camera_medium ? d->camera_medium : d->world_medium;
    for (int i = 0; i < d->num_materials; i++) {
        const MaterialDesc *m = &d->materials[i];
        Error inner = {0};
        if (m->m.type != MATERIAL_PRINCIPLED || !(m->m.subsurface > 0.0f))
            continue;
        if (!scene_data_add_subsurface_medium(data, (uint32_t)i, m->subsurface_radius, &inner)) {
            error_set(err, inner.code, d->path, 0, "%s: materials.%s.subsurface: %s", d->path,
                      m->name, inner.message);
            return false;
        }
    }
    return true;
}
