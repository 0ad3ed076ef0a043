// SPDX-License-Identifier: MIT
/* gltf_material.c: glTF materials to pt's (gltf_material.h): pbrMetallicRoughness is pt's
 * principled, KHR_materials_transmission a dielectric (alone, or mixed with the principled by the
 * transmission), and what the surface itself does (emission, normal map, alpha) goes on the
 * material the triangles name. */
#include "scene/gltf_material.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/gltf_texture.h"
#include "scene/materials.h"

/* One value of the file outside its range: "file.gltf: materials[2].metallicFactor: 1.5 is out of
 * range [0, 1]". */
static bool check_range(const GltfMaterial *g, const char *key, const float *v, int n, float lo,
                        float hi, const char *gltf_path, Error *err)
{
    for (int i = 0; i < n; i++) {
        if (!(v[i] >= lo && v[i] <= hi)) {
            error_set(err, ERR_JSON_VALUE, gltf_path, 0, "%s: %s.%s: %g is out of range [%g, %g]",
                      gltf_path, g->json_path, key, (double)v[i], (double)lo, (double)hi);
            return false;
        }
    }
    return true;
}

static bool check_material(const GltfMaterial *g, const char *path, Error *err)
{
    const float big = FLT_MAX, distance = g->attenuation_distance;
    const float cutoff = g->alpha_cutoff, strength = g->emissive_strength;
    const char *pbr = "pbrMetallicRoughness.", *ext = "extensions.KHR_materials_";
    char k[10][96];
    snprintf(k[0], sizeof k[0], "%sbaseColorFactor", pbr);
    snprintf(k[1], sizeof k[1], "%smetallicFactor", pbr);
    snprintf(k[2], sizeof k[2], "%sroughnessFactor", pbr);
    snprintf(k[3], sizeof k[3], "%semissive_strength.emissiveStrength", ext);
    snprintf(k[4], sizeof k[4], "%sspecular.specularFactor", ext);
    snprintf(k[5], sizeof k[5], "%sspecular.specularColorFactor", ext);
    snprintf(k[6], sizeof k[6], "%stransmission.transmissionFactor", ext);
    snprintf(k[7], sizeof k[7], "%sior.ior", ext);
    snprintf(k[8], sizeof k[8], "%svolume.attenuationColor", ext);
    snprintf(k[9], sizeof k[9], "%svolume.attenuationDistance", ext);
    return check_range(g, k[0], g->base_color, 4, 0, 1, path, err) &&
           check_range(g, k[1], &g->metallic, 1, 0, 1, path, err) &&
           check_range(g, k[2], &g->roughness, 1, 0, 1, path, err) &&
           check_range(g, "emissiveFactor", g->emissive, 3, 0, 1, path, err) &&
           check_range(g, k[3], &strength, 1, 0, big, path, err) &&
           check_range(g, "alphaCutoff", &cutoff, 1, 0, big, path, err) &&
           check_range(g, "normalTexture.scale", &g->normal_texture.amount, 1, -big, big, path,
                       err) &&
           check_range(g, k[4], &g->specular, 1, 0, 1, path, err) &&
           check_range(g, k[5], g->specular_color, 3, 0, big, path, err) &&
           check_range(g, k[6], &g->transmission, 1, 0, 1, path, err) &&
           check_range(g, k[7], &g->ior, 1, 1, big, path, err) &&
           check_range(g, k[8], g->attenuation_color, 3, 0, 1, path, err) &&
           (isinf(distance) || check_range(g, k[9], &distance, 1, FLT_MIN, big, path, err));
}

/* The principled part: base colour, metallic and roughness (the metallicRoughnessTexture's b and g
 * channels times their factors), KHR_materials_specular's factors, the ior. */
