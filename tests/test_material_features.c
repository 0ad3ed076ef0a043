// SPDX-License-Identifier: MIT
/* Which material features a scene uses (scene/materials.h material_features: what the kernels are
 * built for) and the automatic material-sorting choice it drives (render/session.h
 * session_sorts_materials: only where a second way through shading covers enough of the area). */
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
    /* Its plain light is 14% of the area: a second kind of shading worth sorting for. */
    cr_expect(session_sorts_materials(&s.data, SORT_MATERIALS_AUTO), "normal-mapped wall, large light");
    scene_free(&s);
}

/* A normal-mapped floor of side `floor` and a plain quad of side 1 that emits, or that is a rough
 * metal: sorting pays only where another way through shading covers 5% of the area or more. */
static bool sorts_floor_and_quad(float floor, bool metal_quad)
{
    const char *dir = test_temp_dir();
    char obj[512], json[1024], cwd[512];
    cr_assert(getcwd(cwd, sizeof cwd));
    snprintf(obj, sizeof obj,
             "mtllib m.mtl\nv 0 0 0\nv %g 0 0\nv %g 0 %g\nv 0 0 %g\n"
             "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl floor\nf 1/1 4/4 3/3 2/2\n"
             "v 0 2 0\nv 1 2 0\nv 1 2 1\nv 0 2 1\nusemtl quad\nf 5 6 7 8\n",
             floor, floor, floor, floor);
    test_write_file(dir, "m.obj", obj);
    test_write_file(dir, "m.mtl", "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl quad\nKd 0 0 0\nKe 5 5 5\n");
    snprintf(json, sizeof json,
             "{\"textures\": {\"n\": {\"file\": \"%s/tests/scenes/normalmap/normals.png\", "
             "\"encoding\": \"linear\"}},"
             " \"materials\": {\"floor\": {\"type\": \"diffuse\", \"albedo\": [0.5, 0.5, 0.5], "
             "\"normal_map\": \"n\"}%s},"
             " \"objects\": [{\"obj\": \"m.obj\"}]}",
             cwd, metal_quad ? ", \"quad\": {\"type\": \"conductor\", \"roughness\": 0.3}" : "");
    const char *path = test_write_file(dir, "scene.json", json);
    Scene scene;
    Error err = {0};
    cr_assert(scene_load(path, &scene, &err), "%s", err.message);
    bool sorts = session_sorts_materials(&scene.data, SORT_MATERIALS_AUTO);
    scene_free(&scene);
    return sorts;
}

Test(material_features, sorting_needs_a_second_kind_of_shading_on_5_percent_of_the_area)
{
    /* The light (1) against the floor (64, 16, 4): 1.5%, 5.9%, 20% of the area. */
    cr_expect(!sorts_floor_and_quad(8.0f, false), "a normal-mapped room under a small light");
    cr_expect(sorts_floor_and_quad(4.0f, false), "the light at 5.9% of the area");
    cr_expect(sorts_floor_and_quad(2.0f, false), "the light at 20% of the area");
    /* A rough metal quad is another kind: sorted for when it is large, not when it is small. */
    cr_expect(!sorts_floor_and_quad(8.0f, true), "a small metal quad");
    cr_expect(sorts_floor_and_quad(2.0f, true), "a metal quad at 20% of the area");
}
