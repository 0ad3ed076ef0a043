// SPDX-License-Identifier: MIT
/* COLLADA import (io/collada_reader.h, scene/import_collada.h) on files the tests write: polylist,
 * polygons and triangles with n-gons triangulated; the node hierarchy's transforms in document
 * order, instance_node, one mesh for many instances; Z_UP turned to +y up; cameras (xfov and
 * aspect), point/spot/directional lights; the common profile as MTL terms and the CS184 CGL
 * techniques (microfacet, glass, mirror, emission, area lights, analytic spheres); a COLLADA
 * scene and the same scene written as pt JSON with OBJ files render the same bits; bad files
 * fail in one line naming the file, the line and the element. */
#define _DEFAULT_SOURCE /* M_PI */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/collada_reader.h"
#include "io/mesh_shapes.h"
#include "scene/import_collada.h"
#include "scene/scene.h"
#include "support.h"

#define HEADER(up)                                                                                 \
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"                                                 \
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"         \
    "<asset><up_axis>" up "</up_axis></asset>\n"

/* A unit square in z = 0 as one polylist quad, a pentagon as <polygons>, and a triangle. */
#define SHAPE_GEOMETRY                                                                             \
    "<library_geometries>\n"                                                                       \
    "<geometry id=\"shape\"><mesh>\n"                                                              \
    "<source id=\"p\"><float_array id=\"pa\" count=\"30\">0 0 0 1 0 0 1 1 0 0 1 0 "                \
    "3 0 0 4 0 0 4.5 1 0 3.5 2 0 2.5 1 0 6 0 0</float_array>\n"                                    \
    "<technique_common><accessor source=\"#pa\" count=\"10\" stride=\"3\"/></technique_common></source>\n"\
    "<vertices id=\"v\"><input semantic=\"POSITION\" source=\"#p\"/></vertices>\n"                 \
    "<polylist material=\"m1\" count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"\
    "<vcount>4</vcount><p>0 1 2 3</p></polylist>\n"                                                \
    "<polygons material=\"m1\" count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"\
    "<p>4 5 6 7 8</p></polygons>\n"                                                                \
    "<triangles material=\"m1\" count=\"1\"><input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/>"\
    "<p>5 9 6</p></triangles>\n"                                                                   \
    "</mesh></geometry>\n"
#define BALL_GEOMETRY                                                                              \
    "<geometry id=\"ball\"><extra><technique profile=\"CGL\"><sphere><radius>0.5</radius></sphere>"\
    "</technique></extra></geometry>\n"
/* The shape alone (a file without CGL techniques: not a CS184 scene), and with a CGL sphere. */
static const char *const geometry_library = SHAPE_GEOMETRY "</library_geometries>\n";
static const char *const cs184_geometry_library = SHAPE_GEOMETRY BALL_GEOMETRY "</library_geometries>\n";

static const char *write_dae(const char *dir, const char *name, const char *body)
{
    size_t n = strlen(body) + 256;
    char *text = malloc(n);
    cr_assert(text);
    snprintf(text, n, "%s</COLLADA>\n", body);
    const char *path = test_write_file(dir, name, text);
    free(text);
    return path;
}

static const cJSON *get(const cJSON *o, const char *key)
{
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(o, key);
    cr_assert(item, "no key \"%s\"", key);
    return item;
}

static double num(const cJSON *array, int i)
{
    const cJSON *item = cJSON_GetArrayItem(array, i);
    cr_assert(cJSON_IsNumber(item));
    return item->valuedouble;
}

static void expect_vec3(const cJSON *v, double x, double y, double z, double tol, const char *what)
{
    cr_expect(fabs(num(v, 0) - x) < tol && fabs(num(v, 1) - y) < tol && fabs(num(v, 2) - z) < tol,
              "%s: (%g, %g, %g), expected (%g, %g, %g)", what, num(v, 0), num(v, 1), num(v, 2), x,
              y, z);
}

