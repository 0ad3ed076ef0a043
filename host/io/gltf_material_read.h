/* SPDX-License-Identifier: MIT */
/* gltf_material_read.h: a glTF 2.0 material as the file states it (core pbrMetallicRoughness and
 * the KHR material extensions pt reads), in plain C, read from the model io/gltf_loader.cc parsed
 * (host/io/gltf_material_read.cc, the only tinygltf code of materials). scene/gltf_material.h
 * checks the ranges and maps these to pt's materials, as scene/ maps the other readers' records.
 * Defaults are the glTF specification's. */
#ifndef PT_GLTF_MATERIAL_READ_H
#define PT_GLTF_MATERIAL_READ_H

#include <stdbool.h>
#include <stddef.h>

#include "io/gltf_loader.h"

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

/* The materials and images of a loaded file; the materials carry one more entry, the glTF default
 * material, used by primitives that name none. False: out of memory. */
bool gltf_read_materials(const GltfFile *file, GltfMaterial **materials, int *count,
                         GltfImage **images, int *num_images);

#endif
