// SPDX-License-Identifier: MIT
/* The pbrt-v4 importer (host/io/pbrt_parser.c, host/scene/import_pbrt*.c) on generated files: the
 * tokenizer and typed parameter lists, Include, the left-handed camera (an object on pbrt's
 * image-left shows on pt's image-left), the unit conversions (fov on the shorter axis, maxdepth,
 * roughness, named spectra), instancing, and a scene written both as pbrt and as pt JSON that
 * flattens to the same arrays. Bad input: one line naming file:line and the directive. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/pbrt_parser.h"
#include "scene/scene_import.h"
#include "scene/scene.h"
#include "support.h"

static const char *const camera_block =
    "LookAt 0 0 -5  0 0 0  0 1 0\n"
    "Camera \"perspective\" \"float fov\" [40]\n"
    "Film \"rgb\" \"integer xresolution\" [32] \"integer yresolution\" [24] \"string filename\" \"x.exr\"\n"
    "Sampler \"halton\" \"integer pixelsamples\" 4\n"
    "Integrator \"volpath\" \"integer maxdepth\" [4]\n";

static bool load_text(const char *text, Scene *scene, Error *err)
{
    const char *path = test_write_file(test_temp_dir(), "scene.pbrt", text);
    return scene_load_with(path, INSTANCING_NEVER, scene, err);
}

static void load_ok(const char *body, Scene *scene)
{
    char text[8192];
    snprintf(text, sizeof text, "%sWorldBegin\n%s", camera_block, body);
    Error err = {0};
    cr_assert(load_text(text, scene, &err), "%s", err.message);
}

/* The error's message for a failing file. */
static Error load_fail(const char *text)
{
    Scene scene;
    Error err = {0};
    cr_assert_not(load_text(text, &scene, &err), "accepted:\n%s", text);
    cr_assert(err.message[0]);
    cr_assert(!strchr(err.message, '\n'), "one line: %s", err.message);
    return err;
}

Test(pbrt_parser, typed_parameters_arrays_and_single_values)
{
    const char *path = test_write_file(test_temp_dir(), "p.pbrt",
        "Shape \"x\" \"float a\" 1.5 \"integer b\" [1 2 -3] # comment [ \"ignored\"\n"
        "  \"string c\" \"q\\\"uote\" \"bool d\" true \"bool e\" \"false\" \"rgb f\" [.5 +1 2e-1]\n"
        "  \"spectrum g\" \"metal-Au-eta\" \"point3 h\" [] \"normal n\" [0 0 1] Next\n");
    Error err = {0};
    PbrtReader *r = pbrt_reader_open(path, &err);
    cr_assert(r, "%s", err.message);
    PbrtToken t;
    cr_assert(pbrt_next(r, &t, &err) && t.kind == PBRT_TOKEN_WORD && strcmp(t.text, "Shape") == 0);
    cr_assert(pbrt_next(r, &t, &err) && t.kind == PBRT_TOKEN_STRING && strcmp(t.text, "x") == 0);
    PbrtParams p;
    cr_assert_not(pbrt_read_params(r, "Shape", &p, &err), "an empty array is refused");
    cr_expect(strstr(err.message, "p.pbrt:3: Shape: \"h\": no values"), "%s", err.message);
    pbrt_params_free(&p);
    pbrt_reader_close(r);

    path = test_write_file(test_temp_dir(), "p.pbrt",
        "Shape \"x\" \"float a\" 1.5 \"integer b\" [1 2 -3] # comment [ \"ignored\"\n"
        "  \"string c\" \"q\\\"uote\" \"bool d\" true \"bool e\" \"false\" \"rgb f\" [.5 +1 2e-1]\n"
        "  \"spectrum g\" \"metal-Au-eta\" \"normal n\" [0 0 1] Next\n");
    memset(&err, 0, sizeof err);
    r = pbrt_reader_open(path, &err);
    cr_assert(pbrt_next(r, &t, &err) && pbrt_next(r, &t, &err));
    cr_assert(pbrt_read_params(r, "Shape", &p, &err), "%s", err.message);
    cr_assert_eq(p.count, 8);
    PbrtParam *q = pbrt_param(&p, "a");
    cr_expect(q->type == PBRT_FLOAT && q->count == 1 && q->numbers[0] == 1.5);
    q = pbrt_param(&p, "b");
    cr_expect(q->type == PBRT_INTEGER && q->count == 3 && q->numbers[2] == -3.0 && q->line == 1);
    q = pbrt_param(&p, "c");
    cr_expect(q->type == PBRT_STRING && strcmp(q->strings[0], "q\"uote") == 0 && q->line == 2);
    cr_expect(pbrt_param(&p, "d")->numbers[0] == 1.0 && pbrt_param(&p, "e")->numbers[0] == 0.0);
    q = pbrt_param(&p, "f");
    cr_expect(q->type == PBRT_RGB && q->numbers[0] == 0.5 && q->numbers[1] == 1.0 && fabs(q->numbers[2] - 0.2) < 1e-12);
    q = pbrt_param(&p, "g");
    cr_expect(q->type == PBRT_SPECTRUM && q->strings && strcmp(q->strings[0], "metal-Au-eta") == 0);
    cr_expect(pbrt_param(&p, "n")->type == PBRT_NORMAL3, "\"normal\" is normal3");
    cr_assert(pbrt_next(r, &t, &err) && t.kind == PBRT_TOKEN_WORD && strcmp(t.text, "Next") == 0 && t.line == 3);
    pbrt_params_free(&p);
    pbrt_reader_close(r);
}

