// SPDX-License-Identifier: MIT
/* The Mitsuba 3 XML importer (host/scene/import_mitsuba.c) on generated files: BSDFs, textures and
 * emitters mapped onto pt's materials, shape options (flip_normals, face_normals, uvs), a lamp in
 * a shapegroup, unknown plugins warned, and bad input refused in one line naming file:line and
 * the element. The scene's structure (transforms, sensor, parameters, includes): test_import_mitsuba.c. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "base/error.h"
#include "mitsuba_import.h"
#include "scene/import_mitsuba.h"
#include "scene/scene.h"
#include "scene/scene_hash.h"
#include "scene/scene_types.h"
#include "support.h"

Test(import_mitsuba, bsdfs)
{
    ImportedScene s;
    Error err = {0};
    cr_assert(import_body(
        "<bsdf type=\"roughconductor\" id=\"aniso\"><string name=\"distribution\" value=\"ggx\"/>"
        "<float name=\"alpha_u\" value=\"0.2\"/><float name=\"alpha_v\" value=\"0.05\"/>"
        "<string name=\"material\" value=\"Au\"/></bsdf>"
        "<shape type=\"sphere\"><ref id=\"aniso\"/></shape>"
        "<shape type=\"sphere\"><bsdf type=\"dielectric\"><string name=\"int_ior\" value=\"water\"/>"
        "<string name=\"ext_ior\" value=\"air\"/></bsdf></shape>"
        "<shape type=\"sphere\"><bsdf type=\"roughplastic\"><string name=\"distribution\" value=\"ggx\"/>"
        "<float name=\"alpha\" value=\"0.04\"/><rgb name=\"diffuse_reflectance\" value=\"0.1, 0.2, 0.3\"/></bsdf></shape>"
        "<shape type=\"sphere\"><bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.3\"/>"
        "<bsdf type=\"diffuse\"/><bsdf type=\"conductor\"><string name=\"material\" value=\"none\"/></bsdf></bsdf></shape>"
        "<shape type=\"sphere\"><bsdf type=\"mask\"><float name=\"opacity\" value=\"0.25\"/>"
        "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.2\"/></bsdf></bsdf></bsdf></shape>"
        "<shape type=\"sphere\"><bsdf type=\"normalmap\"><texture name=\"normalmap\" type=\"bitmap\">"
        "<string name=\"filename\" value=\"n.png\"/><boolean name=\"raw\" value=\"true\"/></texture>"
        "<bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"bitmap\"><string name=\"filename\" value=\"c.png\"/>"
        "<string name=\"filter_type\" value=\"nearest\"/><string name=\"wrap_mode\" value=\"clamp\"/></texture>"
        "</bsdf></bsdf></shape>"
        "<shape type=\"sphere\"><bsdf type=\"thindielectric\"/></shape>"
        "<shape type=\"sphere\"><bsdf type=\"principled\"><rgb name=\"base_color\" value=\"0.5, 0.4, 0.3\"/>"
        "<float name=\"metallic\" value=\"0.7\"/><float name=\"roughness\" value=\"0.2\"/></bsdf></shape>",
        &s, &err), "%s", err.message);
    const cJSON *m = material_of(&s, 0);
    cr_expect_str_eq(get(m, "type")->valuestring, "conductor");
    /* DESIGN's alpha_x = r^2 / sqrt(1 - 0.9 a), alpha_y = r^2 sqrt(1 - 0.9 a) give back 0.2, 0.05. */
    double r = num(m, "roughness"), a = num(m, "anisotropy");
    expect_near(r * r / sqrt(1 - 0.9 * a), 0.2, "alpha_u");
    expect_near(r * r * sqrt(1 - 0.9 * a), 0.05, "alpha_v");
    expect_near(num(m, "eta.0"), 0.143119, "Au eta");
    m = material_of(&s, 1);
    cr_expect_str_eq(get(m, "type")->valuestring, "dielectric");
    expect_near(num(m, "ior"), 1.3330 / 1.000277, "water / air");
    m = material_of(&s, 2);
    cr_expect_str_eq(get(m, "type")->valuestring, "principled");
    expect_near(num(m, "roughness"), 0.2, "sqrt(alpha)");
    expect_near(num(m, "metallic"), 0.0, "plastic metallic");
    expect_near(num(m, "base_color.2"), 0.3, "plastic base");
    expect_near(num(m, "ior"), 1.49 / 1.000277, "polypropylene / air");
    m = material_of(&s, 3);
    cr_expect_str_eq(get(m, "type")->valuestring, "mix");
    expect_near(num(m, "weight"), 0.3, "blend weight");
    cr_expect_str_eq(get(get(s.root, "materials"), get(m, "a")->valuestring)->child->valuestring, "diffuse");
    cr_expect_str_eq(get(get(s.root, "materials"), get(m, "b")->valuestring)->child->valuestring, "conductor");
    m = material_of(&s, 4);
    cr_expect_str_eq(get(m, "type")->valuestring, "diffuse");
    expect_near(num(m, "opacity"), 0.25, "mask opacity");
    expect_near(num(m, "albedo.1"), 0.2, "twosided's inner diffuse");
    m = material_of(&s, 5);
    const cJSON *normal = get(get(s.root, "textures"), get(m, "normal_map")->valuestring);
    cr_expect_str_eq(get(normal, "encoding")->valuestring, "linear");
    cr_expect_str_eq(get(normal, "file")->valuestring, "n.png");
    const cJSON *colour = get(get(s.root, "textures"), get(m, "albedo")->valuestring);
    cr_expect_str_eq(get(colour, "filter")->valuestring, "nearest");
    cr_expect_str_eq(get(colour, "wrap")->valuestring, "clamp");
    cr_expect(!cJSON_GetObjectItemCaseSensitive(colour, "encoding"), "an 8-bit colour map stays sRGB");
    m = material_of(&s, 6);
    double r0 = pow(0.5046 / 2.5046, 2); /* bk7 in air, at normal incidence */
    expect_near(num(m, "opacity"), 2 * (pow((1.5046 / 1.000277 - 1) / (1.5046 / 1.000277 + 1), 2)) /
                                       (1 + pow((1.5046 / 1.000277 - 1) / (1.5046 / 1.000277 + 1), 2)),
                "thin sheet reflectance");
    cr_expect(fabs(num(m, "opacity") - 2 * r0 / (1 + r0)) < 1e-3);
    m = material_of(&s, 7);
    expect_near(num(m, "metallic"), 0.7, "principled metallic");
    expect_near(num(m, "ior"), 1.5, "specular 0.5 is F0 0.04");
    imported_scene_free(&s);
}

