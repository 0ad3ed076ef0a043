/* SPDX-License-Identifier: MIT */
/* materials.h: MTL materials (io/obj_loader.h) mapped onto the kernels' Material, and their
 * textures loaded into the scene's TextureSet. */
#ifndef PT_MATERIALS_H
#define PT_MATERIALS_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "base/shared_types.h"
#include "io/obj_loader.h"
#include "scene/texture.h"

/* A material of `type` with DESIGN's defaults and no textures. */
Material material_blank(uint32_t type);
/* Maps one MTL material onto the kernels' Material (see README "Materials"). */
Material material_from_obj(const ObjMaterial *m, uint32_t map_kd);
/* The material of triangles that name none: diffuse grey 0.8. */
Material material_default(void);
/* Appends the mesh's materials to *materials (*num_materials of them so far) and loads their
 * textures into `textures`. A missing texture file is a warning (the material keeps its Kd); a
 * corrupt one is an error naming the material and obj_path. */
bool materials_append_obj(Material **materials, uint32_t *num_materials, TextureSet *textures,
                          const ObjMesh *mesh, const char *obj_path, Error *err);

#endif
