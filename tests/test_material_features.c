// SPDX-License-Identifier: MIT
/* Which material features a scene uses (scene/materials.h material_features: what the kernels are
 * built for) and the automatic material-sorting choice it drives (render/session.h
 * session_sorts_materials: only where materials take more than one way through shading). */
#include <criterion/criterion.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include <stb_image_write.h>

#include "render/session.h"
#include "scene/scene.h"
#include "support.h"

static uint32_t features_of(const char *path, Scene *scene)
{
    Error err = {0};
    cr_assert(scene_load(path, scene, &err), "%s", err.message);
    return material_features(scene->data.materials, scene->data.num_materials, &scene->data.textures);
}

Test(material_features, each_scene_reports_what_it_uses)
{
    Scene s;
    cr_expect_eq(features_of("scenes/cornell-box/scene.json", &s), 0u, "Lambert only");
    cr_expect(!session_sorts_materials(&s.data, SORT_MATERIALS_AUTO), "plain boxes are not sorted");
    cr_expect(session_sorts_materials(&s.data, SORT_MATERIALS_ON));
    scene_free(&s);
    cr_expect_eq(features_of("scenes/cornell-box/sphere.json", &s), MATERIAL_FEATURE_REFRACTION,
                 "smooth glass and a Fresnel-1 mirror need only the refraction's roulette");
    cr_expect(!session_sorts_materials(&s.data, SORT_MATERIALS_AUTO), "nor sorting");
    scene_free(&s);
    uint32_t mix = features_of("tests/scenes/mix/scene.json", &s);
    cr_expect_eq(mix, MATERIAL_FEATURE_MIX | MATERIAL_FEATURE_ROUGH_CONDUCTOR | MATERIAL_FEATURE_CONDUCTOR_FRESNEL,
                 "mix: %#x", mix);
    cr_expect(session_sorts_materials(&s.data, SORT_MATERIALS_AUTO), "feature scenes are sorted");
    cr_expect(!session_sorts_materials(&s.data, SORT_MATERIALS_OFF));
    scene_free(&s);
    uint32_t glass = features_of("tests/scenes/glass/scene.json", &s);
    cr_expect_eq(glass, MATERIAL_FEATURE_ROUGH_DIELECTRIC | MATERIAL_FEATURE_ABSORPTION |
                            MATERIAL_FEATURE_REFRACTION, "glass: %#x", glass);
    scene_free(&s);
    uint32_t copper = features_of("tests/scenes/conductors/scene.json", &s);
    cr_expect_eq(copper, MATERIAL_FEATURE_ROUGH_CONDUCTOR | MATERIAL_FEATURE_CONDUCTOR_FRESNEL |
                             MATERIAL_FEATURE_SURFACE_DETAIL, "conductors: %#x", copper);
    scene_free(&s);
    uint32_t wall = features_of("tests/scenes/normalmap/scene.json", &s);
    cr_expect_eq(wall, MATERIAL_FEATURE_TEXTURE | MATERIAL_FEATURE_SURFACE_DETAIL, "normal map: %#x",
                 wall);
    /* One kind of shading: the light only emits. */
    cr_expect(!session_sorts_materials(&s.data, SORT_MATERIALS_AUTO), "normal-mapped wall, a lamp");
    scene_free(&s);
}

/* A normal-mapped floor and a quad whose material is given (the MTL's lamp, or JSON): sorting
 * pays only where materials take more than one way through shading, those that scatter nothing
 * (lamps) aside. */
static bool sorts_floor_and_quad(const char *quad_json)
{
    const char *dir = test_temp_dir();
    char json[1024], cwd[512];
    cr_assert(getcwd(cwd, sizeof cwd));
    test_write_file(dir, "m.obj",
                    "mtllib m.mtl\nv 0 0 0\nv 8 0 0\nv 8 0 8\nv 0 0 8\n"
                    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl floor\nf 1/1 4/4 3/3 2/2\n"
                    "v 0 2 0\nv 1 2 0\nv 1 2 1\nv 0 2 1\nusemtl quad\nf 5 6 7 8\n");
    test_write_file(dir, "m.mtl",
                    "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl quad\nKd 0 0 0\nKe 5 5 5\n");
    snprintf(json, sizeof json,
             "{\"textures\": {\"n\": {\"file\": \"%s/tests/scenes/normalmap/normals.png\", "
             "\"encoding\": \"linear\"}}, \"materials\": {\"floor\": {\"type\": \"diffuse\", "
             "\"albedo\": [0.5, 0.5, 0.5], \"normal_map\": \"n\"}%s%s}, "
             "\"objects\": [{\"obj\": \"m.obj\"}]}",
             cwd, quad_json ? ", \"quad\": " : "", quad_json ? quad_json : "");
    const char *path = test_write_file(dir, "scene.json", json);
    Scene scene;
    Error err = {0};
    cr_assert(scene_load(path, &scene, &err), "%s", err.message);
    bool sorts = session_sorts_materials(&scene.data, SORT_MATERIALS_AUTO);
    scene_free(&scene);
    return sorts;
}

