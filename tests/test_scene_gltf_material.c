// SPDX-License-Identifier: MIT
/* glTF materials (host/scene/gltf_material.c), through gltf_materials_append as the glTF loader
 * calls it: each feature maps to the Material that the equivalent JSON material loads to (field
 * by field, textures by their sampling and texels): metallic-roughness factors and the
 * metallicRoughnessTexture's g and b channels times them, the normal map's scale, emission with
 * KHR_materials_emissive_strength, the alpha modes, KHR_materials_specular and _ior, transmission
 * with KHR_materials_volume's absorption (a dielectric, or a mix by the transmission). Textures
 * sampled alike are shared; embedded images decode like files; bad input names the glTF file, the
 * image and its user. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image_write.h>

#include "gltf_material_fixture.h"

/* 2 x 2 images: base (RGBA, alpha 0.2 .. 1), mr (g and b differ), normal (rgb), emissive (rgb). */
static const unsigned char BASE_PX[] = {200, 100, 50, 51, 20, 40, 60, 255, 255, 0, 0, 128, 0, 255, 0, 204};
static const unsigned char MR_PX[] = {0, 50, 200, 255, 0, 100, 150, 255, 0, 150, 100, 255, 0, 200, 50, 255};
static const unsigned char NORMAL_PX[] = {128, 128, 255, 100, 128, 230, 128, 100, 255, 128, 200, 128};
static const unsigned char EMIT_PX[] = {255, 255, 255, 10, 20, 30, 0, 0, 0, 128, 64, 32};

static void write_images(void)
{
    cr_assert(stbi_write_png(fixture_path("base.png"), 2, 2, 4, BASE_PX, 8));
    cr_assert(stbi_write_png(fixture_path("mr.png"), 2, 2, 4, MR_PX, 8));
    cr_assert(stbi_write_png(fixture_path("normal.png"), 2, 2, 3, NORMAL_PX, 6));
    cr_assert(stbi_write_png(fixture_path("emit.png"), 2, 2, 3, EMIT_PX, 6));
}

Test(gltf_material, factors_map_to_principled)
{
    GltfMaterial g;
    gltf_material_default(&g);
    float base[4] = {0.5f, 0.25f, 0.125f, 1.0f};
    memcpy(g.base_color, base, sizeof base);
    g.metallic = 0.3f, g.roughness = 0.6f, g.specular = 0.4f, g.ior = 1.33f;
    g.specular_color[1] = 0.5f, g.specular_color[2] = 0.25f;
    g.emissive[0] = 1.0f, g.emissive[1] = 0.5f, g.emissive_strength = 2.0f;
    expect_gltf_equals_json(&g, 1, NULL, 0,
                            "\"m\": {\"type\": \"principled\", \"base_color\": [0.5, 0.25, 0.125], "
                            "\"metallic\": 0.3, \"roughness\": 0.6, \"specular\": 0.4, "
                            "\"specular_color\": [1, 0.5, 0.25], \"ior\": 1.33, "
                            "\"emission\": [1, 0.5, 0], \"emission_strength\": 2}",
                            "", "factors");
}

Test(gltf_material, textures_map_with_channels_factors_and_scale)
{
    write_images();
    GltfImage images[4];
    fixture_file_images(images, (const char *[]){"base.png", "mr.png", "normal.png", "emit.png"}, 4);
    GltfMaterial g;
    gltf_material_default(&g);
    g.base_color_texture.image = 0;
    g.metallic_roughness_texture.image = 1;
    g.metallic = 0.5f, g.roughness = 0.8f;
    g.normal_texture.image = 2;
    g.normal_texture.amount = 0.7f;
    g.emissive_texture.image = 3;
    g.emissive[0] = g.emissive[1] = g.emissive[2] = 1.0f;
    g.emissive_strength = 3.0f;
    expect_gltf_equals_json(
        &g, 1, images, 4,
        "\"m\": {\"type\": \"principled\", \"base_color\": \"base\", \"roughness\": \"rough\", "
        "\"metallic\": \"metal\", \"normal_map\": \"normal\", \"bump_scale\": 0.7, "
        "\"emission\": \"emit\", \"emission_strength\": 3}",
        "\"base\": {\"file\": \"base.png\", \"encoding\": \"srgb\"}, "
        "\"rough\": {\"file\": \"mr.png\", \"encoding\": \"linear\", \"channel\": \"g\", \"scale\": 0.8}, "
        "\"metal\": {\"file\": \"mr.png\", \"encoding\": \"linear\", \"channel\": \"b\", \"scale\": 0.5}, "
        "\"normal\": {\"file\": \"normal.png\", \"encoding\": \"linear\"}, "
        "\"emit\": {\"file\": \"emit.png\", \"encoding\": \"srgb\"}",
        "textures");
}

