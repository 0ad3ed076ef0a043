/* SPDX-License-Identifier: MIT */
/* materials.h: MTL materials (io/obj_loader.h) mapped onto the kernels' Material, and their
 * textures loaded into the scene's TextureSet. */
#ifndef PT_MATERIALS_H
#define PT_MATERIALS_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "base/shared_types.h"
#include "io/mesh.h"
#include "scene/texture.h"

/* The JSON materials, which are the scene's materials 0..count-1 and replace MTL materials of the
 * same name everywhere. */
#define NO_MATERIAL 0xffffffffu

typedef struct {
    const char *const *names;
    uint32_t count;
} NamedMaterials;

/* A material of `type` with DESIGN's defaults and no textures. */
Material material_blank(uint32_t type);
/* The texture indices of one MTL material (NO_TEXTURE where none) and what the mapping needs to
 * know about them. */
typedef struct {
    uint32_t kd, ke, pr, pm, d, normal;
    bool kd_alpha;           /* map_Kd has alpha below 1 somewhere: it gives the opacity */
    bool normal_is_height;   /* the normal map (norm, map_Bump) is grey: a bump (height) map */
    float ke_mean_luminance; /* of map_Ke (1 without) */
} ObjTextures;

ObjTextures obj_textures_none(void);
/* Maps one MTL material onto the kernels' Material (shared/DESIGN.md "MTL mapping"). */
Material material_from_obj(const ObjMaterial *m, const ObjTextures *tex);
/* The material of triangles that name none: diffuse grey 0.8. */
Material material_default(void);
/* Appends the mesh's materials to *materials (*num_materials of them so far) and loads their
 * textures into `textures`; mesh_to_scene[i] (mesh->num_materials entries) receives the scene index
 * of the mesh's material i: a material named like one of `named` (may be NULL) maps to it and is
 * not loaded. A missing texture file is a warning (the material keeps its Kd); a corrupt one is an
 * error naming the material and obj_path. */
bool materials_append_obj(Material **materials, uint32_t *num_materials, TextureSet *textures,
                          const Mesh *mesh, const char *obj_path, const NamedMaterials *named,
                          uint32_t *mesh_to_scene, Error *err);

/* The MATERIAL_FEATURE_* mask (cl/shared.h) of what these materials use: the kernels are built
 * for it (render/session.c). */
uint32_t material_features(const Material *materials, uint32_t count, const TextureSet *textures);

#endif
