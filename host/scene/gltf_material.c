// SPDX-License-Identifier: MIT
/* gltf_material.c: glTF materials to pt's (gltf_material.h). STUB of the interface commit: base
 * colour, metallic, roughness and emission factors only; textures and extensions to come. */
#include "scene/gltf_material.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void texture_ref_default(GltfTextureRef *t)
{
    memset(t, 0, sizeof *t);
    t->image = -1;
    t->wrap_s = t->wrap_t = GLTF_WRAP_REPEAT;
    t->scale[0] = t->scale[1] = 1.0f;
    t->amount = 1.0f;
}

void gltf_material_default(GltfMaterial *m)
{
    memset(m, 0, sizeof *m);
    for (int c = 0; c < 4; c++)
        m->base_color[c] = 1.0f;
    m->metallic = m->roughness = 1.0f;
    m->emissive_strength = 1.0f;
    m->alpha_cutoff = 0.5f;
    m->specular = 1.0f;
    m->ior = 1.5f;
    m->attenuation_distance = INFINITY;
    for (int c = 0; c < 3; c++)
        m->specular_color[c] = m->attenuation_color[c] = 1.0f;
    GltfTextureRef *refs[] = {&m->base_color_texture, &m->metallic_roughness_texture,
                              &m->normal_texture, &m->occlusion_texture, &m->emissive_texture,
                              &m->specular_texture, &m->specular_color_texture,
                              &m->transmission_texture};
    for (size_t i = 0; i < sizeof refs / sizeof refs[0]; i++)
        texture_ref_default(refs[i]);
}

bool gltf_materials_append(const GltfMaterial *gltf, int count, const GltfImage *images,
                           int num_images, const char *gltf_path, const char *prefix,
                           MaterialDesc **materials, int *num_materials, TextureDesc **textures,
                           int *num_textures, Error *err)
{
    (void)images, (void)num_images, (void)textures, (void)num_textures;
    if (count <= 0)
        return true;
    MaterialDesc *grown = realloc(*materials, (size_t)(*num_materials + count) * sizeof *grown);
    if (!grown) {
        error_set(err, ERR_TOO_LARGE, gltf_path, 0, "%s: out of memory for %d materials",
                  gltf_path, count);
        return false;
    }
    *materials = grown;
    for (int i = 0; i < count; i++) {
        MaterialDesc *d = &grown[*num_materials + i];
        memset(d, 0, sizeof *d);
        snprintf(d->name, sizeof d->name, "%s%s", prefix, gltf[i].json_path);
        Material *m = &d->m;
        m->type = MATERIAL_PRINCIPLED;
        for (int c = 0; c < 3; c++) {
            m->base.s[c] = gltf[i].base_color[c];
            m->emission.s[c] = gltf[i].emissive[c] * gltf[i].emissive_strength;
            m->specular_color.s[c] = 1.0f;
        }
        m->metallic = gltf[i].metallic;
        m->roughness = gltf[i].roughness;
        m->opacity = 1.0f;
        m->ior = gltf[i].ior;
        m->specular = gltf[i].specular;
        m->bump_scale = 1.0f;
        for (int s = 0; s < MATERIAL_TEX_COUNT; s++)
            m->tex[s] = NO_TEXTURE;
    }
    *num_materials += count;
    return true;
}