/* The object's matrix (its one transform) applied to point p. */
static void object_point(const cJSON *object, const double p[3], double out[3])
{
    const cJSON *m = get(cJSON_GetArrayItem(get(object, "transform"), 0), "matrix");
    for (int i = 0; i < 3; i++)
        out[i] = num(m, 4 * i) * p[0] + num(m, 4 * i + 1) * p[1] + num(m, 4 * i + 2) * p[2] +
                 num(m, 4 * i + 3);
}

Test(collada, geometry_transforms_and_instances, .timeout = 60)
{
    const char *dir = test_temp_dir();
    char body[8192];
    snprintf(body, sizeof body,
             HEADER("Z_UP") "<library_materials><material id=\"red\"><instance_effect url=\"#fx\"/>"
             "</material></library_materials>\n"
             "<library_effects><effect id=\"fx\"><profile_COMMON><technique sid=\"c\"><lambert>"
             "<diffuse><color>0.7 0.1 0.1 1</color></diffuse></lambert></technique></profile_COMMON>"
             "</effect></library_effects>\n%s"
             "<library_nodes><node id=\"lib\"><translate>0 0 5</translate>"
             "<instance_geometry url=\"#shape\"/></node></library_nodes>\n"
             "<library_visual_scenes><visual_scene id=\"s\">\n"
             /* translate then rotate 90 about z then scale 2: p' = T R S p */
             "<node id=\"a\"><translate>1 2 3</translate><rotate>0 0 1 90</rotate><scale>2 2 2</scale>"
             "<instance_geometry url=\"#shape\"><bind_material><technique_common>"
             "<instance_material symbol=\"m1\" target=\"#red\"/></technique_common></bind_material>"
             "</instance_geometry></node>\n"
             "<node id=\"b\"><matrix>1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1</matrix>"
             "<instance_geometry url=\"#shape\"><bind_material><technique_common>"
             "<instance_material symbol=\"m1\" target=\"#red\"/></technique_common></bind_material>"
             "</instance_geometry>"
             "<node id=\"c\"><translate>0 1 0</translate><instance_node url=\"#lib\"/></node></node>\n"
             "</visual_scene></library_visual_scenes>\n"
             "<scene><instance_visual_scene url=\"#s\"/></scene>\n",
             geometry_library);
    const char *path = write_dae(dir, "shapes.dae", body);
    ImportedScene s = {0};
    Error err = {0};
    cr_assert(import_collada(path, &s, &err), "%s", err.message);
    /* a and b bind the same material: one mesh; the library node binds none: a second one. */
    cr_assert_eq(s.num_meshes, 2, "meshes: %d", s.num_meshes);
    const Mesh *m = &s.meshes[imported_scene_find_mesh(&s, "shape")].mesh;
    cr_expect_eq(m->num_triangles, 2 + 3 + 1, "quad 2 + pentagon 3 + triangle 1, got %zu",
                 m->num_triangles);
    cr_expect_eq(m->num_faces, 3);
    cr_expect_str_eq(m->materials[0].name, "red");
    cr_expect(fabsf(m->materials[0].kd[0] - 0.7f) < 1e-6f && m->materials[0].illum == 1);
    const cJSON *objects = get(s.root, "objects");
    cr_assert_eq(cJSON_GetArraySize(objects), 3);
    cr_expect_str_eq(get(cJSON_GetArrayItem(objects, 0), "mesh")->valuestring, "shape");
    cr_expect_str_eq(get(cJSON_GetArrayItem(objects, 1), "mesh")->valuestring, "shape");
    /* Node a: (1, 0, 0) -> S (2, 0, 0) -> R (0, 2, 0) -> T (1, 4, 3) in Z-up; +y up: (1, 3, -4). */
    double p[3] = {1, 0, 0}, w[3];
    object_point(cJSON_GetArrayItem(objects, 0), p, w);
    cr_expect(fabs(w[0] - 1) < 1e-9 && fabs(w[1] - 3) < 1e-9 && fabs(w[2] + 4) < 1e-9,
              "node a maps (1,0,0) to (%g, %g, %g), expected (1, 3, -4)", w[0], w[1], w[2]);
    /* Node c inside b: (0, 0, 0) -> lib (0, 0, 5) -> c (0, 1, 5) -> b (10, 1, 5); +y up (10, 5, -1). */
    double o[3] = {0, 0, 0};
    object_point(cJSON_GetArrayItem(objects, 2), o, w);
    cr_expect(fabs(w[0] - 10) < 1e-9 && fabs(w[1] - 5) < 1e-9 && fabs(w[2] + 1) < 1e-9,
              "nested instance_node at (%g, %g, %g), expected (10, 5, -1)", w[0], w[1], w[2]);
    imported_scene_free(&s);
}

