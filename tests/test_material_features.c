// SPDX-License-Identifier: MIT
/* Which material features a scene uses (scene/materials.h material_features: what the kernels are
 * built for) and the automatic material-sorting choice it drives (render/session.h
 * session_sorts_materials: only where materials take more than one way through shading). */
#include <criterion/criterion.h>
#include <stdio.h>
#include <unistd.h>

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
    cr_expect_eq(wall, MATERIAL_FEATURE_SURFACE_DETAIL, "normal map: %#x", wall);
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