Test(gltf_material, sampler_and_texture_transform_map_to_texture_keys)
{
    write_images();
    GltfImage images[1];
    fixture_file_images(images, (const char *[]){"base.png"}, 1);
    GltfMaterial g;
    gltf_material_default(&g);
    GltfTextureRef *t = &g.base_color_texture;
    t->image = 0;
    t->wrap_s = GLTF_WRAP_CLAMP, t->wrap_t = GLTF_WRAP_MIRROR, t->nearest = true;
    /* No rotation, scale (2, 0.5), offset (0.25, 0.1) in glTF's frame is, in pt's (v up),
     * u' = 2 u + 0.25, v' = 0.5 v + (1 - 0.5 - 0.1) = 0.5 v + 0.4. */
    t->has_transform = true, t->scale[0] = 2.0f, t->scale[1] = 0.5f;
    t->offset[0] = 0.25f, t->offset[1] = 0.1f;
    g.roughness = 0.5f, g.metallic = 0.0f;
    expect_gltf_equals_json(
        &g, 1, images, 1,
        "\"m\": {\"type\": \"principled\", \"base_color\": \"base\", \"roughness\": 0.5}",
        "\"base\": {\"file\": \"base.png\", \"wrap\": [\"clamp\", \"mirror\"], \"filter\": "
        "\"nearest\", \"transform\": {\"offset\": [0.25, 0.4], \"scale\": [2, 0.5]}}",
        "sampler and transform");
}

Test(gltf_material, alpha_blend_and_mask_read_the_base_alpha)
{
    write_images();
    GltfImage images[1];
    fixture_file_images(images, (const char *[]){"base.png"}, 1);
    GltfMaterial g;
    gltf_material_default(&g);
    g.base_color_texture.image = 0;
    g.base_color[3] = 0.5f;
    g.roughness = 0.5f, g.metallic = 0.0f;
    const char *textures =
        "\"base\": {\"file\": \"base.png\"}, "
        "\"alpha\": {\"file\": \"base.png\", \"channel\": \"a\", \"scale\": 0.5}";
    g.alpha_mode = GLTF_ALPHA_BLEND;
    expect_gltf_equals_json(&g, 1, images, 1,
                            "\"m\": {\"type\": \"principled\", \"base_color\": \"base\", "
                            "\"roughness\": 0.5, \"opacity\": \"alpha\"}",
                            textures, "BLEND");
    g.alpha_mode = GLTF_ALPHA_MASK;
    g.alpha_cutoff = 0.4f;
    expect_gltf_equals_json(&g, 1, images, 1,
                            "\"m\": {\"type\": \"principled\", \"base_color\": \"base\", "
                            "\"roughness\": 0.5, \"opacity\": \"alpha\", \"alpha_cutoff\": 0.4}",
                            textures, "MASK");
    /* OPAQUE: the texture's alpha (0.2 in a texel) is ignored. */
    g.alpha_mode = GLTF_ALPHA_OPAQUE;
    expect_gltf_equals_json(&g, 1, images, 1,
                            "\"m\": {\"type\": \"principled\", \"base_color\": \"base\", "
                            "\"roughness\": 0.5}",
                            "\"base\": {\"file\": \"base.png\"}", "OPAQUE");
}