Test(material_features, sorting_needs_a_second_kind_of_shading)
{
    cr_expect(!sorts_floor_and_quad(NULL), "a normal-mapped floor under the MTL's lamp");
    cr_expect(!sorts_floor_and_quad("{\"type\": \"diffuse\", \"albedo\": [0, 0, 0], "
                                    "\"emission\": [5, 5, 5], \"normal_map\": \"n\"}"),
              "a lamp that is normal-mapped too");
    cr_expect(sorts_floor_and_quad("{\"type\": \"conductor\", \"roughness\": 0.3}"),
              "a rough metal quad");
    cr_expect(sorts_floor_and_quad("{\"type\": \"diffuse\", \"albedo\": [0.5, 0.5, 0.5]}"),
              "a plain diffuse quad (no normal map: another way)");
    cr_expect(!sorts_floor_and_quad("{\"type\": \"diffuse\", \"albedo\": [0, 0, 0]}"),
              "a black quad scatters nothing either");
}

/* Features of one diffuse quad whose material reads textures of the given JSON (name "t" for the
 * albedo, "n" for the normal map, "b" for a bump map; NULL leaves the slot constant). */
static uint32_t texture_features(const char *albedo, const char *normal, const char *bump)
{
    const char *dir = test_temp_dir();
    const unsigned char rgb[] = {200, 100, 50};
    char png[512], hdr[512];
    snprintf(png, sizeof png, "%s/t.png", dir);
    snprintf(hdr, sizeof hdr, "%s/t.hdr", dir);
    cr_assert(stbi_write_png(png, 1, 1, 3, rgb, 3));
    const float one[] = {1.0f, 0.5f, 0.25f};
    cr_assert(stbi_write_hdr(hdr, 1, 1, 3, one));
    test_write_file(dir, "q.obj",
                    "v 0 0 0\nv 1 0 0\nv 1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n");
    char textures[1024] = "", material[512] = "\"type\": \"diffuse\"";
    const char *json[3] = {albedo, normal, bump}, *slot[3] = {"albedo", "normal_map", "bump_map"};
    const char *name[3] = {"t", "n", "b"};
    for (int i = 0; i < 3; i++) {
        if (!json[i])
            continue;
        size_t used = strlen(textures);
        snprintf(textures + used, sizeof textures - used, "%s\"%s\": %s", used ? ", " : "", name[i],
                 json[i]);
        used = strlen(material);
        snprintf(material + used, sizeof material - used, ", \"%s\": \"%s\"", slot[i], name[i]);
    }
    char scene_json[2048];
    snprintf(scene_json, sizeof scene_json,
             "{\"textures\": {%s}, \"materials\": {\"m\": {%s}}, "
             "\"objects\": [{\"obj\": \"q.obj\", \"material\": \"m\"}]}",
             textures, material);
    Scene scene;
    uint32_t features = features_of(test_write_file(dir, "scene.json", scene_json), &scene);
    scene_free(&scene);
    return features;
}

/* Texture lookups, each texel format, glTF's sampling and bump maps keep their code only where a
 * texture needs them (cl/material/texture.cl inlines a lookup at every call site). */
Test(material_features, textures_report_their_format_sampling_and_bump)
{
    enum {
        TEX = MATERIAL_FEATURE_TEXTURE,
        SRGB = MATERIAL_FEATURE_SRGB_TEXTURE,
        FLOAT = MATERIAL_FEATURE_FLOAT_TEXTURE,
        SAMPLER = MATERIAL_FEATURE_TEXTURE_SAMPLER,
        DETAIL = MATERIAL_FEATURE_SURFACE_DETAIL,
        BUMP = MATERIAL_FEATURE_BUMP_MAP
    };
    uint32_t f = texture_features("{\"file\": \"t.png\"}", NULL, NULL);
    cr_expect_eq(f, TEX | SRGB, "an 8-bit colour image is sRGB: %#x", f);
    f = texture_features("{\"file\": \"t.png\", \"encoding\": \"linear\"}", NULL, NULL);
    cr_expect_eq(f, TEX, "8-bit linear is the plain lookup: %#x", f);
    f = texture_features("{\"file\": \"t.hdr\"}", NULL, NULL);
    cr_expect_eq(f, TEX | FLOAT, "a Radiance image is float: %#x", f);
    f = texture_features("{\"file\": \"t.png\", \"encoding\": \"linear\", \"wrap\": \"clamp\"}", NULL,
                         NULL);
    cr_expect_eq(f, TEX | SAMPLER, "a wrap mode: %#x", f);
    f = texture_features("{\"file\": \"t.png\", \"encoding\": \"linear\", \"filter\": \"nearest\"}",
                         NULL, NULL);
    cr_expect_eq(f, TEX | SAMPLER, "nearest: %#x", f);
    f = texture_features(NULL, "{\"file\": \"t.png\", \"encoding\": \"linear\"}", NULL);
    cr_expect_eq(f, TEX | DETAIL, "a normal map without bump: %#x", f);
    f = texture_features(NULL, NULL, "{\"file\": \"t.png\", \"encoding\": \"linear\"}");
    cr_expect_eq(f, TEX | DETAIL | BUMP, "a bump map: %#x", f);
    f = texture_features("{\"file\": \"t.hdr\"}", "{\"file\": \"t.png\", \"encoding\": \"linear\"}",
                         "{\"file\": \"t.png\"}");
    cr_expect_eq(f, TEX | FLOAT | SRGB | DETAIL | BUMP, "all three: %#x", f);
}