Test(pbrt_parser, include_is_read_in_place_and_may_not_escape)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "inc.pbrt", "Translate 1 2 3\n");
    const char *path = test_write_file(dir, "main.pbrt", "Include \"inc.pbrt\" Scale 2 2 2\n");
    Error err = {0};
    PbrtReader *r = pbrt_reader_open(path, &err);
    PbrtToken t;
    cr_assert(pbrt_next(r, &t, &err) && strcmp(t.text, "Translate") == 0 && strstr(t.file, "inc.pbrt"));
    for (int i = 0; i < 3; i++)
        cr_assert(pbrt_next(r, &t, &err) && t.kind == PBRT_TOKEN_NUMBER && t.number == i + 1);
    cr_assert(pbrt_next(r, &t, &err) && strcmp(t.text, "Scale") == 0 && strstr(t.file, "main.pbrt"));
    pbrt_reader_close(r);
    Error e = load_fail("Import \"../outside.pbrt\"\n");
    cr_expect_eq(e.code, ERR_PATH_ESCAPES, "%s", e.message);
    cr_expect(strstr(e.message, "scene.pbrt:1"), "%s", e.message);
}

Test(pbrt_parser, bad_input_names_file_line_and_directive)
{
    static const struct { const char *text, *needle; } cases[] = {
        {"Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 5]\n", ":1: Shape \"trianglemesh\": index 5"},
        {"\n\nShape \"sphere\" \"float radius\" \"a\"\n", ":3: Shape: \"radius\": expected a number"},
        {"LookAt 0 0 0 0 0 0 0 1 0\n", ":1: LookAt"},
        {"Rotate 30 0 0\n", ":1: Rotate: expected 4 numbers"},
        {"Shape \"x\" \"floot a\" 1\n", ":1: Shape: \"floot a\": unknown parameter type"},
        {"Shape \"x\" \"string a\" \"open\n", ":1: unterminated string"},
        {"AttributeEnd\n", ":1: AttributeEnd without a matching begin"},
        {"Frobnicate 1\n", ":1: unknown directive \"Frobnicate\""},
        {"WorldBegin\nNamedMaterial \"nope\"\n", ":2: NamedMaterial: no material \"nope\""},
        {"WorldBegin\nObjectInstance \"nope\"\n", ":2: ObjectInstance: no object \"nope\""},
        {"Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0]\n", ":1: Shape: \"P\": 5 values is not a multiple of 3"},
        {"Film \"rgb\" \"integer xresolution\" [0]\n", ":1: Film: resolution 0"},
        {"WorldBegin\nCamera \"perspective\"\n", ":2: Camera: inside the world block"},
        {"WorldBegin\n", "no shapes"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        Error e = load_fail(cases[i].text);
        cr_expect(strstr(e.message, cases[i].needle), "case %zu: \"%s\" lacks \"%s\"", i, e.message,
                  cases[i].needle);
        cr_expect(strstr(e.message, "scene.pbrt"), "names the file: %s", e.message);
    }
}

/* pbrt's camera: LookAt from -z toward the origin, up +y, shows world +x on the image's RIGHT
 * (left-handed). pt's camera must see pbrt's world the same way. */
Test(pbrt_scene, handedness_object_on_the_right_stays_right)
{
    Scene scene;
    load_ok("Translate 1 0 0\nShape \"sphere\" \"float radius\" 0.5\n", &scene);
    const CameraDesc *c = &scene.desc.camera;
    double fwd[3], right[3], center[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++)
        fwd[k] = c->target[k] - c->eye[k];
    /* pt: image right = forward x up */
    right[0] = fwd[1] * c->up[2] - fwd[2] * c->up[1];
    right[1] = fwd[2] * c->up[0] - fwd[0] * c->up[2];
    right[2] = fwd[0] * c->up[1] - fwd[1] * c->up[0];
    const SceneData *d = &scene.data;
    for (uint32_t v = 0; v < d->num_vertices; v++)
        for (int k = 0; k < 3; k++)
            center[k] += d->positions[v].s[k] / d->num_vertices;
    double side = 0.0;
    for (int k = 0; k < 3; k++)
        side += (center[k] - c->eye[k]) * right[k];
    cr_expect(side > 0.9, "the sphere at pbrt +x must be on the image's right (%g)", side);
    cr_expect_eq(scene.desc.max_depth, 5, "pbrt maxdepth 4 (bounces) is pt max_depth 5 (segments)");
    cr_expect_eq(scene.desc.spp, 4);
    cr_expect_eq(scene.desc.width, 32);
    cr_expect(fabsf(scene.desc.camera.fov_y - 40.0f) < 1e-5f, "landscape: fov is vertical");
    scene_free(&scene);
}

/* The same in pixels: an emitter at pbrt's +x lights the right half, one at -x the left. The red
 * one faces the camera (its normal, cross(p1 - p0, p2 - p0), points to -z); the blue one faces
 * away and shows only because it is two-sided. */
Test(pbrt_scene, handedness_in_the_rendered_image)
{
    char text[4096];
    snprintf(text, sizeof text,
             "%sWorldBegin\n"
             "AttributeBegin AreaLightSource \"diffuse\" \"rgb L\" [1 0 0] Translate 1.2 0 0\n"
             "  Shape \"trianglemesh\" \"point3 P\" [-.5 -.5 0  0 .5 0  .5 -.5 0] \"integer indices\" [0 1 2]\n"
             "AttributeEnd\n"
             "AttributeBegin AreaLightSource \"diffuse\" \"rgb L\" [0 0 1] \"bool twosided\" true\n"
             "  Translate -1.2 0 0 Shape \"trianglemesh\" \"point3 P\" [-.5 -.5 0  .5 -.5 0  0 .5 0]\n"
             "AttributeEnd\n", camera_block);
    const char *path = test_write_file(test_temp_dir(), "scene.pbrt", text);
    RenderFixture f;
    render_fixture_open(&f, path, 32, 24);
    float *rgb = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 1}, NULL);
    double red[2] = {0, 0}, blue[2] = {0, 0};
    for (int y = 0; y < 24; y++)
        for (int x = 0; x < 32; x++) {
            red[x >= 16] += rgb[3 * (y * 32 + x)];
            blue[x >= 16] += rgb[3 * (y * 32 + x) + 2];
        }
    cr_expect(red[1] > 10.0 && red[0] == 0.0, "red (pbrt +x) on the right: left %g right %g", red[0], red[1]);
    cr_expect(blue[0] > 10.0 && blue[1] == 0.0, "blue (pbrt -x, two-sided: its back faces the camera) "
              "on the left: left %g right %g", blue[0], blue[1]);
    free(rgb);
    render_fixture_close(&f);
}