Test(collada, cameras_and_lights, .timeout = 60)
{
    const char *dir = test_temp_dir();
    const char *path = write_dae(dir, "lights.dae",
        HEADER("Y_UP")
        "<library_cameras><camera id=\"cam\"><optics><technique_common><perspective>"
        "<xfov>60</xfov><aspect_ratio>2</aspect_ratio></perspective></technique_common></optics>"
        "</camera></library_cameras>\n"
        "<library_lights>"
        "<light id=\"pt\"><technique_common><point><color>1 2 3</color></point></technique_common></light>"
        "<light id=\"sp\"><technique_common><spot><color>4 4 4</color><falloff_angle>40</falloff_angle>"
        "</spot></technique_common></light>"
        "<light id=\"sun\"><technique_common><directional><color>5 5 5</color></directional>"
        "</technique_common></light></library_lights>\n"
        "<library_visual_scenes><visual_scene id=\"s\">"
        "<node id=\"c\"><lookat>0 0 10 0 0 0 0 1 0</lookat><instance_camera url=\"#cam\"/></node>"
        "<node id=\"l1\"><translate>1 2 3</translate><instance_light url=\"#pt\"/></node>"
        "<node id=\"l2\"><translate>0 5 0</translate><rotate>1 0 0 -90</rotate><instance_light url=\"#sp\"/></node>"
        "<node id=\"l3\"><rotate>0 1 0 90</rotate><instance_light url=\"#sun\"/></node>"
        "</visual_scene></library_visual_scenes>\n");
    ImportedScene s = {0};
    Error err = {0};
    cr_assert(import_collada(path, &s, &err), "%s", err.message);
    const cJSON *camera = get(s.root, "camera");
    expect_vec3(get(camera, "eye"), 0, 0, 10, 1e-6, "camera eye");
    expect_vec3(get(camera, "target"), 0, 0, 9, 1e-6, "camera looks along -z");
    double fov_y = 2 * atan(tan(30 * M_PI / 180) / 2) * 180 / M_PI;
    cr_expect(fabs(get(camera, "fov_y")->valuedouble - fov_y) < 1e-3, "fov_y %g, expected %g",
              get(camera, "fov_y")->valuedouble, fov_y);
    cr_expect_eq(get(get(s.root, "film"), "height")->valueint, 320, "640 wide at aspect 2");
    const cJSON *lights = get(s.root, "lights");
    cr_assert_eq(cJSON_GetArraySize(lights), 3);
    const cJSON *l = cJSON_GetArrayItem(lights, 0);
    cr_expect_str_eq(get(l, "type")->valuestring, "point");
    expect_vec3(get(l, "position"), 1, 2, 3, 1e-6, "point position");
    expect_vec3(get(l, "intensity"), 1, 2, 3, 1e-6, "point intensity");
    l = cJSON_GetArrayItem(lights, 1);
    cr_expect_str_eq(get(l, "type")->valuestring, "spot");
    expect_vec3(get(l, "direction"), 0, -1, 0, 1e-6, "spot turned -90 about x looks down");
    cr_expect(fabs(get(l, "cone_angle")->valuedouble - 20) < 1e-6, "cone = falloff_angle / 2");
    l = cJSON_GetArrayItem(lights, 2);
    cr_expect_str_eq(get(l, "type")->valuestring, "directional");
    expect_vec3(get(l, "direction"), -1, 0, 0, 1e-6, "-z turned 90 about y is -x");
    expect_vec3(get(l, "irradiance"), 5, 5, 5, 1e-6, "irradiance");
    imported_scene_free(&s);
}

