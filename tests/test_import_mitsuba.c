// SPDX-License-Identifier: MIT
/* The Mitsuba 3 XML importer (host/scene/import_mitsuba.c) on generated files: the scene's
 * structure (transforms in Mitsuba's order, the sensor, parameters, the integrator, includes,
 * instancing) mapped onto pt's JSON scene, and a scene written both ways flattening to the same
 * bits. BSDFs, textures, emitters, shape options and bad input: test_import_mitsuba_materials.c. */
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

#define PI 3.14159265358979323846

static const char *shape_obj = "<shape type=\"obj\"><string name=\"filename\" value=\"m.obj\"/></shape>";

/* The object's matrix applied to p. */
static void apply(const cJSON *object, const double p[3], double out[3])
{
    const cJSON *m = get(object, "transform.0.matrix");
    for (int r = 0; r < 3; r++)
        out[r] = cJSON_GetArrayItem(m, 4 * r + 3)->valuedouble;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            out[r] += cJSON_GetArrayItem(m, 4 * r + c)->valuedouble * p[c];
}

Test(import_mitsuba, transform_operations_compose_in_mitsuba_order)
{
    ImportedScene s;
    Error err = {0};
    /* scale 2, then rotate 90 degrees about +y (x -> -z), then translate: (1,0,0) -> (1, 2, 1). */
    cr_assert(import_body("<shape type=\"obj\"><string name=\"filename\" value=\"m.obj\"/>"
                          "<transform name=\"to_world\"><scale value=\"2\"/><rotate y=\"1\" angle=\"90\"/>"
                          "<translate x=\"1\" y=\"2\" z=\"3\"/></transform></shape>"
                          "<shape type=\"ply\"><string name=\"filename\" value=\"m.ply\"/>"
                          "<boolean name=\"flip_tex_coords\" value=\"true\"/>"
                          "<transform name=\"to_world\"><matrix value=\"0 -1 0 5  1 0 0 0  0 0 1 0  0 0 0 1\"/>"
                          "<scale x=\"3\" y=\"1\" z=\"1\"/></transform></shape>",
                          &s, &err), "%s", err.message);
    double p[3] = {1, 0, 0}, q[3];
    apply(get(s.root, "objects.0"), p, q);
    expect_near(q[0], 1, "x"), expect_near(q[1], 2, "y"), expect_near(q[2], 1, "z");
    cr_expect_str_eq(get(s.root, "objects.0.obj")->valuestring, "m.obj");
    /* matrix first (x -> y, then + 5 x), then scale x 3: (1,0,0) -> (5, 1, 0) -> (15, 1, 0). */
    apply(get(s.root, "objects.1"), p, q);
    expect_near(q[0], 15, "x"), expect_near(q[1], 1, "y"), expect_near(q[2], 0, "z");
    cr_expect_str_eq(get(s.root, "objects.1.ply")->valuestring, "m.ply");
    imported_scene_free(&s);
}

static void import_sensor(const char *axis, double fov, int width, int height, ImportedScene *s)
{
    char body[2048];
    Error err = {0};
    snprintf(body, sizeof body,
             "<sensor type=\"perspective\"><float name=\"fov\" value=\"%g\"/>"
             "<string name=\"fov_axis\" value=\"%s\"/>"
             "<transform name=\"to_world\"><lookat origin=\"1, 2, 3\" target=\"1, 2, 0\" up=\"0, 1, 0\"/></transform>"
             "<film type=\"hdrfilm\"><integer name=\"width\" value=\"%d\"/><integer name=\"height\" value=\"%d\"/>"
             "<rfilter type=\"box\"/></film></sensor>%s",
             fov, axis, width, height, shape_obj);
    cr_assert(import_body(body, s, &err), "%s", err.message);
}

