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

ObjTextures obj_textures_none(void)
{
    return (ObjTextures){.kd = NO_TEXTURE, .ke = NO_TEXTURE, .pr = NO_TEXTURE, .pm = NO_TEXTURE,
                         .d = NO_TEXTURE, .normal = NO_TEXTURE, .ke_mean_luminance = 1.0f};
}

/* The type DESIGN's "MTL mapping" gives, in its order of precedence. */
static uint32_t obj_type(const ObjMaterial *m)
{
    bool has_ks = m->ks[0] + m->ks[1] + m->ks[2] > 0.0f;
    if ((m->illum == 3 || m->illum == 5) && has_ks)
        return MATERIAL_CONDUCTOR;
    if (m->illum == 4 || m->illum == 6 || m->illum == 7 || (m->ni > 1.0f && m->d < 1.0f))
        return MATERIAL_DIELECTRIC;
    if (m->has_pr || m->has_pm || (m->illum == 2 && has_ks && m->has_ns))
        return MATERIAL_PRINCIPLED;
    return MATERIAL_DIFFUSE;
}

static float unit(float v) { return isfinite(v) ? fminf(fmaxf(v, 0.0f), 1.0f) : 0.0f; }

Material material_from_obj(const ObjMaterial *m, const ObjTextures *tex)
{
    Material out = material_blank(obj_type(m));
    switch (out.type) {
    case MATERIAL_CONDUCTOR:
        out.base = reflectance(m->ks);
        out.flags |= MATERIAL_FLAG_FRESNEL_ONE;
        out.roughness = m->has_pr ? unit(m->pr) : 0.0f;
        out.tex[MATERIAL_TEX_ROUGHNESS] = tex->pr;
        break;
    case MATERIAL_DIELECTRIC:
        out.base = reflectance(m->tf);
        /* An absent or black Tf would make a glass object opaque black; MTL writers mean "untinted". */
        if (out.base.s[0] + out.base.s[1] + out.base.s[2] <= 0.0f)
            out.base = (float4){{1.0f, 1.0f, 1.0f, 0.0f}};
        out.ior = isfinite(m->ni) && m->ni > 1.0f ? m->ni : 1.5f;
        out.roughness = m->has_pr ? unit(m->pr) : 0.0f;
        out.tex[MATERIAL_TEX_ROUGHNESS] = tex->pr;
        break;
    case MATERIAL_PRINCIPLED:
        out.base = reflectance(m->kd);
        out.tex[MATERIAL_TEX_BASE] = tex->kd;
        if (m->has_pr || m->has_pm) {
            out.roughness = m->has_pr ? unit(m->pr) : 0.5f; /* Mitsuba's principled default */
            out.metallic = m->has_pm ? unit(m->pm) : 0.0f;
            out.tex[MATERIAL_TEX_ROUGHNESS] = tex->pr;
            out.tex[MATERIAL_TEX_METALLIC] = tex->pm;
        } else { /* illum 2 with Ks and Ns: a glossy dielectric coat over Kd */
            float ns = isfinite(m->ns) ? fminf(fmaxf(m->ns, 0.0f), 1000.0f) : 0.0f;
            out.roughness = 1.0f - sqrtf(ns / 1000.0f);
        }
        break;
    default:
        out.base = reflectance(m->kd);
        out.tex[MATERIAL_TEX_BASE] = tex->kd;
    }
    /* An RGBA map_Kd with cut-outs: its alpha is the opacity (where it is the base texture). */
    if (out.tex[MATERIAL_TEX_BASE] != NO_TEXTURE && tex->kd_alpha)
        out.flags |= MATERIAL_FLAG_BASE_ALPHA | MATERIAL_FLAG_CUTOUT;
    if (tex->d != NO_TEXTURE) {
        out.tex[MATERIAL_TEX_OPACITY] = tex->d;
        out.flags |= MATERIAL_FLAG_CUTOUT;
    } else if (out.type != MATERIAL_DIELECTRIC && m->d < 1.0f) {
        out.opacity = unit(m->d);
        out.flags |= MATERIAL_FLAG_CUTOUT;
    }
    if (tex->normal != NO_TEXTURE) {
        out.tex[tex->normal_is_height ? MATERIAL_TEX_BUMP : MATERIAL_TEX_NORMAL] = tex->normal;
        out.bump_scale = isfinite(m->bump_scale) ? m->bump_scale : 1.0f;
    }
    for (int i = 0; i < 3; i++)
        out.emission.s[i] = isfinite(m->ke[i]) ? fmaxf(m->ke[i], 0.0f) : 0.0f;
    if (tex->ke != NO_TEXTURE) {
        out.tex[MATERIAL_TEX_EMISSION] = tex->ke;
        /* map_Ke without a Ke (or with Ke 0): the texture alone is the emitted radiance. */
        if (luminance3(out.emission.s) <= 0.0f)
            out.emission = (float4){{1.0f, 1.0f, 1.0f, 0.0f}};
    }
    out.emission.s[3] = luminance3(out.emission.s) * tex->ke_mean_luminance;
    return out;
}

