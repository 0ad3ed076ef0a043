/* SPDX-License-Identifier: MIT */
/* gltf_material.h: a glTF 2.0 material as the file states it (core pbrMetallicRoughness and the
 * KHR material extensions pt reads), in plain C, and its mapping to pt's materials and textures
 * (gltf_material.c). The glTF loader (io/gltf_loader.cc) fills these from the file; the mapping
 * appends the scene's MaterialDesc and TextureDesc entries, so materials_load and textures_load
 * treat an imported material like a JSON one. Defaults are the glTF specification's. */
#ifndef PT_GLTF_MATERIAL_H
#define PT_GLTF_MATERIAL_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"
#include "scene/material_json.h"
#include "scene/texture_json.h"

/* An image of the file: encoded bytes (PNG, JPEG) embedded in the GLB or a data URI, or a file
 * resolved against the glTF's folder. */
typedef struct {
    const unsigned char *bytes; /* embedded: owned by the loader, valid until gltf_scene_free */
    size_t size;
    char path[1024];            /* external file, "" when embedded */
    char mime[32];              /* "image/png", "image/jpeg", "" when not stated */
    char json_path[64];         /* "images[3]", for messages */
} GltfImage;

/* GL sampler wrap modes (glTF samplers[].wrapS / wrapT). */
enum { GLTF_WRAP_REPEAT = 10497, GLTF_WRAP_CLAMP = 33071, GLTF_WRAP_MIRROR = 33648 };

/* A textureInfo: which image, through which sampler, with KHR_texture_transform. */
typedef struct {
    int image;            /* index into the images, -1: no texture */
    int texcoord;         /* TEXCOORD_n (pt reads TEXCOORD_0 only: others warn) */
    int wrap_s, wrap_t;   /* GLTF_WRAP_*, default REPEAT */
    bool nearest;         /* magFilter NEAREST */
    bool has_transform;   /* KHR_texture_transform */
    float offset[2], rotation, scale[2]; /* default 0, 0, 0, 1 1 */
    float amount;         /* normalTexture.scale or occlusionTexture.strength; 1 otherwise */
    char json_path[96];   /* "materials[2].pbrMetallicRoughness.baseColorTexture", for messages */
} GltfTextureRef;

enum { GLTF_ALPHA_OPAQUE, GLTF_ALPHA_MASK, GLTF_ALPHA_BLEND };

typedef struct {
    char name[128];           /* the material's name, or "" */
    float base_color[4];      /* default 1 1 1 1 */
    GltfTextureRef base_color_texture;          /* sRGB, rgba */
    float metallic, roughness;                  /* default 1, 1 */
    GltfTextureRef metallic_roughness_texture;  /* linear: G roughness, B metallic */
    GltfTextureRef normal_texture;              /* linear, amount = scale */
    GltfTextureRef occlusion_texture;           /* read for completeness; pt ignores it */
    float emissive[3];                          /* default 0 0 0 */
    GltfTextureRef emissive_texture;            /* sRGB */
    float emissive_strength;                    /* KHR_materials_emissive_strength, default 1 */
    int alpha_mode;                             /* GLTF_ALPHA_* */
    float alpha_cutoff;                         /* default 0.5 */
    bool double_sided;
    /* KHR_materials_specular */
    float specular;                             /* specularFactor, default 1 */
    GltfTextureRef specular_texture;            /* A channel */
    float specular_color[3];                    /* default 1 1 1 */
    GltfTextureRef specular_color_texture;      /* sRGB rgb */
    /* KHR_materials_transmission, KHR_materials_ior, KHR_materials_volume */
    float transmission;                         /* default 0 */
    GltfTextureRef transmission_texture;        /* R channel */
    float ior;                                  /* default 1.5 */
    bool has_volume;
    float thickness;                            /* thicknessFactor */
    float attenuation_distance;                 /* default +inf */
    float attenuation_color[3];                 /* default 1 1 1 */
    char json_path[32];                         /* "materials[2]" */
} GltfMaterial;

/* The glTF defaults above (an absent material is gltf_material_default's). */
void gltf_material_default(GltfMaterial *m);

/* Appends a MaterialDesc per glTF material (and the TextureDescs they need) to *materials and
 * *textures (malloc'ed arrays, grown; counts updated); the material of glTF index i is then
 * (*materials)[first + i], first being *num_materials on entry. Material names are
 * "<prefix>materials[i]" so that they cannot collide with JSON names. Errors name gltf_path and
 * the JSON path (missing image, out-of-range index, a value outside its range).
 * The descs index each other as JSON ones do: tex[] slots index *textures and a mix's a and b
 * index *materials, both from the arrays' start, so the whole arrays go to textures_load and
 * materials_load (first 0) together. An embedded image's bytes are borrowed by its TextureDesc
 * until textures_load has run.
 * The mapping (what a glTF viewer shows):
 * - pbrMetallicRoughness -> principled; metallicRoughnessTexture's b (metallic) and g (roughness)
 *   times their factors; baseColorTexture (sRGB) times baseColorFactor.
 * - KHR_materials_transmission T -> a dielectric (ior, roughness, base colour as tint, Beer-Lambert
 *   absorption -ln(attenuationColor) / attenuationDistance) when T = 1, else a mix of the
 *   principled ("<name>/surface") and the dielectric ("<name>/transmission") by T (times
 *   transmissionTexture's r), both appended after the count top-level materials. pt refracts at
 *   every transmissive surface: a thin-walled glTF material (no KHR_materials_volume) should be a
 *   closed mesh. KHR_materials_specular's textures are not read (a warning; the factors apply).
 * - Emission, normal map and alpha sit on the top-level material (what the triangles name).
 *   doubleSided changes nothing: pt's surfaces scatter on both sides whatever it says (glTF's
 *   back-face culling of single-sided materials is a rasteriser's saving, not a look), and
 *   emission stays one-sided on the front (counter-clockwise) side, as for every pt emitter.
 * - uv: pt's v runs up the image (v = 0 its bottom row), glTF's down: the loader gives pt
 *   v = 1 - TEXCOORD_0.v, and KHR_texture_transform is converted to that frame here. */
bool gltf_materials_append(const GltfMaterial *gltf, int count, const GltfImage *images,
                           int num_images, const char *gltf_path, const char *prefix,
                           MaterialDesc **materials, int *num_materials, TextureDesc **textures,
                           int *num_textures, Error *err);

#endif