Test(import_mitsuba, sensor_lookat_and_fov_axes)
{
    ImportedScene s;
    double tan30 = tan(PI / 6);
    struct {
        const char *axis;
        int width, height;
        double fov_y;
    } cases[] = {
        {"y", 200, 100, 60.0},
        {"x", 200, 100, 2 * atan(tan30 / 2) * 180 / PI},
        {"diagonal", 200, 100, 2 * atan(tan30 / sqrt(5.0)) * 180 / PI},
        {"smaller", 200, 100, 60.0},                               /* y is smaller */
        {"larger", 200, 100, 2 * atan(tan30 / 2) * 180 / PI},      /* x is larger */
        {"smaller", 100, 200, 2 * atan(tan30 * 2) * 180 / PI},     /* x is smaller */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        import_sensor(cases[i].axis, 60, cases[i].width, cases[i].height, &s);
        expect_near(num(s.root, "camera.fov_y"), cases[i].fov_y, cases[i].axis);
        expect_near(num(s.root, "film.width"), cases[i].width, "width");
        imported_scene_free(&s);
    }
    import_sensor("y", 60, 64, 64, &s);
    double eye[3] = {1, 2, 3}, target[3] = {1, 2, 2}, up[3] = {0, 1, 0};
    for (int i = 0; i < 3; i++) {
        expect_near(num(get(s.root, "camera.eye"), (char[]){(char)('0' + i), 0}), eye[i], "eye");
        expect_near(num(get(s.root, "camera.target"), (char[]){(char)('0' + i), 0}), target[i], "target");
        expect_near(num(get(s.root, "camera.up"), (char[]){(char)('0' + i), 0}), up[i], "up");
    }
    imported_scene_free(&s);
}

/* Mitsuba's image x runs along its camera's -x: a to_world that mirrors it cannot be rendered
 * by pt's right-handed camera, and says so. */
Test(import_mitsuba, mirrored_camera_is_warned)
{
    ImportedScene s;
    Error err = {0};
    int before = warning_count();
    cr_assert(import_body("<sensor type=\"perspective\"><transform name=\"to_world\"><scale x=\"-1\"/>"
                          "<lookat origin=\"0, 0, 5\" target=\"0, 0, 0\"/></transform>"
                          "<film type=\"hdrfilm\"><rfilter type=\"box\"/></film></sensor>", &s, &err) ||
              true);
    imported_scene_free(&s);
    cr_assert(import_body("<sensor type=\"perspective\"><transform name=\"to_world\"><scale x=\"-1\"/>"
                          "<lookat origin=\"0, 0, 5\" target=\"0, 0, 0\"/></transform>"
                          "<film type=\"hdrfilm\"><rfilter type=\"box\"/></film></sensor>"
                          "<shape type=\"sphere\"/>", &s, &err), "%s", err.message);
    cr_expect(warning_count() > before);
    int mirrored = warning_count();
    imported_scene_free(&s);
    cr_assert(import_body("<sensor type=\"perspective\"><transform name=\"to_world\">"
                          "<lookat origin=\"0, 0, 5\" target=\"0, 0, 0\"/></transform>"
                          "<film type=\"hdrfilm\"><rfilter type=\"box\"/></film></sensor>"
                          "<shape type=\"sphere\"/>", &s, &err), "%s", err.message);
    cr_expect(warning_count() == mirrored, "an ordinary lookat warned");
    imported_scene_free(&s);
}

Test(import_mitsuba, defaults_parameters_and_command_line_overrides)
{
    ImportedScene s;
    Error err = {0};
    const char *body = "<default name=\"spp\" value=\"16\"/><default name=\"r\" value=\"0.25\"/>"
                       "<sensor type=\"perspective\"><sampler type=\"independent\">"
                       "<integer name=\"sample_count\" value=\"$spp\"/></sampler>"
                       "<film type=\"hdrfilm\"><rfilter type=\"box\"/></film></sensor>"
                       "<shape type=\"sphere\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"$r, 0.5, $r\"/>"
                       "</bsdf></shape>";
    cr_assert(import_body(body, &s, &err), "%s", err.message);
    expect_near(num(s.root, "render.spp"), 16, "spp from <default>");
    expect_near(num(get(s.root, "materials"), "bsdf_0.albedo.0"), 0.25, "$r");
    imported_scene_free(&s);
    cr_assert(mitsuba_import_define("spp=64", &err), "%s", err.message);
    cr_assert(import_body(body, &s, &err), "%s", err.message);
    mitsuba_import_clear_defines();
    expect_near(num(s.root, "render.spp"), 64, "spp from -D");
    imported_scene_free(&s);
    cr_expect(!mitsuba_import_define("=3", &err) && err.code == ERR_USAGE);

    err = (Error){0};
    cr_assert(!import_body("<shape type=\"sphere\">\n<float name=\"radius\" value=\"$size\"/></shape>", &s, &err));
    cr_expect(strstr(err.message, "scene.xml:3: <float name=\"radius\">") && strstr(err.message, "$size"),
              "%s", err.message);
    imported_scene_free(&s);
}

