// SPDX-License-Identifier: MIT
/* The Assimp path (io/assimp_reader.h, scene/import_assimp.h): binary and ASCII STL the test
 * writes; an ASCII FBX written by Assimp's own exporter from a COLLADA file the test writes (two
 * nodes instancing one mesh, a material, a light): one mesh, two objects at the nodes' places,
 * the diffuse colour; a scene of it loads through scene_desc_load ("mesh" objects); a file Assimp
 * cannot read fails in one line with Assimp's reason. */
#include <assimp/cexport.h>
#include <assimp/cimport.h>
#include <assimp/scene.h>
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "scene/import_assimp.h"
#include "scene/scene.h"
#include "support.h"

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

/* The object's matrix applied to p. */
static void object_point(const cJSON *object, const double p[3], double out[3])
{
    const cJSON *m = get(cJSON_GetArrayItem(get(object, "transform"), 0), "matrix");
    for (int i = 0; i < 3; i++)
        out[i] = num(m, 4 * i) * p[0] + num(m, 4 * i + 1) * p[1] + num(m, 4 * i + 2) * p[2] +
                 num(m, 4 * i + 3);
}

static void write_binary_stl(const char *path)
{
    /* Two triangles of the unit square in z = 0, normal +z. */
    const float tris[2][12] = {{0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 0}};
    FILE *f = fopen(path, "wb");
    cr_assert(f);
    char header[80] = "pt test";
    uint32_t n = 2;
    uint16_t attr = 0;
    fwrite(header, 1, 80, f);
    fwrite(&n, 4, 1, f);
    for (int t = 0; t < 2; t++) {
        fwrite(tris[t], 4, 12, f);
        fwrite(&attr, 2, 1, f);
    }
    fclose(f);
}

