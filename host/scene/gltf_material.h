/* SPDX-License-Identifier: MIT */
/* gltf_material.h: a glTF 2.0 material as the file states it (io/gltf_material_read.h) mapped to
 * pt's materials and textures (gltf_material.c). The mapping appends the scene's MaterialDesc and
 * TextureDesc entries, so materials_load and textures_load treat an imported material like a JSON
 * one. */
#ifndef PT_GLTF_MATERIAL_H
#define PT_GLTF_MATERIAL_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"
#include "io/gltf_material_read.h"
#include "scene/material_json.h"
#include "scene/texture_json.h"

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