Material material_default(void)
{
    ObjMaterial grey = {.kd = {0.8f, 0.8f, 0.8f}, .ni = 1.0f, .d = 1.0f, .illum = -1};
    ObjTextures none = obj_textures_none();
    return material_from_obj(&grey, &none);
}

/* One texture of an MTL material: a missing file is a warning (the material goes without it), a
 * corrupt one an error naming the material and obj_path. */
static bool load_texture(TextureSet *textures, const char *path, TextureEncoding encoding,
                         const char *statement, const ObjMaterial *m, const char *obj_path,
                         uint32_t *out, Error *err)
{
    *out = NO_TEXTURE;
    if (!path[0])
        return true;
    Error texture_err = {0};
    *out = texture_set_add_encoded(textures, path, encoding, &texture_err);
    if (texture_err.code == ERR_FILE_MISSING) {
        warn("%s: texture %s (%s) of material '%s' not found: %s", obj_path, path, statement,
             m->name, strcmp(statement, "map_Kd") == 0 ? "using its Kd" : "ignored");
    } else if (error_is_set(&texture_err)) {
        error_set(err, texture_err.code, texture_err.file, 0, "%s (%s of material '%s' of %s)",
                  texture_err.message, statement, m->name, obj_path);
        return false;
    }
    return true;
}

/* DESIGN "Textures": map_Kd and map_Ke are colours (sRGB for 8-bit files); map_Pr, map_Pm, map_d
 * and normal maps are linear. */
static bool load_obj_textures(const ObjMaterial *m, TextureSet *textures, const char *obj_path,
                              ObjTextures *tex, Error *err)
{
    *tex = obj_textures_none();
    const TextureEncoding linear = TEXTURE_ENCODING_LINEAR, colour = TEXTURE_ENCODING_DEFAULT;
    if (!load_texture(textures, m->map_kd, colour, "map_Kd", m, obj_path, &tex->kd, err) ||
        !load_texture(textures, m->map_ke, colour, "map_Ke", m, obj_path, &tex->ke, err) ||
        !load_texture(textures, m->map_pr, linear, "map_Pr", m, obj_path, &tex->pr, err) ||
        !load_texture(textures, m->map_pm, linear, "map_Pm", m, obj_path, &tex->pm, err) ||
        !load_texture(textures, m->map_d, linear, "map_d", m, obj_path, &tex->d, err) ||
        !load_texture(textures, m->map_normal, linear, m->normal_statement, m, obj_path, &tex->normal,
                      err))
        return false;
    tex->kd_alpha = tex->kd != NO_TEXTURE && textures->stats[tex->kd].alpha_below_one;
    /* A grey map_Bump is a height map (classic MTL bump), an rgb one a normal map. */
    tex->normal_is_height = tex->normal != NO_TEXTURE && textures->stats[tex->normal].channels < 3;
    if (tex->ke != NO_TEXTURE)
        tex->ke_mean_luminance = texture_mean_luminance(textures, tex->ke);
    return true;
}

static uint32_t find_named(const NamedMaterials *named, const char *name)
{
    for (uint32_t i = 0; named && i < named->count; i++)
        if (strcmp(named->names[i], name) == 0)
            return i;
    return NO_MATERIAL;
}