Test(gltf_material, alpha_without_texture_is_a_constant)
{
    GltfMaterial g;
    gltf_material_default(&g);
    g.base_color[3] = 0.3f;
    g.alpha_mode = GLTF_ALPHA_BLEND;
    Material m = fixture_gltf_one(&g);
    cr_expect(fabsf(m.opacity - 0.3f) < 1e-7f && (m.flags & MATERIAL_FLAG_CUTOUT), "BLEND %g", m.opacity);
    g.alpha_mode = GLTF_ALPHA_MASK;
    m = fixture_gltf_one(&g);
    cr_expect(m.opacity == 0.0f && (m.flags & MATERIAL_FLAG_CUTOUT), "MASK below: %g", m.opacity);
    g.alpha_cutoff = 0.25f;
    m = fixture_gltf_one(&g);
    cr_expect(m.opacity == 1.0f && !(m.flags & MATERIAL_FLAG_CUTOUT), "MASK above: %g", m.opacity);
}

Test(gltf_material, full_transmission_is_an_absorbing_dielectric)
{
    GltfMaterial g;
    gltf_material_default(&g);
    g.transmission = 1.0f, g.metallic = 0.0f, g.roughness = 0.2f, g.ior = 1.4f;
    g.base_color[0] = 0.9f, g.base_color[1] = 0.8f, g.base_color[2] = 0.7f;
    g.has_volume = true, g.attenuation_distance = 2.0f;
    g.attenuation_color[0] = 0.5f, g.attenuation_color[1] = 0.25f;
    /* sigma = -ln(colour) / distance: ln 2 / 2, ln 4 / 2, 0. */
    expect_gltf_equals_json(&g, 1, NULL, 0,
                            "\"m\": {\"type\": \"dielectric\", \"ior\": 1.4, \"roughness\": 0.2, "
                            "\"tint\": [0.9, 0.8, 0.7], \"absorption\": [0.34657359, 0.69314718, 0]}",
                            "", "transmission 1");
}

/* Metallic 0.5: only the dielectric half transmits: weight 0.3, the surface's metallic 0.5 / 0.7
 * so that the metal keeps half of the whole. Emission sits on the mix (what the triangles name). */
Test(gltf_material, partial_transmission_mixes_surface_and_dielectric)
{
    static const struct {
        float metallic, emissive;
        const char *mix, *surface_metallic;
    } cases[] = {
        {0.0f, 0.5f, "\"weight\": 0.6, \"emission\": [0.5, 0, 0]", "0"},
        {0.5f, 0.0f, "\"weight\": 0.3", "0.71428571"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        GltfMaterial g;
        gltf_material_default(&g);
        g.transmission = 0.6f, g.metallic = cases[i].metallic, g.roughness = 0.3f;
        g.emissive[0] = cases[i].emissive;
        char json[1024];
        snprintf(json, sizeof json,
                 "\"m\": {\"type\": \"mix\", \"a\": \"s\", \"b\": \"t\", %s}, "
                 "\"s\": {\"type\": \"principled\", \"metallic\": %s, \"roughness\": 0.3}, "
                 "\"t\": {\"type\": \"dielectric\", \"roughness\": 0.3}",
                 cases[i].mix, cases[i].surface_metallic);
        expect_gltf_equals_json(&g, 1, NULL, 0, json, "", cases[i].mix);
    }
}

Test(gltf_material, transmission_texture_is_the_mix_weight)
{
    write_images();
    GltfImage images[1];
    fixture_file_images(images, (const char *[]){"mr.png"}, 1);
    GltfMaterial g;
    gltf_material_default(&g);
    g.transmission = 0.5f, g.metallic = 0.0f, g.roughness = 0.3f;
    g.transmission_texture.image = 0;
    expect_gltf_equals_json(&g, 1, images, 1,
                            "\"m\": {\"type\": \"mix\", \"a\": \"s\", \"b\": \"t\", \"weight\": \"w\"}, "
                            "\"s\": {\"type\": \"principled\", \"metallic\": 0, \"roughness\": 0.3}, "
                            "\"t\": {\"type\": \"dielectric\", \"roughness\": 0.3}",
                            "\"w\": {\"file\": \"mr.png\", \"encoding\": \"linear\", \"scale\": 0.5}",
                            "transmission texture");
}
