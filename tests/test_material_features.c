// SPDX-License-Identifier: MIT
/* Which material features a scene uses (scene/materials.h material_features: what the kernels are
 * built for) and the automatic material-sorting choice it drives (render/session.h
 * session_sorts_materials). */
#include <criterion/criterion.h>

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
    scene_free(&s);
}