Test(import_mitsuba, checkerboard_becomes_its_mean_with_a_warning)
{
    ImportedScene s;
    Error err = {0};
    int before = warning_count();
    cr_assert(import_body(QUIET_SENSOR "<shape type=\"sphere\"><bsdf type=\"diffuse\"><texture name=\"reflectance\" "
                          "type=\"checkerboard\"><rgb name=\"color0\" value=\"0.8\"/><rgb name=\"color1\" "
                          "value=\"0.2, 0.4, 0.6\"/></texture></bsdf></shape>", &s, &err), "%s", err.message);
    const cJSON *m = material_of(&s, 0);
    expect_near(num(m, "albedo.0"), 0.5, "mean r");
    expect_near(num(m, "albedo.2"), 0.7, "mean b");
    cr_expect(warning_count() == before + 1);
    imported_scene_free(&s);
}

Test(import_mitsuba, emitters)
{
    ImportedScene s;
    Error err = {0};
    cr_assert(import_body(
        "<shape type=\"rectangle\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"4, 5, 6\"/></emitter></shape>"
        "<emitter type=\"point\"><point name=\"position\" x=\"1\" y=\"2\" z=\"3\"/><rgb name=\"intensity\" value=\"7\"/></emitter>"
        "<emitter type=\"spot\"><transform name=\"to_world\"><lookat origin=\"0, 5, 0\" target=\"0, 0, 0\" up=\"0, 0, 1\"/>"
        "</transform><float name=\"cutoff_angle\" value=\"30\"/><float name=\"beam_width\" value=\"10\"/></emitter>"
        "<emitter type=\"directional\"><vector name=\"direction\" x=\"0\" y=\"-1\" z=\"0\"/>"
        "<rgb name=\"irradiance\" value=\"2\"/></emitter>"
        "<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/><float name=\"scale\" value=\"0.5\"/>"
        "<transform name=\"to_world\"><rotate y=\"1\" angle=\"90\"/></transform></emitter>"
        "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.1, 0.2, 0.3\"/></emitter>",
        &s, &err), "%s", err.message);
    const cJSON *m = material_of(&s, 0);
    expect_near(num(m, "emission.2"), 6, "area radiance");
    expect_near(num(m, "albedo"), 0.5, "Mitsuba's default bsdf");
    const cJSON *l = get(s.root, "lights");
    cr_expect_str_eq(get(l, "0.type")->valuestring, "point");
    expect_near(num(l, "0.position.2"), 3, "point position");
    expect_near(num(l, "0.intensity.1"), 7, "point intensity");
    cr_expect_str_eq(get(l, "1.type")->valuestring, "spot");
    expect_near(num(l, "1.position.1"), 5, "spot position");
    expect_near(num(l, "1.direction.1"), -1, "spot along +z of to_world");
    expect_near(num(l, "1.cone_angle"), 30, "cutoff");
    expect_near(num(l, "1.falloff_angle"), 10, "beam width");
    expect_near(num(l, "2.direction.1"), -1, "directional");
    expect_near(num(l, "2.irradiance.0"), 2, "irradiance");
    /* Mitsuba's u = 0 looks along -z (pt's u = 0.5): a turn of 90 degrees is pt's 90 - 180. */
    expect_near(num(s.root, "environment.rotation"), 270, "envmap rotation");
    expect_near(num(s.root, "environment.scale"), 0.5, "envmap scale");
    expect_near(num(s.root, "background.2"), 0.3, "constant");
    imported_scene_free(&s);
}