/* A CS184-style scene: CGL techniques, an area light, a sphere. */
static const char *cs184_scene(const char *dir, const char *name)
{
    char body[8192];
    snprintf(body, sizeof body,
        HEADER("Z_UP")
        "<library_lights><light id=\"area\"><technique_common><point><color>1 1 1</color>"
        "<quadratic_attenuation>0.001</quadratic_attenuation></point></technique_common>"
        "<extra><technique profile=\"CGL\"><area><color>7 8 9</color></area></technique></extra>"
        "</light></library_lights>\n"
        "<library_effects>"
        "<effect id=\"gold-fx\"><profile_COMMON><technique sid=\"c\"><phong><diffuse><color>1 1 1 1</color>"
        "</diffuse></phong></technique></profile_COMMON><extra><technique profile=\"CGL\"><microfacet>"
        "<alpha>0.25</alpha><eta>0.1 0.2 0.3</eta><k>3 2 1</k></microfacet></technique></extra></effect>"
        "<effect id=\"glass-fx\"><extra><technique profile=\"CMU462\"><glass><ior>1.45</ior>"
        "<roughness>0</roughness><reflectance>1 1 1</reflectance><transmittance>1 0.5 1</transmittance>"
        "</glass></technique></extra></effect>"
        "<effect id=\"lamp-fx\"><extra><technique profile=\"CGL\"><emission><radiance>3 3 3</radiance>"
        "</emission></technique></extra></effect>"
        "<effect id=\"wall-fx\"><profile_COMMON><technique sid=\"c\"><phong><diffuse><color>0.2 0.6 0.2 1"
        "</color></diffuse><specular><color>0.5 0.5 0.5 1</color></specular></phong></technique>"
        "</profile_COMMON></effect></library_effects>\n"
        "<library_materials><material id=\"gold\"><instance_effect url=\"#gold-fx\"/></material>"
        "<material id=\"glass\"><instance_effect url=\"#glass-fx\"/></material>"
        "<material id=\"lamp\"><instance_effect url=\"#lamp-fx\"/></material>"
        "<material id=\"wall\"><instance_effect url=\"#wall-fx\"/></material></library_materials>\n%s"
        "<library_visual_scenes><visual_scene id=\"s\">"
        "<node id=\"A\"><matrix>0.6 0 0 0 0 0.8 0 0 0 0 1 1.5 0 0 0 1</matrix><instance_light url=\"#area\"/></node>"
        "<node id=\"s1\"><translate>0.5 0 0.5</translate><instance_geometry url=\"#ball\"><bind_material>"
        "<technique_common><instance_material symbol=\"x\" target=\"#gold\"/></technique_common>"
        "</bind_material></instance_geometry></node>"
        "<node id=\"s2\"><translate>-0.5 0 0.5</translate><instance_geometry url=\"#ball\"><bind_material>"
        "<technique_common><instance_material symbol=\"x\" target=\"#glass\"/></technique_common>"
        "</bind_material></instance_geometry></node>"
        "<node id=\"w\"><translate>-2 -2 0</translate><scale>0.5 2 1</scale><instance_geometry url=\"#shape\"><bind_material>"
        "<technique_common><instance_material symbol=\"m1\" target=\"#wall\"/></technique_common>"
        "</bind_material></instance_geometry></node>"
        "<node id=\"lampmesh\"><translate>0 0 1.49</translate><instance_geometry url=\"#shape\"><bind_material>"
        "<technique_common><instance_material symbol=\"m1\" target=\"#lamp\"/></technique_common>"
        "</bind_material></instance_geometry></node>"
        "</visual_scene></library_visual_scenes>\n", cs184_geometry_library);
    return write_dae(dir, name, body);
}

