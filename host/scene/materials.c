// SPDX-License-Identifier: MIT
#include "scene/materials.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static float luminance3(const float c[3])
{
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

/* Reflectances above 1 would create energy and non-finite ones poison the image: clamp to [0, 1]. */
static float4 reflectance(const float c[3])
{
    float4 out = {{0.0f, 0.0f, 0.0f, 0.0f}};
    for (int i = 0; i < 3; i++)
        out.s[i] = isfinite(c[i]) ? fminf(fmaxf(c[i], 0.0f), 1.0f) : 0.0f;
    return out;
}

/* A material of `type` with every texture slot empty and the neutral values DESIGN gives. */
Material material_blank(uint32_t type)
{
    Material out = {.type = type, .opacity = 1.0f, .ior = 1.5f, .specular = 1.0f, .weight = 0.5f,
                    .bump_scale = 1.0f, .mix_a = 0, .mix_b = 0};
    for (int i = 0; i < 3; i++)
        out.base.s[i] = out.specular_color.s[i] = 1.0f;
    for (int i = 0; i < MATERIAL_TEX_COUNT; i++)
        out.tex[i] = NO_TEXTURE;
    return out;
}

Material material_from_obj(const ObjMaterial *m, uint32_t map_kd)
{
    bool has_ks = m->ks[0] + m->ks[1] + m->ks[2] > 0.0f;
    bool refracts = m->illum == 4 || m->illum == 6 || m->illum == 7 || (m->ni > 1.0f && m->d < 1.0f);
    Material out;
    if ((m->illum == 3 || m->illum == 5) && has_ks) {
        out = material_blank(MATERIAL_CONDUCTOR);
        out.base = reflectance(m->ks);
        out.flags |= MATERIAL_FLAG_FRESNEL_ONE;
    } else if (refracts) {
        out = material_blank(MATERIAL_DIELECTRIC);
        out.base = reflectance(m->tf);
        /* An absent or black Tf would make a glass object opaque black; MTL writers mean "untinted". */
        if (out.base.s[0] + out.base.s[1] + out.base.s[2] <= 0.0f)
            out.base = (float4){{1.0f, 1.0f, 1.0f, 0.0f}};
        out.ior = isfinite(m->ni) && m->ni > 1.0f ? m->ni : 1.5f;
    } else {
        out = material_blank(MATERIAL_DIFFUSE);
        out.base = reflectance(m->kd);
        out.tex[MATERIAL_TEX_BASE] = map_kd;
    }
    for (int i = 0; i < 3; i++)
        out.emission.s[i] = isfinite(m->ke[i]) ? fmaxf(m->ke[i], 0.0f) : 0.0f;
    out.emission.s[3] = luminance3(out.emission.s);
    return out;
}

Material material_default(void)
{
    ObjMaterial grey = {.kd = {0.8f, 0.8f, 0.8f}, .ni = 1.0f, .d = 1.0f, .illum = -1};
    return material_from_obj(&grey, NO_TEXTURE);
}

static uint32_t find_named(const NamedMaterials *named, const char *name)
{
    for (uint32_t i = 0; named && i < named->count; i++)
        if (strcmp(named->names[i], name) == 0)
            return i;
    return NO_MATERIAL;
}

bool materials_append_obj(Material **materials, uint32_t *num_materials, TextureSet *textures,
                          const ObjMesh *mesh, const char *obj_path, const NamedMaterials *named,
                          uint32_t *mesh_to_scene, Error *err)
{
    if (mesh->num_materials > (size_t)UINT32_MAX - 1 - *num_materials) {
        error_set(err, ERR_TOO_LARGE, obj_path, 0, "%s: too many materials", obj_path);
        return false;
    }
    size_t count = *num_materials + mesh->num_materials;
    Material *grown = realloc(*materials, (count ? count : 1) * sizeof *grown);
    if (!grown) {
        error_set(err, ERR_TOO_LARGE, obj_path, 0, "%s: out of memory for materials", obj_path);
        return false;
    }
    *materials = grown;
    for (size_t i = 0; i < mesh->num_materials; i++) {
        const ObjMaterial *m = &mesh->materials[i];
        if ((mesh_to_scene[i] = find_named(named, m->name)) != NO_MATERIAL)
            continue;
        uint32_t map_kd = NO_TEXTURE;
        if (m->map_kd[0]) {
            Error texture_err = {0};
            map_kd = texture_set_add(textures, m->map_kd, &texture_err);
            if (texture_err.code == ERR_FILE_MISSING) {
                warn("%s: texture %s of material '%s' not found: using its Kd", obj_path, m->map_kd,
                     m->name);
            } else if (error_is_set(&texture_err)) {
                error_set(err, texture_err.code, texture_err.file, 0, "%s (material '%s' of %s)",
                          texture_err.message, m->name, obj_path);
                return false;
            }
        }
        mesh_to_scene[i] = *num_materials;
        (*materials)[(*num_materials)++] = material_from_obj(m, map_kd);
    }
    return true;
}