Test(assimp, stl_binary_and_ascii, .timeout = 60)
{
    const char *dir = test_temp_dir();
    char path[1024];
    snprintf(path, sizeof path, "%s/square.stl", dir);
    write_binary_stl(path);
    ImportedScene s = {0};
    Error err = {0};
    cr_assert(import_assimp(path, &s, &err), "%s", err.message);
    cr_assert_eq(s.num_meshes, 1);
    const Mesh *m = &s.meshes[0].mesh;
    cr_expect_eq(m->num_triangles, 2);
    double area = 0;
    for (size_t t = 0; t < m->num_triangles; t++) {
        const float *a = m->positions + 3 * m->corners[9 * t], *b = m->positions + 3 * m->corners[9 * t + 3],
                    *c = m->positions + 3 * m->corners[9 * t + 6];
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    cr_expect(fabs(area - 1.0) < 1e-6, "the square's signed area is %g, expected +1 (counter-clockwise)", area);
    cr_expect_eq(cJSON_GetArraySize(get(s.root, "objects")), 1);
    imported_scene_free(&s);

    const char *ascii = test_write_file(dir, "tri.stl",
                                        "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                        "vertex 2 0 0\nvertex 0 3 0\nendloop\nendfacet\nendsolid t\n");
    cr_assert(import_assimp(ascii, &s, &err), "%s", err.message);
    cr_assert_eq(s.num_meshes, 1);
    cr_expect_eq(s.meshes[0].mesh.num_triangles, 1);
    float ymax = 0;
    for (size_t i = 0; i < s.meshes[0].mesh.num_positions; i++)
        ymax = fmaxf(ymax, s.meshes[0].mesh.positions[3 * i + 1]);
    cr_expect(fabsf(ymax - 3.0f) < 1e-6f, "STL axes are kept as written");
    imported_scene_free(&s);
}

static const char *const two_nodes_dae =
    "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
    "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
    "<asset><up_axis>Y_UP</up_axis></asset>\n"
    "<library_lights><light id=\"lamp\" name=\"lamp\"><technique_common><point><color>5 6 7</color>"
    "</point></technique_common></light></library_lights>\n"
    "<library_effects><effect id=\"fx\"><profile_COMMON><technique sid=\"c\"><lambert><diffuse>"
    "<color>0.7 0.2 0.1 1</color></diffuse></lambert></technique></profile_COMMON></effect>"
    "</library_effects>\n"
    "<library_materials><material id=\"red\" name=\"red\"><instance_effect url=\"#fx\"/></material>"
    "</library_materials>\n"
    "<library_geometries><geometry id=\"tri\" name=\"tri\"><mesh><source id=\"p\"><float_array "
    "id=\"pa\" count=\"9\">0 0 0 1 0 0 0 1 0</float_array><technique_common><accessor source=\"#pa\" "
    "count=\"3\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" type=\"float\"/>"
    "<param name=\"Z\" type=\"float\"/></accessor></technique_common></source><vertices id=\"v\">"
    "<input semantic=\"POSITION\" source=\"#p\"/></vertices><triangles material=\"m\" count=\"1\">"
    "<input semantic=\"VERTEX\" source=\"#v\" offset=\"0\"/><p>0 1 2</p></triangles></mesh>"
    "</geometry></library_geometries>\n"
    "<library_visual_scenes><visual_scene id=\"s\">\n"
    "<node id=\"a\" name=\"a\"><translate>1 0 0</translate><instance_geometry url=\"#tri\">"
    "<bind_material><technique_common><instance_material symbol=\"m\" target=\"#red\"/>"
    "</technique_common></bind_material></instance_geometry></node>\n"
    "<node id=\"b\" name=\"b\"><translate>0 0 -5</translate><instance_geometry url=\"#tri\">"
    "<bind_material><technique_common><instance_material symbol=\"m\" target=\"#red\"/>"
    "</technique_common></bind_material></instance_geometry></node>\n"
    "<node id=\"lamp\" name=\"lamp\"><translate>0 4 0</translate><instance_light url=\"#lamp\"/></node>\n"
    "</visual_scene></library_visual_scenes><scene><instance_visual_scene url=\"#s\"/></scene>"
    "</COLLADA>\n";

/* An ASCII FBX of two_nodes_dae, by Assimp's exporter. (Assimp 5.2.5 cannot read back the binary
 * FBX its exporter writes: "block offset is out of range".) */
static const char *write_fbx(const char *dir)
{
    const char *dae = test_write_file(dir, "two.dae", two_nodes_dae);
    const struct aiScene *s = aiImportFile(dae, 0);
    cr_assert(s, "%s", aiGetErrorString());
    static char path[1024];
    snprintf(path, sizeof path, "%s/two.fbx", dir);
    cr_assert_eq(aiExportScene(s, "fbxa", path, 0), aiReturn_SUCCESS, "%s", aiGetErrorString());
    aiReleaseImport(s);
    return path;
}

Test(assimp, fbx_instances_materials_and_lights, .timeout = 60)
{
    const char *path = write_fbx(test_temp_dir());
    ImportedScene s = {0};
    Error err = {0};
    cr_assert(import_assimp(path, &s, &err), "%s", err.message);
    cr_assert_eq(s.num_meshes, 1, "one mesh for both nodes, got %d", s.num_meshes);
    const ObjMaterial *m = &s.meshes[0].mesh.materials[0];
    cr_expect(fabsf(m->kd[0] - 0.7f) < 1e-5f && fabsf(m->kd[1] - 0.2f) < 1e-5f &&
                  fabsf(m->kd[2] - 0.1f) < 1e-5f,
              "diffuse (%g, %g, %g)", m->kd[0], m->kd[1], m->kd[2]);
    const cJSON *objects = get(s.root, "objects");
    cr_assert_eq(cJSON_GetArraySize(objects), 2);
    double o[3] = {0, 0, 0}, a[3], b[3];
    object_point(cJSON_GetArrayItem(objects, 0), o, a);
    object_point(cJSON_GetArrayItem(objects, 1), o, b);
    /* FBX keeps the node order; Assimp's FBX round trip keeps the units (scale 1). */
    cr_expect(fabs(a[0] - 1) < 1e-5 && fabs(a[1]) < 1e-5 && fabs(a[2]) < 1e-5, "a at (%g %g %g)",
              a[0], a[1], a[2]);
    cr_expect(fabs(b[0]) < 1e-5 && fabs(b[1]) < 1e-5 && fabs(b[2] + 5) < 1e-5, "b at (%g %g %g)",
              b[0], b[1], b[2]);
    const cJSON *lights = get(s.root, "lights");
    cr_assert_eq(cJSON_GetArraySize(lights), 1);
    const cJSON *l = cJSON_GetArrayItem(lights, 0);
    cr_expect_str_eq(get(l, "type")->valuestring, "point");
    const cJSON *p = get(l, "position");
    cr_expect(fabs(num(p, 0)) < 1e-5 && fabs(num(p, 1) - 4) < 1e-5 && fabs(num(p, 2)) < 1e-5,
              "light at (%g %g %g)", num(p, 0), num(p, 1), num(p, 2));
    const cJSON *in = get(l, "intensity");
    cr_expect(fabs(num(in, 1) / num(in, 0) - 6.0 / 5.0) < 1e-4, "the light's colour is kept");
    imported_scene_free(&s);

    /* The whole scene description: two objects naming one in-memory mesh. */
    SceneDesc d;
    cr_assert(scene_desc_load(path, &d, &err), "%s", err.message);
    cr_expect_eq(d.num_objects, 2);
    cr_expect(d.object_meshes[0] && d.object_meshes[0] == d.object_meshes[1], "instancing");
    scene_desc_free(&d);
}

Test(assimp, unreadable_files_give_assimps_reason_in_one_line, .timeout = 60)
{
    const char *dir = test_temp_dir();
    const char *bad = test_write_file(dir, "bad.fbx", "this is not an FBX file\n");
    ImportedScene s = {0};
    Error err = {0};
    cr_expect_not(import_assimp(bad, &s, &err));
    cr_expect(strstr(err.message, "bad.fbx: Assimp cannot read it: ") && !strchr(err.message, '\n'),
              "message: %s", err.message);
    imported_scene_free(&s);
    /* Assimp asserts (aborts the process) on an empty buffer: pt refuses it first. */
    const char *empty = test_write_file(dir, "empty.3ds", "");
    err = (Error){0};
    cr_expect_not(import_assimp(empty, &s, &err));
    cr_expect(strstr(err.message, "empty.3ds: the file is empty"), "message: %s", err.message);
    imported_scene_free(&s);
    const char *broken = test_write_file(dir, "broken.stl", "solid x\nfacet normal 0 0 1\nouter loop\n"
                                                            "vertex 0 0 0\nvertex 1 0\nendloop\n");
    err = (Error){0};
    cr_expect_not(import_assimp(broken, &s, &err));
    cr_expect(strstr(err.message, "broken.stl") && !strchr(err.message, '\n'), "message: %s", err.message);
    imported_scene_free(&s);
}