static bool principled(GltfTextures *t, const GltfMaterial *g, Material *m)
{
    *m = material_blank(MATERIAL_PRINCIPLED);
    for (int c = 0; c < 3; c++) {
        m->base.s[c] = g->base_color[c];
        m->specular_color.s[c] = g->specular_color[c];
    }
    m->metallic = g->metallic;
    m->roughness = g->roughness;
    m->specular = g->specular;
    m->ior = g->ior;
    const GltfTextureRef *mr = &g->metallic_roughness_texture;
    const TextureEncoding linear = TEXTURE_ENCODING_LINEAR;
    if (g->specular_texture.image >= 0 || g->specular_color_texture.image >= 0)
        warn("%s: %s: KHR_materials_specular textures are not supported: the factors apply",
             t->gltf_path, g->json_path);
    return gltf_texture(t, &g->base_color_texture, TEXTURE_ENCODING_SRGB, 0, 1.0f,
                        &m->tex[MATERIAL_TEX_BASE]) &&
           gltf_texture(t, mr, linear, 1, g->roughness, &m->tex[MATERIAL_TEX_ROUGHNESS]) &&
           gltf_texture(t, mr, linear, 2, g->metallic, &m->tex[MATERIAL_TEX_METALLIC]);
}

/* KHR_materials_transmission's part: a dielectric with the material's ior, roughness and base
 * colour (the tint), absorbing per KHR_materials_volume: sigma = -ln(attenuationColor) /
 * attenuationDistance per channel (Beer-Lambert; the volume's thicknessFactor is not needed: pt
 * traces the mesh's own thickness). */
static Material dielectric(const GltfMaterial *g, const Material *surface)
{
    Material m = material_blank(MATERIAL_DIELECTRIC);
    m.ior = g->ior;
    m.roughness = g->roughness;
    m.tex[MATERIAL_TEX_ROUGHNESS] = surface->tex[MATERIAL_TEX_ROUGHNESS];
    m.tex[MATERIAL_TEX_BASE] = surface->tex[MATERIAL_TEX_BASE];
    for (int c = 0; c < 3; c++) {
        m.base.s[c] = g->base_color[c];
        if (g->has_volume && isfinite(g->attenuation_distance))
            m.absorption.s[c] = -logf(fmaxf(g->attenuation_color[c], 1e-30f)) /
                                g->attenuation_distance;
    }
    return m;
}

/* What the surface does whatever scatters: emission (factor times texture times
 * KHR_materials_emissive_strength), the normal map with its scale (pt's bump_scale scales the
 * map's xy, as glTF's scale does), and the alpha mode: OPAQUE ignores alpha; BLEND makes the
 * alpha (baseColorFactor's a times the base texture's a) the opacity; MASK makes it 1 at or above
 * alphaCutoff, else 0. */
static bool surface(GltfTextures *t, const GltfMaterial *g, uint32_t base_texture, Material *m)
{
    float luminance = 0.0f;
    for (int c = 0; c < 3; c++) {
        m->emission.s[c] = g->emissive[c] * g->emissive_strength;
        luminance += m->emission.s[c];
    }
    const TextureEncoding linear = TEXTURE_ENCODING_LINEAR;
    if ((luminance > 0.0f && !gltf_texture(t, &g->emissive_texture, TEXTURE_ENCODING_SRGB, 0, 1.0f,
                                            &m->tex[MATERIAL_TEX_EMISSION])) ||
        !gltf_texture(t, &g->normal_texture, linear, 0, 1.0f, &m->tex[MATERIAL_TEX_NORMAL]))
        return false;
    if (m->tex[MATERIAL_TEX_NORMAL] != NO_TEXTURE)
        m->bump_scale = g->normal_texture.amount;
    if (g->alpha_mode == GLTF_ALPHA_OPAQUE)
        return true;
    float alpha = g->base_color[3];
    if (base_texture == NO_TEXTURE) {
        m->opacity = g->alpha_mode == GLTF_ALPHA_MASK ? (alpha >= g->alpha_cutoff ? 1.0f : 0.0f)
                                                      : alpha;
        if (m->opacity < 1.0f)
            m->flags |= MATERIAL_FLAG_CUTOUT;
        return true;
    }
    /* The base colour's image, alpha moved to x and times the factor's alpha; sRGB as the base
     * texture is, so that both share its texels (alpha is linear in either encoding). */
    if (!gltf_texture(t, &g->base_color_texture, TEXTURE_ENCODING_SRGB, 3, alpha,
                      &m->tex[MATERIAL_TEX_OPACITY]))
        return false;
    m->flags |= MATERIAL_FLAG_CUTOUT;
    if (g->alpha_mode == GLTF_ALPHA_MASK) {
        m->flags |= MATERIAL_FLAG_ALPHA_MASK;
        m->base.s[3] = g->alpha_cutoff;
    }
    return true;
}