Test(collada, cs184_materials_spheres_and_area_lights, .timeout = 60)
{
    const char *path = cs184_scene(test_temp_dir(), "cs184.dae");
    ImportedScene s = {0};
    Error err = {0};
    int warnings = warning_count();
    cr_assert(import_collada(path, &s, &err), "%s", err.message);
    cr_expect_geq(warning_count() - warnings, 1, "the dropped lamp mesh is warned about");
    const cJSON *mats = get(s.root, "materials");
    const cJSON *gold = get(mats, "gold");
    cr_expect_str_eq(get(gold, "type")->valuestring, "conductor");
    cr_expect(fabs(get(gold, "roughness")->valuedouble - 0.5) < 1e-6, "alpha 0.25 = r^2, r 0.5");
    expect_vec3(get(gold, "eta"), 0.1, 0.2, 0.3, 1e-6, "eta");
    expect_vec3(get(gold, "k"), 3, 2, 1, 1e-6, "k");
    const cJSON *glass = get(mats, "glass");
    cr_expect_str_eq(get(glass, "type")->valuestring, "dielectric");
    cr_expect(fabs(get(glass, "ior")->valuedouble - 1.45) < 1e-6);
    expect_vec3(get(glass, "tint"), 1, 0.5, 1, 1e-6, "tint = transmittance");
    const cJSON *wall = get(mats, "wall");
    cr_expect_str_eq(get(wall, "type")->valuestring, "diffuse", "CS184 renders phong as Lambert");
    expect_vec3(get(wall, "albedo"), 0.2, 0.6, 0.2, 1e-6, "wall albedo");
    /* Two spheres with two bindings: two meshes of the sphere's tessellation. */
    int ball = imported_scene_find_mesh(&s, "ball"), ball1 = imported_scene_find_mesh(&s, "ball#1");
    cr_assert(ball >= 0 && ball1 >= 0);
    Mesh ref;
    float centre[3] = {0, 0, 0};
    cr_assert(mesh_sphere(&ref, centre, 0.5f, MESH_SPHERE_SEGMENTS));
    cr_expect_eq(s.meshes[ball].mesh.num_triangles, ref.num_triangles);
    cr_expect_eq(memcmp(s.meshes[ball].mesh.positions, ref.positions, ref.num_positions * 12), 0,
                 "the CGL radius is the mesh's");
    mesh_free(&ref);
    cr_expect_str_eq(s.meshes[ball].mesh.materials[0].name, "gold");
    cr_expect_str_eq(s.meshes[ball1].mesh.materials[0].name, "glass");
    /* Objects: 2 spheres, the wall, the area light; the emissive lamp mesh dropped. */
    const cJSON *objects = get(s.root, "objects");
    cr_assert_eq(cJSON_GetArraySize(objects), 4, "objects: %d", cJSON_GetArraySize(objects));
    const cJSON *lamp = cJSON_GetArrayItem(objects, 3);
    cr_expect_str_eq(get(lamp, "mesh")->valuestring, "cgl_area_light");
    const cJSON *lamp_mat = get(mats, get(lamp, "material")->valuestring);
    expect_vec3(get(lamp_mat, "emission"), 7, 8, 9, 1e-6, "area light radiance");
    /* The square's corner (1, 1, 0) of [-1, 1]^2 is the light's (0.5, -0.5, 0) (halved, turned
     * over about x), scaled to (0.3, -0.4, 1.5) in Z-up, (0.3, 1.5, 0.4) +y up. */
    double corner[3] = {1, 1, 0}, w[3];
    object_point(lamp, corner, w);
    cr_expect(fabs(w[0] - 0.3) < 1e-6 && fabs(w[1] - 1.5) < 1e-6 && fabs(w[2] - 0.4) < 1e-6,
              "area light corner at (%g, %g, %g)", w[0], w[1], w[2]);
    /* Its front (+z of the square, turned over: the light's -z, Z-up's down) faces -y. */
    double n0[3] = {0, 0, 0}, n1[3] = {0, 0, 1}, a[3], b[3];
    object_point(lamp, n0, a);
    object_point(lamp, n1, b);
    cr_expect(b[1] - a[1] < -0.1 && fabs(b[0] - a[0]) < 1e-9, "the area light shines down");
    imported_scene_free(&s);
}

