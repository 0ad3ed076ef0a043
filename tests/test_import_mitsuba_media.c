// SPDX-License-Identifier: MIT
/* The Mitsuba 3 importer's media (host/scene/mitsuba_media.c): homogeneous media (sigma_t/albedo
 * and Mitsuba 0.6's sigma_a/sigma_s, scale, hg), heterogeneous gridvolume media placed where
 * Mitsuba puts them (use_grid_bbox false: the unit cube; true: the file's box), shapes' interior /
 * exterior by nested medium or ref, the sensor's medium, the null bsdf as pt's interface; the
 * imported scene loads, and bad media are one line naming the element. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "mitsuba_import.h"
#include "scene/scene.h"
#include "media_fixtures.h"
#include "support.h"

static const char *write_in(const char *name, const char *text)
{
    return test_write_file(scene_dir, name, text);
}

/* A .vol in the scene folder (made after import_body chose it: imports read it there), 2^3
 * voxels of 1 over the box [lo, hi]^3. */
static void write_vol(const char *dir, const char *name, float lo, float hi)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    const float ones[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    write_vol_file(path, 2, 2, 2, ones, (const float[3]){lo, lo, lo}, (const float[3]){hi, hi, hi});
}

#define CUBE_WITH(media) "<shape type=\"cube\"><bsdf type=\"null\"/>" media "</shape>"

Test(import_mitsuba_media, homogeneous_interior_exterior_and_sensor)
{
    ImportedScene s;
    Error err = {0};
    cr_assert(import_body(
                  "<medium type=\"homogeneous\" id=\"fog\"><rgb name=\"sigma_t\" value=\"1, 2, 4\"/>"
                  "<rgb name=\"albedo\" value=\"0.5, 0.25, 1\"/><float name=\"scale\" value=\"3\"/>"
                  "<phase type=\"hg\"><float name=\"g\" value=\"0.4\"/></phase></medium>"
                  "<sensor type=\"perspective\"><ref id=\"fog\"/><film type=\"hdrfilm\"><rfilter "
                  "type=\"box\"/></film></sensor>"
                  CUBE_WITH("<ref name=\"interior\" id=\"fog\"/>"
                            "<medium type=\"homogeneous\" name=\"exterior\"><float name=\"sigma_a\" "
                            "value=\"0.1\"/><float name=\"sigma_s\" value=\"0.2\"/></medium>"),
                  &s, &err),
              "%s", err.message);
    const cJSON *fog = get(s.root, "media.fog");
    cr_expect_str_eq(get(fog, "type")->valuestring, "homogeneous");
    /* sigma_s = albedo sigma_t, sigma_a = (1 - albedo) sigma_t; scale kept as pt's scale. */
    expect_near(num(fog, "sigma_s.0"), 0.5, "sigma_s r");
    expect_near(num(fog, "sigma_s.1"), 0.5, "sigma_s g");
    expect_near(num(fog, "sigma_s.2"), 4.0, "sigma_s b");
    expect_near(num(fog, "sigma_a.0"), 0.5, "sigma_a r");
    expect_near(num(fog, "sigma_a.1"), 1.5, "sigma_a g");
    expect_near(num(fog, "sigma_a.2"), 0.0, "sigma_a b");
    expect_near(num(fog, "scale"), 3.0, "scale");
    expect_near(num(fog, "g"), 0.4, "g");
    cr_expect_str_eq(get(s.root, "camera.medium")->valuestring, "fog");
    const cJSON *cube = get(s.root, "objects.0");
    cr_expect_str_eq(get(cube, "interior")->valuestring, "fog");
    const char *outside = get(cube, "exterior")->valuestring;
    const cJSON *ext = get(get(s.root, "media"), outside);
    expect_near(num(ext, "sigma_a.0"), 0.1, "0.6's sigma_a");
    expect_near(num(ext, "sigma_s.2"), 0.2, "0.6's sigma_s");
    expect_near(num(ext, "g"), 0.0, "no phase: isotropic");
    const cJSON *material = material_of(&s, 0);
    cr_expect_str_eq(get(material, "type")->valuestring, "interface", "null bsdf");
    cr_expect_eq(cJSON_GetArraySize(material), 1, "an interface has no other keys");
    imported_scene_free(&s);
}