static bool grow(MaterialDesc **materials, int count, const char *gltf_path, Error *err)
{
    MaterialDesc *grown = realloc(*materials, (size_t)count * sizeof *grown);
    if (!grown) {
        error_set(err, ERR_TOO_LARGE, gltf_path, 0, "%s: out of memory for %d materials",
                  gltf_path, count);
        return false;
    }
    *materials = grown;
    return true;
}

/* Appends the parts of a transmissive material after the count top-level ones; returns the index
 * of the part. */
static bool append_part(MaterialDesc **materials, int *num_materials, const Material *m,
                        const char *name, const char *suffix, const char *gltf_path,
                        uint32_t *index, Error *err)
{
    if (!grow(materials, *num_materials + 1, gltf_path, err))
        return false;
    MaterialDesc *d = &(*materials)[*num_materials];
    memset(d, 0, sizeof *d);
    snprintf(d->name, sizeof d->name, "%s%s", name, suffix);
    d->m = *m;
    *index = (uint32_t)(*num_materials)++;
    return true;
}

/* One glTF material into (*materials)[top] (and its parts appended). Transmission T with a
 * constant metallic M: glTF's f = M metal + (1 - M) ((1 - T) dielectric + T transmission), which
 * is mix(principled with metallic M / (1 - w), dielectric, w = T (1 - M)). A textured metallic
 * or transmission keeps metallic as it is and the weight T times the texture's red (1 - M). */
static bool map_one(GltfTextures *t, const GltfMaterial *g, int top, MaterialDesc **materials,
                    int *num_materials)
{
    Material p, out;
    if (!check_material(g, t->gltf_path, t->err) || !principled(t, g, &p))
        return false;
    bool textured_metallic = p.tex[MATERIAL_TEX_METALLIC] != NO_TEXTURE;
    bool textured_transmission = g->transmission > 0.0f && g->transmission_texture.image >= 0;
    if (g->transmission <= 0.0f) {
        out = p;
    } else if (g->transmission >= 1.0f && !textured_transmission && g->metallic <= 0.0f &&
               !textured_metallic) {
        out = dielectric(g, &p);
    } else {
        float w = g->transmission * (textured_metallic ? 1.0f : 1.0f - g->metallic);
        if (!textured_metallic && !textured_transmission && w < 1.0f)
            p.metallic = g->metallic / (1.0f - w);
        Material d = dielectric(g, &p);
        out = material_blank(MATERIAL_MIX);
        out.weight = w;
        char name[SCENE_NAME_LIMIT];
        snprintf(name, sizeof name, "%s", (*materials)[top].name);
        if (!append_part(materials, num_materials, &p, name, "/surface", t->gltf_path, &out.mix_a,
                         t->err) ||
            !append_part(materials, num_materials, &d, name, "/transmission", t->gltf_path,
                         &out.mix_b, t->err) ||
            !gltf_texture(t, &g->transmission_texture, TEXTURE_ENCODING_LINEAR, 0, w,
                          &out.tex[MATERIAL_TEX_WEIGHT]))
            return false;
    }
    if (!surface(t, g, p.tex[MATERIAL_TEX_BASE], &out))
        return false;
    (*materials)[top].m = out;
    return true;
}

bool gltf_materials_append(const GltfMaterial *gltf, int count, const GltfImage *images,
                           int num_images, const char *gltf_path, const char *prefix,
                           MaterialDesc **materials, int *num_materials, TextureDesc **textures,
                           int *num_textures, Error *err)
{
    if (count <= 0)
        return true;
    int first = *num_materials;
    if (!grow(materials, first + count, gltf_path, err))
        return false;
    for (int i = 0; i < count; i++) {
        MaterialDesc *d = &(*materials)[first + i];
        memset(d, 0, sizeof *d);
        snprintf(d->name, sizeof d->name, "%s%s", prefix, gltf[i].json_path);
        d->m = material_blank(MATERIAL_PRINCIPLED);
    }
    *num_materials = first + count;
    GltfTextures t = {images, num_images, gltf_path, prefix, textures, num_textures, *num_textures,
                      err};
    for (int i = 0; i < count; i++)
        if (!map_one(&t, &gltf[i], first + i, materials, num_materials))
            return false;
    return true;
}
