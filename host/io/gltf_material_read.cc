// SPDX-License-Identifier: MIT
/* gltf_material_read.cc: a glTF's materials and images, from the model that io/gltf_loader.cc
 * parsed, as the plain records of io/gltf_material_read.h (factors, textureInfos with their
 * samplers and KHR_texture_transform, the KHR_materials_* extensions pt reads). Values are copied
 * as the file states them; scene/gltf_material.c checks their ranges and maps them. */
#include "io/gltf_primitives.h" /* tinygltf, the C++ spellings of base/'s C11 */

#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#define _Noreturn [[noreturn]]
#define _Static_assert static_assert
extern "C" {
#include "io/gltf_material_read.h"
}
#undef _Static_assert
#undef _Noreturn

namespace {

void texture_ref_default(GltfTextureRef *t)
{
    memset(t, 0, sizeof *t);
    t->image = -1;
    t->wrap_s = t->wrap_t = GLTF_WRAP_REPEAT;
    t->scale[0] = t->scale[1] = 1.0f;
    t->amount = 1.0f;
}

float number(const tinygltf::Value &obj, const char *key, float def)
{
    if (!obj.IsObject() || !obj.Has(key) || !obj.Get(key).IsNumber())
        return def;
    return (float)obj.Get(key).GetNumberAsDouble();
}

/* An integer of an extension object; gltf_io::check_json refused one outside [0, 2^31 - 1]
 * under "index" and "texCoord", so the conversion cannot overflow (a float could round 2^31 - 1
 * up to 2^31). */
int integer(const tinygltf::Value &obj, const char *key, int def)
{
    if (!obj.IsObject() || !obj.Has(key) || !obj.Get(key).IsNumber())
        return def;
    double v = obj.Get(key).GetNumberAsDouble();
    return v >= 0 && v <= 2147483647.0 ? (int)v : def;
}

void numbers(const tinygltf::Value &obj, const char *key, float *out, int n)
{
    if (!obj.IsObject() || !obj.Has(key) || !obj.Get(key).IsArray() ||
        obj.Get(key).ArrayLen() != (size_t)n)
        return;
    for (int i = 0; i < n; i++)
        if (obj.Get(key).Get(i).IsNumber())
            out[i] = (float)obj.Get(key).Get(i).GetNumberAsDouble();
}

/* A textureInfo given by its texture index, texCoord and extensions. */
void texture_ref(const tinygltf::Model &m, int texture, int texcoord,
                 const tinygltf::ExtensionMap &extensions, float amount, const std::string &where,
                 GltfTextureRef *out)
{
    snprintf(out->json_path, sizeof out->json_path, "%s", where.c_str());
    out->amount = amount;
    if (texture < 0)
        return;
    out->texcoord = texcoord;
    /* An index out of range stays visible to the mapping, which names it (INT_MAX: no image
     * has that index; texture + a constant overflowed near 2^31). */
    out->image = (size_t)texture < m.textures.size() ? m.textures[texture].source : INT_MAX;
    if ((size_t)texture < m.textures.size()) {
        int s = m.textures[texture].sampler;
        if (s >= 0 && (size_t)s < m.samplers.size()) {
            out->wrap_s = m.samplers[s].wrapS;
            out->wrap_t = m.samplers[s].wrapT;
            out->nearest = m.samplers[s].magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        }
    }
    auto t = extensions.find("KHR_texture_transform");
    if (t != extensions.end() && t->second.IsObject()) {
        out->has_transform = true;
        numbers(t->second, "offset", out->offset, 2);
        out->rotation = number(t->second, "rotation", 0.0f);
        numbers(t->second, "scale", out->scale, 2);
        out->texcoord = integer(t->second, "texCoord", out->texcoord);
    }
}

/* A textureInfo written inside an extension object (a Value, not parsed by tinygltf). */
void texture_ref_value(const tinygltf::Model &m, const tinygltf::Value &ext, const char *key,
                       const std::string &where, GltfTextureRef *out)
{
    if (!ext.IsObject() || !ext.Has(key) || !ext.Get(key).IsObject())
        return;
    const tinygltf::Value &info = ext.Get(key);
    tinygltf::ExtensionMap extensions;
    if (info.Has("extensions") && info.Get("extensions").IsObject())
        for (const std::string &k : info.Get("extensions").Keys())
            extensions[k] = info.Get("extensions").Get(k);
    texture_ref(m, integer(info, "index", -1), integer(info, "texCoord", 0), extensions, 1.0f,
                where + "." + key, out);
}

const tinygltf::Value *extension(const tinygltf::Material &mat, const char *name)
{
    auto it = mat.extensions.find(name);
    return it != mat.extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

void read_material(const tinygltf::Model &m, int i, GltfMaterial *g)
{
    const tinygltf::Material &mat = m.materials[i];
    gltf_material_default(g);
    snprintf(g->name, sizeof g->name, "%s", mat.name.c_str());
    snprintf(g->json_path, sizeof g->json_path, "materials[%d]", i);
    std::string at = g->json_path;
    const tinygltf::PbrMetallicRoughness &pbr = mat.pbrMetallicRoughness;
    for (int c = 0; c < 4 && pbr.baseColorFactor.size() == 4; c++)
        g->base_color[c] = (float)pbr.baseColorFactor[c];
    g->metallic = (float)pbr.metallicFactor;
    g->roughness = (float)pbr.roughnessFactor;
    texture_ref(m, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                pbr.baseColorTexture.extensions, 1.0f, at + ".pbrMetallicRoughness.baseColorTexture",
                &g->base_color_texture);
    texture_ref(m, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                pbr.metallicRoughnessTexture.extensions, 1.0f,
                at + ".pbrMetallicRoughness.metallicRoughnessTexture", &g->metallic_roughness_texture);
    texture_ref(m, mat.normalTexture.index, mat.normalTexture.texCoord, mat.normalTexture.extensions,
                (float)mat.normalTexture.scale, at + ".normalTexture", &g->normal_texture);
    texture_ref(m, mat.occlusionTexture.index, mat.occlusionTexture.texCoord,
                mat.occlusionTexture.extensions, (float)mat.occlusionTexture.strength,
                at + ".occlusionTexture", &g->occlusion_texture);
    texture_ref(m, mat.emissiveTexture.index, mat.emissiveTexture.texCoord,
                mat.emissiveTexture.extensions, 1.0f, at + ".emissiveTexture", &g->emissive_texture);
    for (int c = 0; c < 3 && mat.emissiveFactor.size() == 3; c++)
        g->emissive[c] = (float)mat.emissiveFactor[c];
    g->alpha_mode = mat.alphaMode == "MASK" ? GLTF_ALPHA_MASK
                    : mat.alphaMode == "BLEND" ? GLTF_ALPHA_BLEND : GLTF_ALPHA_OPAQUE;
    g->alpha_cutoff = (float)mat.alphaCutoff;
    g->double_sided = mat.doubleSided;
    const tinygltf::Value *e;
    if ((e = extension(mat, "KHR_materials_emissive_strength")))
        g->emissive_strength = number(*e, "emissiveStrength", 1.0f);
    if ((e = extension(mat, "KHR_materials_specular"))) {
        std::string ext = at + ".extensions.KHR_materials_specular";
        g->specular = number(*e, "specularFactor", 1.0f);
        numbers(*e, "specularColorFactor", g->specular_color, 3);
        texture_ref_value(m, *e, "specularTexture", ext, &g->specular_texture);
        texture_ref_value(m, *e, "specularColorTexture", ext, &g->specular_color_texture);
    }
    if ((e = extension(mat, "KHR_materials_transmission"))) {
        g->transmission = number(*e, "transmissionFactor", 0.0f);
        texture_ref_value(m, *e, "transmissionTexture", at + ".extensions.KHR_materials_transmission",
                          &g->transmission_texture);
    }
    if ((e = extension(mat, "KHR_materials_ior")))
        g->ior = number(*e, "ior", 1.5f);
    if ((e = extension(mat, "KHR_materials_volume"))) {
        g->has_volume = true;
        g->thickness = number(*e, "thicknessFactor", 0.0f);
        g->attenuation_distance = number(*e, "attenuationDistance", g->attenuation_distance);
        numbers(*e, "attenuationColor", g->attenuation_color, 3);
    }
}

std::string url_decode(const std::string &s)
{
    std::string out;
    for (size_t i = 0; i < s.size(); i++) {
        unsigned hex;
        if (s[i] == '%' && i + 2 < s.size() && sscanf(s.substr(i + 1, 2).c_str(), "%2x", &hex) == 1) {
            out += (char)hex;
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

} // namespace

extern "C" void gltf_material_default(GltfMaterial *m)
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

extern "C" bool gltf_read_materials(const GltfFile *file, GltfMaterial **materials, int *count,
                                    GltfImage **images, int *num_images)
{
    const tinygltf::Model &m = *static_cast<const tinygltf::Model *>(file->model);
    size_t nm = m.materials.size(), ni = m.images.size();
    /* One more material: the glTF default, for primitives that name none. */
    *materials = static_cast<GltfMaterial *>(calloc(nm + 1, sizeof(GltfMaterial)));
    *images = static_cast<GltfImage *>(calloc(ni ? ni : 1, sizeof(GltfImage)));
    if (!*materials || !*images)
        return false;
    for (size_t i = 0; i < nm; i++)
        read_material(m, (int)i, &(*materials)[i]);
    gltf_material_default(&(*materials)[nm]);
    snprintf((*materials)[nm].json_path, sizeof(*materials)[nm].json_path, "default material");
    *count = (int)nm + 1;
    const char *slash = strrchr(file->path, '/');
    std::string folder = slash ? std::string(file->path, (size_t)(slash - file->path)) : ".";
    for (size_t i = 0; i < ni; i++) {
        const tinygltf::Image &img = m.images[i];
        GltfImage *g = &(*images)[i];
        snprintf(g->json_path, sizeof g->json_path, "images[%zu]", i);
        snprintf(g->mime, sizeof g->mime, "%s", img.mimeType.c_str());
        if (!img.uri.empty() && img.uri.compare(0, 5, "data:") != 0) {
            std::string p = img.uri[0] == '/' ? url_decode(img.uri) : folder + "/" + url_decode(img.uri);
            snprintf(g->path, sizeof g->path, "%s", p.c_str());
        } else {
            g->bytes = img.image.data();
            g->size = img.image.size();
        }
    }
    *num_images = (int)ni;
    return true;
}