bool materials_append_obj(Material **materials, uint32_t *num_materials, TextureSet *textures,
                          const Mesh *mesh, const char *obj_path, const NamedMaterials *named,
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
        ObjTextures tex;
        if (!load_obj_textures(m, textures, obj_path, &tex, err))
            return false;
        mesh_to_scene[i] = *num_materials;
        (*materials)[(*num_materials)++] = material_from_obj(m, &tex);
    }
    return true;
}

/* Whether the kernels could treat material m as rough: its largest GGX alpha (as bsdf_at computes
 * it) reaches half the kernels' smooth bound, or a texture sets its roughness. Erring toward rough
 * only keeps code the material does not need; the kernels still decide per hit. */
static bool material_may_be_rough(const Material *m)
{
    if (m->tex[MATERIAL_TEX_ROUGHNESS] != NO_TEXTURE)
        return true;
    float alpha = m->roughness * m->roughness;
    float stretch = m->anisotropy > 0.0f ? sqrtf(1.0f - 0.9f * m->anisotropy) : 1.0f;
    return fmaxf(alpha / stretch, alpha * stretch) >= 0.5e-3f;
}

uint32_t material_features(const Material *materials, uint32_t count, const TextureSet *textures)
{
    uint32_t features = 0;
    /* Each texel format and glTF's sampling keep their code only where a texture needs it
     * (cl/material/texture.cl): a lookup is inlined at every one of its call sites. */
    if (textures->count > 0)
        features |= MATERIAL_FEATURE_TEXTURE;
    for (uint32_t i = 0; i < textures->count; i++) {
        const TextureInfo *t = &textures->infos[i];
        if (t->format == TEXTURE_NOISE)
            features |= MATERIAL_FEATURE_NOISE_TEXTURE;
        if (t->format == TEXTURE_RGBA8_SRGB)
            features |= MATERIAL_FEATURE_SRGB_TEXTURE;
        if (t->format == TEXTURE_RGBA32F)
            features |= MATERIAL_FEATURE_FLOAT_TEXTURE;
        if (t->format != TEXTURE_NOISE && t->flags != 0u)
            features |= MATERIAL_FEATURE_TEXTURE_SAMPLER;
    }
    for (uint32_t i = 0; i < count; i++) {
        const Material *m = &materials[i];
        if (m->type == MATERIAL_CONDUCTOR && material_may_be_rough(m))
            features |= MATERIAL_FEATURE_ROUGH_CONDUCTOR;
        if (m->type == MATERIAL_CONDUCTOR && !(m->flags & MATERIAL_FLAG_FRESNEL_ONE))
            features |= MATERIAL_FEATURE_CONDUCTOR_FRESNEL;
        if (m->type == MATERIAL_DIELECTRIC && material_may_be_rough(m))
            features |= MATERIAL_FEATURE_ROUGH_DIELECTRIC;
        if (m->type == MATERIAL_DIELECTRIC)
            features |= MATERIAL_FEATURE_REFRACTION;
        if (m->type == MATERIAL_DIELECTRIC &&
            (m->absorption.s[0] > 0.0f || m->absorption.s[1] > 0.0f || m->absorption.s[2] > 0.0f))
            features |= MATERIAL_FEATURE_ABSORPTION;
        if (m->type == MATERIAL_PRINCIPLED)
            features |= MATERIAL_FEATURE_PRINCIPLED;
        if (m->type == MATERIAL_MIX)
            features |= MATERIAL_FEATURE_MIX;
        if (m->tex[MATERIAL_TEX_NORMAL] != NO_TEXTURE || m->tex[MATERIAL_TEX_BUMP] != NO_TEXTURE ||
            m->anisotropy != 0.0f)
            features |= MATERIAL_FEATURE_SURFACE_DETAIL;
        if (m->tex[MATERIAL_TEX_BUMP] != NO_TEXTURE)
            features |= MATERIAL_FEATURE_BUMP_MAP;
        if (m->tex[MATERIAL_TEX_ROUGHNESS] != NO_TEXTURE || m->tex[MATERIAL_TEX_METALLIC] != NO_TEXTURE ||
            m->tex[MATERIAL_TEX_WEIGHT] != NO_TEXTURE)
            features |= MATERIAL_FEATURE_TEXTURED_SCALARS;
        if (m->tex[MATERIAL_TEX_EMISSION] != NO_TEXTURE)
            features |= MATERIAL_FEATURE_EMISSION_TEXTURE;
    }
    return features;
}