Test(pbrt_scene, fov_spans_the_shorter_axis)
{
    Scene scene;
    Error err = {0};
    cr_assert(load_text("Camera \"perspective\" \"float fov\" 40\n"
                        "Film \"rgb\" \"integer xresolution\" 24 \"integer yresolution\" 48\n"
                        "WorldBegin Shape \"sphere\"\n", &scene, &err), "%s", err.message);
    double expected = 2.0 * atan(tan(20.0 * 3.14159265358979323846 / 180.0) * 2.0) * 180.0 / 3.14159265358979323846;
    cr_expect(fabs(scene.desc.camera.fov_y - expected) < 1e-4, "portrait: fov is horizontal, fov_y %g "
              "(expected %g)", scene.desc.camera.fov_y, expected);
    scene_free(&scene);
}

Test(pbrt_scene, instances_share_one_mesh)
{
    Scene scene;
    load_ok("ObjectBegin \"tri\"\n Translate 0 1 0\n"
            " Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\nObjectEnd\n"
            "ObjectInstance \"tri\"\nTranslate 5 0 0 ObjectInstance \"tri\"\n", &scene);
    scene_free(&scene);
    Error err = {0};
    char text[4096];
    snprintf(text, sizeof text, "%sWorldBegin\nObjectBegin \"tri\"\n Translate 0 1 0\n"
             " Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\nObjectEnd\n"
             "ObjectInstance \"tri\"\nTranslate 5 0 0 ObjectInstance \"tri\"\n", camera_block);
    cr_assert(scene_load_with(test_write_file(test_temp_dir(), "i.pbrt", text), INSTANCING_ALWAYS, &scene, &err),
              "%s", err.message);
    cr_expect_eq(scene.data.num_meshes, 1, "one mesh for both instances, not %u", scene.data.num_meshes);
    cr_expect_eq(scene.data.num_instances, 2);
    cr_expect_eq(scene.data.num_triangles, 1);
    /* instance 2 = Translate(5,0,0) * Translate(0,1,0), mirrored into pt (x -> -x) */
    const Affine *m = &scene.data.instances[1].to_world;
    cr_expect(m->m[0][3] == -5.0 && m->m[1][3] == 1.0 && m->m[0][0] == -1.0, "%g %g %g", m->m[0][3],
              m->m[1][3], m->m[0][0]);
    scene_free(&scene);
}