/* Each bad input: refused, one line naming the file, the line and the element. */
Test(import_mitsuba, bad_input_is_one_line_with_file_line_and_element)
{
    struct {
        const char *body, *expected;
    } cases[] = {
        {"<shape type=\"sphere\">\n<float name=\"radius\" value=\"big\"/></shape>", "scene.xml:3: <float name=\"radius\">"},
        {"<shape type=\"sphere\">\n<ref id=\"nothing\"/></shape>", "scene.xml:3: <ref id=\"nothing\">"},
        {"<shape type=\"obj\">\n<string name=\"filename\" value=\"/etc/passwd\"/></shape>", "scene.xml:2: <shape type=\"obj\">"},
        {"<shape type=\"sphere\">\n<transform name=\"to_world\"><rotate angle=\"3\"/></transform></shape>", "scene.xml:3: <rotate>"},
        {"<shape type=\"sphere\"><bsdf type=\"dielectric\">\n<string name=\"int_ior\" value=\"unobtainium\"/></bsdf></shape>",
         "scene.xml:3: <string name=\"int_ior\">"},
        {"<shape type=\"sphere\"/>\n<bsdf type=\"diffuse\" id=\"x\"/><bsdf type=\"diffuse\" id=\"x\"/>", "scene.xml:3: <bsdf type=\"diffuse\" id=\"x\">"},
        {"<shape type=\"sphere\"></scene>", "scene.xml:2: malformed XML"},
        {"<sensor type=\"orthographic\"/><shape type=\"sphere\"/>", "scene.xml:2: <sensor type=\"orthographic\">"},
        {"<emitter type=\"point\"/>", "no shape"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        ImportedScene s;
        Error err = {0};
        cr_expect(!import_body(cases[i].body, &s, &err), "accepted: %s", cases[i].body);
        cr_expect(strstr(err.message, cases[i].expected), "case %zu: \"%s\" lacks \"%s\"", i, err.message,
                  cases[i].expected);
        cr_expect(!strchr(err.message, '\n'), "two lines: %s", err.message);
        imported_scene_free(&s);
    }
}

Test(import_mitsuba, unknown_plugins_are_warned_once_and_the_rest_imported)
{
    ImportedScene s;
    Error err = {0};
    int before = warning_count();
    cr_assert(import_body("<shape type=\"cylinder\"/><shape type=\"cylinder\"/><medium type=\"homogeneous\"/>"
                          "<shape type=\"sphere\"><bsdf type=\"hair\"/></shape>", &s, &err), "%s", err.message);
    cr_expect_eq(warning_count(), before + 4, "cylinder once, medium, hair, and no sensor");
    cr_expect_eq(cJSON_GetArraySize(get(s.root, "objects")), 1);
    imported_scene_free(&s);
}


/* flip_normals reverses the winding (and normals) of the file's mesh, face_normals drops its
 * normals; Mitsuba's rectangle has uv (0, 0) at (-1, -1) with v read from the image's top, so pt
 * (v from the bottom) stores v = 1 there. */
Test(import_mitsuba, flip_and_face_normals_and_shape_uvs)
{
    ImportedScene s;
    Error err = {0};
    import_body("", &s, &err); /* makes scene_dir */
    imported_scene_free(&s);
    const char *dir = scene_dir;
    test_write_file(dir, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n");
    const char *path = test_write_file(dir, "scene.xml",
        "<scene version=\"3.0.0\"><shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/>"
        "<boolean name=\"flip_normals\" value=\"true\"/></shape>"
        "<shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/>"
        "<boolean name=\"face_normals\" value=\"true\"/></shape><shape type=\"rectangle\"/>"
        "<shape type=\"ply\"><string name=\"filename\" value=\"uv.ply\"/></shape></scene>");
    test_write_file(dir, "uv.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                   "property float z\nproperty float u\nproperty float v\nelement face 1\n"
                                   "property list uchar int vertex_indices\nend_header\n"
                                   "0 0 0 0 0.25\n1 0 0 1 0.25\n0 1 0 0 1\n3 0 1 2\n");
    memset(&s, 0, sizeof s);
    cr_assert(mitsuba_import(path, &s, &err), "%s", err.message);
    cr_assert_eq(s.num_meshes, 4);
    const Mesh *flipped = &s.meshes[0].mesh, *flat = &s.meshes[1].mesh, *rect = &s.meshes[2].mesh;
    cr_expect(flipped->corners[0] == 0 && flipped->corners[3] == 2 && flipped->corners[6] == 1,
              "winding reversed");
    cr_expect(flipped->normals[2] == -1.0f, "normal flipped");
    cr_expect(flat->num_normals == 0 && flat->corners[2] == -1, "normals dropped");
    for (size_t i = 0; i < 3 * rect->num_triangles; i++) {
        const float *p = rect->positions + 3 * rect->corners[3 * i], *uv = rect->texcoords + 2 * rect->corners[3 * i + 1];
        cr_expect(fabsf(uv[0] - 0.5f * (p[0] + 1)) < 1e-6f && fabsf(uv[1] - 0.5f * (1 - p[1])) < 1e-6f,
                  "corner (%g, %g) has uv (%g, %g)", p[0], p[1], uv[0], uv[1]);
    }
    /* Mitsuba keeps a PLY's v (flip_tex_coords false), so its images read from the top: pt's v is 1 - v. */
    const Mesh *ply = &s.meshes[3].mesh;
    cr_assert_eq(ply->num_texcoords, 3);
    cr_expect(fabsf(ply->texcoords[1] - 0.75f) < 1e-6f && fabsf(ply->texcoords[5] - 0.0f) < 1e-6f,
              "PLY v not flipped: %g, %g", ply->texcoords[1], ply->texcoords[5]);
    imported_scene_free(&s);
}

/* A lamp in a shapegroup is one emissive material, however often the group is instanced. */
Test(import_mitsuba, instanced_lamp_is_one_material)
{
    ImportedScene s;
    Error err = {0};
    cr_assert(import_body("<shape type=\"shapegroup\" id=\"g\"><shape type=\"rectangle\"><emitter type=\"area\">"
                          "<rgb name=\"radiance\" value=\"2\"/></emitter></shape></shape>"
                          "<shape type=\"instance\"><ref id=\"g\"/></shape>"
                          "<shape type=\"instance\"><ref id=\"g\"/></shape>", &s, &err), "%s", err.message);
    cr_expect_str_eq(get(s.root, "objects.0.material")->valuestring, get(s.root, "objects.1.material")->valuestring);
    cr_expect_eq(cJSON_GetArraySize(get(s.root, "materials")), 2, "the default diffuse and its lamp");
    imported_scene_free(&s);
}