Test(import_mitsuba_media, grid_placed_as_mitsuba_places_it)
{
    ImportedScene s;
    Error err = {0};
    /* import_body picks the folder; the .vol must be there before the import reads its box. */
    scene_dir = test_temp_dir();
    write_vol(scene_dir, "smoke.vol", -2.0f, 2.0f);
    char text[4096];
    snprintf(text, sizeof text,
             "<scene version=\"3.0.0\"><medium type=\"heterogeneous\" id=\"smoke\">"
             "<volume type=\"gridvolume\" name=\"sigma_t\"><string name=\"filename\" "
             "value=\"smoke.vol\"/><transform name=\"to_world\"><scale value=\"2\"/></transform>"
             "</volume><float name=\"scale\" value=\"5\"/><rgb name=\"albedo\" value=\"0.9\"/>"
             "</medium><medium type=\"heterogeneous\" id=\"boxed\">"
             "<volume type=\"gridvolume\" name=\"sigma_t\"><string name=\"filename\" "
             "value=\"smoke.vol\"/><boolean name=\"use_grid_bbox\" value=\"true\"/></volume>"
             "</medium>%s%s</scene>",
             CUBE_WITH("<ref name=\"interior\" id=\"smoke\"/>"),
             CUBE_WITH("<ref name=\"interior\" id=\"boxed\"/>"));
    memset(&s, 0, sizeof s);
    cr_assert(mitsuba_import(write_in("scene.xml", text), &s, &err), "%s", err.message);
    const cJSON *smoke = get(s.root, "media.smoke");
    cr_expect_str_eq(get(smoke, "type")->valuestring, "grid");
    cr_expect_str_eq(get(smoke, "file")->valuestring, "smoke.vol");
    expect_near(num(smoke, "density_scale"), 5.0, "density_scale = scale");
    expect_near(num(smoke, "albedo.1"), 0.9, "albedo");
    /* Default use_grid_bbox false: the box [-2, 2]^3 onto the unit cube, then scale 2: a point
     * x of the box lands at 2 (x + 2) / 4 = x / 2 + 1. */
    const cJSON *m = get(get(smoke, "transform"), "0.matrix");
    expect_near(get(m, "0")->valuedouble, 0.5, "x scale");
    expect_near(get(m, "3")->valuedouble, 1.0, "x offset");
    expect_near(get(m, "5")->valuedouble, 0.5, "y scale");
    cr_expect_null(cJSON_GetObjectItemCaseSensitive(get(s.root, "media.boxed"), "transform"),
                   "use_grid_bbox: the file's box as it is");
    imported_scene_free(&s);
    /* The scene loads: the grid sits where the transform says (world x 1 is index x 1 of 2... the
     * box's middle: Mitsuba's unit cube [0, 2] after scale 2, voxel centre 1 = index 1). */
    Scene scene;
    cr_assert(scene_load(write_in("scene.xml", text), &scene, &err), "%s", err.message);
    cr_assert_eq(scene.data.num_media, 2);
    const Medium *g = &scene.data.media[0];
    float x = g->to_index[0].s[0] * 1.0f + g->to_index[0].s[3];
    cr_expect(fabsf(x - 1.0f) < 1e-5f, "world x 1 (Mitsuba's cube [0, 2] middle) is index x %g", x);
    scene_free(&scene);
}

Test(import_mitsuba_media, bad_media_are_one_line)
{
    ImportedScene s;
    Error err = {0};
    cr_expect(!import_body("<medium type=\"homogeneous\" id=\"f\"><phase type=\"hg\"><float "
                           "name=\"g\" value=\"1.5\"/></phase></medium>" CUBE_WITH("<ref name=\"interior\" id=\"f\"/>"),
                           &s, &err));
    cr_expect(strstr(err.message, "g 1.5 is outside (-1, 1)") && strstr(err.message, "scene.xml:"),
              "%s", err.message);
    imported_scene_free(&s);
    err = (Error){0};
    cr_expect(!import_body("<medium type=\"heterogeneous\" id=\"f\"><volume type=\"gridvolume\" "
                           "name=\"sigma_t\"><string name=\"filename\" value=\"none.vol\"/></volume>"
                           "</medium>" CUBE_WITH("<ref name=\"interior\" id=\"f\"/>"),
                           &s, &err));
    cr_expect(strstr(err.message, "none.vol"), "%s", err.message);
    cr_expect(!strchr(err.message, '\n'));
    imported_scene_free(&s);
    err = (Error){0};
    cr_expect(!import_body("<medium type=\"vdb\" id=\"f\"/>" CUBE_WITH("<ref name=\"interior\" id=\"f\"/>"),
                           &s, &err));
    cr_expect(strstr(err.message, "medium type \"vdb\""), "%s", err.message);
    imported_scene_free(&s);
    err = (Error){0};
    cr_expect(!import_body("<bsdf type=\"diffuse\" id=\"d\"/><shape type=\"cube\">"
                           "<ref name=\"interior\" id=\"d\"/></shape>",
                           &s, &err));
    cr_expect(strstr(err.message, "names a <bsdf>, not a <medium>"),
              "%s", err.message);
    imported_scene_free(&s);
}

Test(import_mitsuba_media, a_fog_filled_sphere_loads_closed)
{
    ImportedScene s;
    Error err = {0};
    cr_assert(import_body("<medium type=\"homogeneous\" id=\"fog\"/>"
                          "<shape type=\"sphere\"><bsdf type=\"dielectric\"/>"
                          "<ref name=\"interior\" id=\"fog\"/></shape>" QUIET_SENSOR,
                          &s, &err),
              "%s", err.message);
    imported_scene_free(&s);
    Scene scene;
    cr_assert(scene_load(write_in("scene.xml", "<scene version=\"3.0.0\"><medium "
                                               "type=\"homogeneous\" id=\"fog\"/><shape "
                                               "type=\"sphere\"><bsdf type=\"dielectric\"/><ref "
                                               "name=\"interior\" id=\"fog\"/></shape>"
                                               QUIET_SENSOR "</scene>"),
                         &scene, &err),
              "Mitsuba's sphere must be closed for pt: %s", err.message);
    /* Mitsuba's homogeneous defaults: sigma_t 1, albedo 0.75. */
    const Medium *fog = &scene.data.media[0];
    cr_expect(fabsf(fog->sigma_s.s[0] - 0.75f) < 1e-6f && fabsf(fog->sigma_a.s[0] - 0.25f) < 1e-6f,
              "sigma_s %g sigma_a %g", fog->sigma_s.s[0], fog->sigma_a.s[0]);
    scene_free(&scene);
}