Test(import_mitsuba, integrator_depth_counts_as_pt)
{
    ImportedScene s;
    Error err = {0};
    cr_assert(import_body("<integrator type=\"path\"><integer name=\"max_depth\" value=\"5\"/></integrator>"
                          "<shape type=\"cube\"/>", &s, &err), "%s", err.message);
    expect_near(num(s.root, "render.max_depth"), 5, "max_depth");
    imported_scene_free(&s);
    int before = warning_count();
    cr_assert(import_body(QUIET_SENSOR "<integrator type=\"volpath\"/><shape type=\"cube\"/>", &s, &err), "%s", err.message);
    expect_near(num(s.root, "render.max_depth"), MAX_DEPTH_LIMIT, "-1: pt's limit");
    cr_expect(warning_count() == before + 1);
    imported_scene_free(&s);
}

Test(import_mitsuba, shapegroup_instances_share_one_mesh)
{
    ImportedScene s;
    Error err = {0};
    cr_assert(import_body("<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\"/>"
                          "<shape type=\"obj\"><string name=\"filename\" value=\"a.obj\"/></shape></shape>"
                          "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">"
                          "<translate x=\"1\"/></transform></shape>"
                          "<shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">"
                          "<translate x=\"-1\"/></transform></shape>", &s, &err), "%s", err.message);
    const cJSON *o = get(s.root, "objects");
    cr_assert_eq(cJSON_GetArraySize(o), 4);
    cr_expect_str_eq(get(o, "0.mesh")->valuestring, "sphere");
    cr_expect_str_eq(get(o, "2.mesh")->valuestring, "sphere");
    cr_expect_str_eq(get(o, "1.obj")->valuestring, "a.obj");
    cr_expect_str_eq(get(o, "3.obj")->valuestring, "a.obj");
    expect_near(num(o, "2.transform.0.matrix.3"), -1, "second instance");
    cr_expect_eq(s.num_meshes, 1, "one sphere mesh for both instances");
    imported_scene_free(&s);
}

Test(import_mitsuba, include_and_refs_across_files)
{
    ImportedScene s;
    Error err = {0};
    scene_dir = test_temp_dir();
    char sub[600];
    snprintf(sub, sizeof sub, "%s/parts", scene_dir);
    cr_assert(mkdir(sub, 0755) == 0);
    test_write_file(sub, "materials.xml",
                    "<scene version=\"3.0.0\"><bsdf type=\"diffuse\" id=\"red\"><texture name=\"reflectance\" "
                    "type=\"bitmap\"><string name=\"filename\" value=\"red.png\"/></texture></bsdf></scene>");
    const char *path = test_write_file(scene_dir, "scene.xml",
                                       "<scene version=\"3.0.0\"><include filename=\"parts/materials.xml\"/>"
                                       "<shape type=\"cube\"><ref id=\"red\"/></shape></scene>");
    memset(&s, 0, sizeof s);
    cr_assert(mitsuba_import(path, &s, &err), "%s", err.message);
    const cJSON *m = material_of(&s, 0);
    /* the texture named inside parts/ is relative to the imported file's folder */
    cr_expect_str_eq(get(get(s.root, "textures"), get(m, "albedo")->valuestring)->child->valuestring,
                     "parts/red.png");
    imported_scene_free(&s);
    path = test_write_file(scene_dir, "escape.xml",
                           "<scene version=\"3.0.0\">\n<include filename=\"../other.xml\"/></scene>");
    memset(&s, 0, sizeof s);
    cr_assert(!mitsuba_import(path, &s, &err));
    cr_expect(strstr(err.message, "escape.xml:2: <include>") && strstr(err.message, "leaves"), "%s", err.message);
    imported_scene_free(&s);
}


/* ---- The same scene written as pt JSON and as Mitsuba XML flattens to the same bits ---------- */

static const char *tetra_obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
                               "f 1/1 3/3 2/2\nf 1/1 2/2 4/3\nf 1/1 4/3 3/2\nf 2/1 3/2 4/3\n";