/* The same scene through the renderer: the COLLADA file and a JSON scene with the same OBJ
 * geometry, materials and matrices flatten to the same arrays: the same bits. */
Test(collada, renders_the_bits_of_its_json_twin, .timeout = 300)
{
    const char *dir = test_temp_dir();
    char body[8192];
    snprintf(body, sizeof body,
        HEADER("Y_UP")
        "<library_cameras><camera id=\"cam\"><optics><technique_common><perspective>"
        "<yfov>40</yfov></perspective></technique_common></optics></camera></library_cameras>\n"
        "<library_effects><effect id=\"red-fx\"><profile_COMMON><technique sid=\"c\"><lambert>"
        "<diffuse><color>0.8 0.2 0.2 1</color></diffuse></lambert></technique></profile_COMMON></effect>"
        "<effect id=\"lamp-fx\"><profile_COMMON><technique sid=\"c\"><lambert><emission><color>4 4 4 1"
        "</color></emission><diffuse><color>0 0 0 1</color></diffuse></lambert></technique>"
        "</profile_COMMON></effect></library_effects>\n"
        "<library_materials><material id=\"red\"><instance_effect url=\"#red-fx\"/></material>"
        "<material id=\"lamp\"><instance_effect url=\"#lamp-fx\"/></material></library_materials>\n%s"
        "<library_visual_scenes><visual_scene id=\"s\">"
        "<node id=\"c\"><lookat>2 1 8 2 1 0 0 1 0</lookat><instance_camera url=\"#cam\"/></node>"
        "<node id=\"a\"><rotate>0 0 1 10</rotate><instance_geometry url=\"#shape\"><bind_material>"
        "<technique_common><instance_material symbol=\"m1\" target=\"#red\"/></technique_common>"
        "</bind_material></instance_geometry></node>"
        "<node id=\"b\"><matrix>1 0 0 0 0 0 -1 3 0 1 0 1 0 0 0 1</matrix><instance_geometry url=\"#shape\">"
        "<bind_material><technique_common><instance_material symbol=\"m1\" target=\"#lamp\"/>"
        "</technique_common></bind_material></instance_geometry></node>"
        "</visual_scene></library_visual_scenes>\n", geometry_library);
    const char *dae = write_dae(dir, "twin.dae", body);
    /* Two files: the COLLADA's two bindings of one geometry are two meshes. */
    static const char *const shape = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 3 0 0\nv 4 0 0\n"
                                     "v 4.5 1 0\nv 3.5 2 0\nv 2.5 1 0\nv 6 0 0\n"
                                     "f 1 2 3 4\nf 5 6 7 8 9\nf 6 10 7\n";
    char obj[512];
    snprintf(obj, sizeof obj, "mtllib m.mtl\nusemtl red\n%s", shape);
    test_write_file(dir, "shape.obj", obj);
    snprintf(obj, sizeof obj, "mtllib m.mtl\nusemtl lamp\n%s", shape);
    test_write_file(dir, "lamp.obj", obj);
    /* The common profile's lambert is MTL's illum 1 with Kd (and Ke). */
    test_write_file(dir, "m.mtl", "newmtl red\nillum 1\nKd 0.8 0.2 0.2\n"
                                  "newmtl lamp\nillum 1\nKd 0 0 0\nKe 4 4 4\n");
    double c = cos(10 * M_PI / 180), s10 = sin(10 * M_PI / 180);
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"eye\": [2, 1, 8], \"target\": [2, 1, 7], \"up\": [0, 1, 0], \"fov_y\": 40},\n"
             " \"film\": {\"width\": 24, \"height\": 24},\n"

             " \"objects\": [{\"obj\": \"shape.obj\", \"transform\": [{\"matrix\": "
             "[%.17g, %.17g, 0, 0, %.17g, %.17g, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]}]},\n"
             "  {\"obj\": \"lamp.obj\", \"transform\": [{\"matrix\": "
             "[1, 0, 0, 0, 0, 0, -1, 3, 0, 1, 0, 1, 0, 0, 0, 1]}]}]}\n",
             c, -s10, s10, c);
    const char *twin = test_write_file(dir, "twin.json", json);
    RenderSettings rs = {.spp = 8, .max_depth = 4, .seed = 9};
    RenderFixture f;
    render_fixture_open(&f, dae, 24, 24);
    float *a = render_fixture_render(&f, rs, NULL);
    render_fixture_close(&f);
    render_fixture_open(&f, twin, 24, 24);
    float *b = render_fixture_render(&f, rs, NULL);
    render_fixture_close(&f);
    double sum = 0;
    for (int i = 0; i < 24 * 24 * 3; i++)
        sum += a[i];
    cr_expect_gt(sum, 1.0, "the image is not black");
    cr_expect(memcmp(a, b, 24 * 24 * 3 * sizeof(float)) == 0, "the COLLADA scene and its JSON twin differ");
    free(a), free(b);
}

