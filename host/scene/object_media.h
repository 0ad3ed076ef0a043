/* SPDX-License-Identifier: MIT */
/* object_media.h: objects that bound media (shared/DESIGN.md "Media"): an object's "interior" /
 * "exterior" go on its triangles' materials, as derived copies so that other objects using the
 * same material stay as they are, and a mesh that holds a medium (an interior, or a principled
 * material with subsurface) must be closed. */
#ifndef PT_OBJECT_MEDIA_H
#define PT_OBJECT_MEDIA_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "scene/scene_data.h"

/* The derived materials made so far, one per (material, interior, exterior), shared by every
 * object asking for the same. */
typedef struct {
    uint32_t (*keys)[4]; /* source material, interior, exterior, derived material */
    uint32_t count, capacity;
} DerivedMaterials;

/* Gives the triangles [first_triangle, data->num_triangles) of an object with options o the media
 * o names (data->world_medium already set): each triangle's material is replaced by its derived copy carrying
 * MATERIAL_FLAG_MEDIUM_INTERFACE, o->interior (or the material's own interior when o gives none)
 * and o->exterior (or MEDIUM_SLOT_WORLD). A triangle still waiting for the default material gets a
 * copy of material_default(). Nothing happens when o names no medium. Checks that the triangles
 * form a closed surface when o gives an interior other than its exterior, or a material has
 * subsurface. Errors name
 * scene_path and the object's key ("objects[2].interior: the mesh is not closed (...)"). */
bool object_media_apply(SceneData *data, uint32_t first_triangle, const ObjectOptions *o,
                        DerivedMaterials *derived, const char *scene_path, Error *err);
void derived_materials_free(DerivedMaterials *derived);

/* How far the triangles [first, end) are from closing a surface: edges (between distinct
 * positions, welded by value) with one triangle, and edges with more than two. Degenerate
 * triangles (two corners at one position) are left out. Returns false when out of memory. */
bool mesh_open_edges(const SceneData *data, uint32_t first, uint32_t end, uint64_t *one_face,
                     uint64_t *many_faces);

#endif