Test(import_mitsuba, xml_and_json_flatten_to_the_same_bits, .timeout = 60)
{
    const char *dir = test_temp_dir();
    test_write_file(dir, "tetra.obj", tetra_obj);
    const char *xml = test_write_file(dir, "scene.xml",
        "<scene version=\"3.0.0\">\n"
        "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"5\"/></integrator>\n"
        "  <sensor type=\"thinlens\"><float name=\"fov\" value=\"35\"/><string name=\"fov_axis\" value=\"y\"/>\n"
        "    <float name=\"aperture_radius\" value=\"0.05\"/><float name=\"focus_distance\" value=\"4\"/>\n"
        "    <transform name=\"to_world\"><lookat origin=\"0, 1, 4\" target=\"0, 1, 0\" up=\"0, 1, 0\"/></transform>\n"
        "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"8\"/></sampler>\n"
        "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"40\"/><integer name=\"height\" value=\"30\"/>\n"
        "      <rfilter type=\"box\"/></film></sensor>\n"
        "  <bsdf type=\"twosided\" id=\"white\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.7, 0.6, 0.5\"/></bsdf></bsdf>\n"
        "  <bsdf type=\"conductor\" id=\"mirror\"><string name=\"material\" value=\"none\"/></bsdf>\n"
        "  <shape type=\"obj\"><string name=\"filename\" value=\"tetra.obj\"/><ref id=\"white\"/>\n"
        "    <transform name=\"to_world\"><scale value=\"2\"/><rotate y=\"1\" angle=\"30\"/><translate x=\"0.5\"/></transform></shape>\n"
        "  <shape type=\"obj\"><string name=\"filename\" value=\"tetra.obj\"/><ref id=\"mirror\"/>\n"
        "    <emitter type=\"area\"><rgb name=\"radiance\" value=\"3, 3, 2\"/></emitter></shape>\n"
        "  <emitter type=\"point\"><point name=\"position\" value=\"0, 3, 0\"/><rgb name=\"intensity\" value=\"5\"/></emitter>\n"
        "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"0.1, 0.1, 0.2\"/></emitter>\n"
        "</scene>\n");
    const char *json = test_write_file(dir, "scene.json",
        "{\"camera\": {\"eye\": [0, 1, 4], \"target\": [0, 1, 3], \"up\": [0, 1, 0], \"fov_y\": 35,\n"
        "             \"aperture\": 0.1, \"focus_distance\": 4},\n"
        " \"film\": {\"width\": 40, \"height\": 30}, \"render\": {\"spp\": 8, \"max_depth\": 5},\n"
        " \"background\": [0.1, 0.1, 0.2],\n"
        " \"lights\": [{\"type\": \"point\", \"position\": [0, 3, 0], \"intensity\": [5, 5, 5]}],\n"
        " \"materials\": {\"white\": {\"type\": \"diffuse\", \"albedo\": [0.7, 0.6, 0.5]},\n"
        "               \"mirror\": {\"type\": \"conductor\", \"reflectance\": 1},\n"
        "               \"lamp\": {\"type\": \"conductor\", \"reflectance\": 1, \"emission\": [3, 3, 2]}},\n"
        " \"objects\": [{\"obj\": \"tetra.obj\", \"material\": \"white\", \"smooth\": true,\n"
        "              \"transform\": [{\"scale\": 2}, {\"rotate\": {\"axis\": [0, 1, 0], \"angle\": 30}},\n"
        "                            {\"translate\": [0.5, 0, 0]}]},\n"
        "             {\"obj\": \"tetra.obj\", \"material\": \"lamp\", \"smooth\": true}]}\n");
    Scene from_xml, from_json;
    Error err = {0};
    cr_assert(scene_load(xml, &from_xml, &err), "%s", err.message);
    cr_assert(scene_load(json, &from_json, &err), "%s", err.message);
    cr_expect_eq(from_xml.data.num_triangles, from_json.data.num_triangles);
    cr_expect_eq(from_xml.desc.max_depth, 5);
    cr_expect_eq(from_xml.desc.spp, 8);
    cr_expect(scene_hash(&from_xml) == scene_hash(&from_json), "the XML and JSON scenes differ");
    scene_free(&from_xml);
    scene_free(&from_json);
}