static void expect_error(const char *dir, const char *name, const char *body, const char *needle1,
                         const char *needle2)
{
    const char *path = write_dae(dir, name, body);
    ImportedScene s = {0};
    Error err = {0};
    cr_expect_not(import_collada(path, &s, &err), "%s was accepted", name);
    cr_expect(strstr(err.message, name) && strstr(err.message, needle1) &&
                  (!needle2 || strstr(err.message, needle2)) && !strchr(err.message, '\n'),
              "%s: message \"%s\" lacks \"%s\" / \"%s\"", name, err.message, needle1,
              needle2 ? needle2 : "");
    imported_scene_free(&s);
}

Test(collada, bad_files_fail_in_one_line_naming_file_line_and_element, .timeout = 60)
{
    const char *dir = test_temp_dir();
    expect_error(dir, "unclosed.dae", HEADER("Y_UP") "<library_geometries>", "malformed XML", NULL);
    expect_error(dir, "matrix.dae", HEADER("Y_UP")
                 "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">\n"
                 "<matrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 1</matrix></node></visual_scene>"
                 "</library_visual_scenes>", ":5: <matrix>", "16 numbers");
    char body[4096];
    snprintf(body, sizeof body, "%s%s", HEADER("Y_UP"),
             "<library_geometries><geometry id=\"g\"><mesh><source id=\"p\"><float_array id=\"pa\" "
             "count=\"9\">0 0 0 1 0 0 0 1 0</float_array><technique_common><accessor source=\"#pa\" "
             "count=\"3\" stride=\"3\"/></technique_common></source><vertices id=\"v\"><input "
             "semantic=\"POSITION\" source=\"#p\"/></vertices><triangles count=\"1\"><input "
             "semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>0 1 7</p></triangles></mesh>"
             "</geometry></library_geometries>");
    expect_error(dir, "index.dae", body, "<p>", "index 7 out of range");
    expect_error(dir, "missing.dae", HEADER("Y_UP")
                 "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
                 "<instance_geometry url=\"#nothing\"/></node></visual_scene></library_visual_scenes>",
                 "<instance_geometry>", "no geometry \"#nothing\"");
    expect_error(dir, "cycle.dae", HEADER("Y_UP")
                 "<library_nodes><node id=\"x\"><instance_node url=\"#x\"/></node></library_nodes>"
                 "<library_visual_scenes><visual_scene id=\"s\"><node id=\"n\">"
                 "<instance_node url=\"#x\"/></node></visual_scene></library_visual_scenes>",
                 "deeper than 64", NULL);
    expect_error(dir, "escape.dae", HEADER("Y_UP")
                 "<library_images><image id=\"i\"><init_from>../../etc/passwd</init_from></image>"
                 "</library_images><library_effects><effect id=\"e\"><profile_COMMON><technique sid=\"c\">"
                 "<lambert><diffuse><texture texture=\"i\" texcoord=\"uv\"/></diffuse></lambert>"
                 "</technique></profile_COMMON></effect></library_effects><library_materials>"
                 "<material id=\"m\"><instance_effect url=\"#e\"/></material></library_materials>",
                 "../../etc/passwd", NULL);
    expect_error(dir, "noscene.dae", HEADER("Y_UP"), "no <visual_scene>", NULL);
}