/* The same scene written in pbrt-v4 and in pt JSON flattens to the same arrays. pbrt's world is
 * mirrored (x -> -x) into pt's, so the JSON's transforms end with a scale -1 1 1. */
Test(pbrt_scene, same_arrays_as_the_pt_json_scene)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "quad.obj",
                    "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                    "vn 0 1 0\nvn 0 1 0\nvn 0 1 0\nvn 0 1 0\nf 1/1/1 3/3/3 2/2/2\nf 1/1/1 4/4/4 3/3/3\n");
    test_write_file(dir, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const char *json = test_write_file(dir, "scene.json",
        "{\"camera\": {\"eye\": [-1, 2, -5], \"target\": [0, 0.5, 0], \"up\": [0, 1, 0], \"fov_y\": 40},\n"
        " \"film\": {\"width\": 32, \"height\": 24}, \"render\": {\"spp\": 4, \"max_depth\": 5},\n"
        " \"materials\": {\"floor\": {\"type\": \"diffuse\", \"albedo\": [0.2, 0.4, 0.6]},\n"
        "   \"gold\": {\"type\": \"conductor\", \"eta\": [0.143, 0.374, 1.442], \"k\": [3.983, 2.385, 1.603], \"roughness\": 0.5},\n"
        "   \"glass\": {\"type\": \"dielectric\", \"ior\": 1.5168, \"roughness\": 0},\n"
        "   \"default\": {\"type\": \"diffuse\", \"albedo\": 0.5},\n"
        "   \"lamp\": {\"type\": \"diffuse\", \"albedo\": 0.5, \"emission\": [2, 3, 4]}},\n"
        " \"objects\": [\n"
        "  {\"obj\": \"quad.obj\", \"material\": \"floor\", \"transform\": [{\"scale\": [2, 1, 2]}, {\"scale\": [-1, 1, 1]}]},\n"
        "  {\"obj\": \"tri.obj\", \"material\": \"gold\", \"transform\": [{\"translate\": [1, 0, 0]}, {\"scale\": [-1, 1, 1]}]},\n"
        "  {\"obj\": \"tri.obj\", \"material\": \"glass\", \"transform\": [{\"translate\": [0, 0, 2]}, {\"scale\": [-1, 1, 1]}]},\n"
        "  {\"obj\": \"tri.obj\", \"material\": \"lamp\", \"transform\": [{\"translate\": [0, 3, 0]}, {\"scale\": [-1, 1, 1]}]}],\n"
        " \"lights\": [{\"type\": \"point\", \"position\": [-1, 4, 0], \"intensity\": [5, 5, 5]}]}\n");
    const char *pbrt = test_write_file(dir, "scene.pbrt",
        "LookAt 1 2 -5  0 .5 0  0 1 0\nCamera \"perspective\" \"float fov\" 40\n"
        "Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 24\n"
        "Sampler \"zsobol\" \"integer pixelsamples\" 4\nIntegrator \"path\" \"integer maxdepth\" 4\n"
        "WorldBegin\n"
        "LightSource \"point\" \"rgb I\" [2.5 2.5 2.5] \"float scale\" 2 \"point3 from\" [1 4 0]\n"
        "MakeNamedMaterial \"floor\" \"string type\" \"diffuse\" \"rgb reflectance\" [0.2 0.4 0.6]\n"
        "MakeNamedMaterial \"gold\" \"string type\" \"conductor\" \"spectrum eta\" \"metal-Au-eta\"\n"
        "  \"spectrum k\" \"metal-Au-k\" \"float roughness\" 0.0625\n"
        "MakeNamedMaterial \"glass\" \"string type\" \"dielectric\" \"spectrum eta\" \"glass-BK7\"\n"
        "AttributeBegin NamedMaterial \"floor\" Scale 2 1 2\n"
        "  Shape \"trianglemesh\" \"point3 P\" [-1 0 -1 1 0 -1 1 0 1 -1 0 1] \"point2 uv\" [0 0 1 0 1 1 0 1]\n"
        "   \"normal N\" [0 1 0 0 1 0 0 1 0 0 1 0] \"integer indices\" [0 2 1 0 3 2]\nAttributeEnd\n"
        "AttributeBegin NamedMaterial \"gold\" Translate 1 0 0\n"
        "  Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 2]\nAttributeEnd\n"
        "AttributeBegin NamedMaterial \"glass\" Translate 0 0 2\n"
        "  Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\nAttributeEnd\n"
        "AttributeBegin AreaLightSource \"diffuse\" \"rgb L\" [1 1.5 2] \"float scale\" 2\n"
        "  Translate 0 3 0 Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0]\nAttributeEnd\n");
    Scene a, b;
    Error err = {0};
    cr_assert(scene_load_with(json, INSTANCING_NEVER, &a, &err), "%s", err.message);
    cr_assert(scene_load_with(pbrt, INSTANCING_NEVER, &b, &err), "%s", err.message);
    const SceneData *x = &a.data, *y = &b.data;
    cr_assert_eq(x->num_vertices, y->num_vertices);
    cr_assert_eq(x->num_triangles, y->num_triangles);
    cr_expect(memcmp(x->positions, y->positions, x->num_vertices * sizeof *x->positions) == 0, "positions");
    cr_expect(memcmp(x->normals, y->normals, x->num_vertices * sizeof *x->normals) == 0, "normals");
    cr_expect(memcmp(x->uvs, y->uvs, x->num_vertices * sizeof *x->uvs) == 0, "uvs");
    cr_expect(memcmp(x->triangles, y->triangles, x->num_triangles * sizeof *x->triangles) == 0, "triangles");
    cr_expect(memcmp(x->material_ids, y->material_ids, x->num_triangles * sizeof *x->material_ids) == 0,
              "material ids");
    /* pbrt's lamp is a variant of the default material: the same Material constants. */
    cr_assert_eq(x->num_materials, y->num_materials, "%u vs %u materials", x->num_materials, y->num_materials);
    for (uint32_t i = 0; i < x->num_materials; i++)
        cr_expect(memcmp(&x->materials[i], &y->materials[i], sizeof x->materials[i]) == 0, "material %u", i);
    cr_assert_eq(x->num_analytic, y->num_analytic);
    cr_expect(memcmp(x->analytic_lights, y->analytic_lights, x->num_analytic * sizeof *x->analytic_lights) == 0,
              "lights");
    cr_expect_eq(a.desc.max_depth, b.desc.max_depth);
    cr_expect_eq(a.desc.spp, b.desc.spp);
    const CameraDesc *ca = &a.desc.camera, *cb = &b.desc.camera;
    double dot = 0.0, la = 0.0, lb = 0.0;
    for (int k = 0; k < 3; k++) {
        cr_expect(fabsf(ca->eye[k] - cb->eye[k]) < 1e-6f, "eye");
        double da = ca->target[k] - ca->eye[k], db = cb->target[k] - cb->eye[k];
        dot += da * db, la += da * da, lb += db * db;
    }
    cr_expect(dot / sqrt(la * lb) > 1.0 - 1e-9, "view direction");
    cr_expect(ca->fov_y == cb->fov_y);
    scene_free(&a);
    scene_free(&b);
}

/* The importers' mesh table (scene/scene_import.c): names found after the index grows, a second
 * mesh of the same name refused, a name never added not found. */
Test(pbrt_scene, imported_mesh_names_are_indexed)
{
    ImportedScene s = {0};
    Error err = {0};
    char name[32];
    for (int i = 0; i < 300; i++) {
        Mesh m = {0};
        snprintf(name, sizeof name, "m%d", i);
        cr_assert(imported_scene_add_mesh(&s, name, &m, &err), "%s", err.message);
    }
    for (int i = 0; i < 300; i++) {
        snprintf(name, sizeof name, "m%d", i);
        cr_expect_eq(imported_scene_find_mesh(&s, name), i);
    }
    cr_expect_eq(imported_scene_find_mesh(&s, "m300"), -1);
    Mesh m = {0};
    cr_expect_not(imported_scene_add_mesh(&s, "m17", &m, &err));
    cr_expect(strstr(err.message, "two meshes named \"m17\""), "%s", err.message);
    imported_scene_free(&s);
}
