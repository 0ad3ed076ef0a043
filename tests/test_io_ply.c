// SPDX-License-Identifier: MIT
/* PLY import (host/io/ply_reader.c): one mesh with normals, uvs, a quad and a concave pentagon,
 * written as OBJ and as PLY ascii, binary little- and big-endian (with properties and an element
 * to skip), loads to the same triangles as the OBJ; short faces and tristrips; scenes name PLY
 * files with "ply" and render like the OBJ. Bad input: test_io_ply_bad_input.c; the shared
 * writers: ply_fixtures.c. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/obj_loader.h"
#include "io/ply_reader.h"
#include "scene/scene.h"
#include "ply_fixtures.h"
#include "support.h"

static void expect_same_mesh(const Mesh *a, const Mesh *b, const char *what)
{
    cr_assert_eq(a->num_positions, b->num_positions, "%s", what);
    cr_assert_eq(a->num_normals, b->num_normals, "%s", what);
    cr_assert_eq(a->num_texcoords, b->num_texcoords, "%s", what);
    cr_assert_eq(a->num_triangles, b->num_triangles, "%s", what);
    cr_assert_eq(a->num_faces, b->num_faces, "%s", what);
    cr_assert(!memcmp(a->positions, b->positions, 3 * a->num_positions * sizeof(float)), "%s", what);
    cr_assert(!memcmp(a->normals, b->normals, 3 * a->num_normals * sizeof(float)), "%s", what);
    cr_assert(!memcmp(a->texcoords, b->texcoords, 2 * a->num_texcoords * sizeof(float)), "%s", what);
    cr_assert(!memcmp(a->corners, b->corners, 9 * a->num_triangles * sizeof(int32_t)), "%s", what);
    for (size_t t = 0; t < b->num_triangles; t++)
        cr_assert_eq(b->material_ids[t], -1, "%s", what);
    cr_assert_eq(b->num_materials, 0u, "%s", what);
}

Test(ply, every_format_loads_like_the_obj)
{
    const char *dir = test_temp_dir();
    Error err = {0};
    Mesh obj;
    cr_assert(obj_load(write_obj(dir), &obj, &err), "%s", err.message);
    cr_assert_eq(obj.num_triangles, 2u + 3u + 1u); /* quad, pentagon, triangle */
    const char *paths[] = {write_ascii(dir), NULL, NULL};
    char little[1024], big[1024];
    snprintf(little, sizeof little, "%s", write_binary(dir, false));
    snprintf(big, sizeof big, "%s", write_binary(dir, true));
    paths[1] = little, paths[2] = big;
    for (int i = 0; i < 3; i++) {
        Mesh ply;
        load_ply_ok(paths[i], &ply);
        expect_same_mesh(&obj, &ply, paths[i]);
        mesh_free(&ply);
    }
    mesh_free(&obj);
}

Test(ply, short_faces_are_skipped_with_a_warning)
{
    const char *path = test_write_file(test_temp_dir(), "short.ply",
                                       HEAD "element face 3\nproperty list uchar int vertex_indices\nend_header\n" TRI
                                       "2 0 1\n3 0 1 2\n0\n");
    int before = warning_count();
    warnings_set_quiet(true);
    Mesh mesh;
    load_ply_ok(path, &mesh);
    cr_assert_eq(warning_count(), before + 1);
    cr_assert_eq(mesh.num_triangles, 1u);
    cr_assert_eq(mesh.num_faces, 1u);
    cr_assert_null(mesh.normals);
    cr_assert_eq(mesh.corners[1], -1);
    cr_assert_eq(mesh.corners[2], -1);
    mesh_free(&mesh);
}


static const char *write_scene(const char *dir, const char *name, const char *object)
{
    char text[2048];
    snprintf(text, sizeof text,
             "{\"camera\": {\"eye\": [1.5, 0.8, 4], \"target\": [1.5, 0.8, 0], \"up\": [0, 1, 0], "
             "\"fov_y\": 50},\n \"film\": {\"width\": 24, \"height\": 16},\n"
             " \"render\": {\"spp\": 4, \"max_depth\": 3},\n \"background\": [1, 1, 1],\n"
             " \"objects\": [%s]}\n",
             object);
    return test_write_file(dir, name, text);
}

/* The key, not the extension, says how to read the file; exactly one of "obj" and "ply". */
Test(ply, scene_keys)
{
    const char *dir = test_temp_dir();
    write_obj(dir);
    size_t size;
    char *text = test_read_file(write_ascii(dir), &size);
    test_write_file(dir, "mesh.data", text);
    free(text);
    SceneDesc d;
    Error err = {0};
    cr_assert(scene_desc_load(write_scene(dir, "a.json", "{\"ply\": \"mesh.data\"}"), &d, &err), "%s", err.message);
    cr_assert_eq(d.object_formats[0], MESH_PLY);
    scene_desc_free(&d);
    Scene scene;
    cr_assert(scene_load(write_scene(dir, "b.json", "{\"ply\": \"mesh.data\", \"smooth\": true}"), &scene, &err),
              "%s", err.message);
    scene_free(&scene);
    const char *both = write_scene(dir, "c.json", "{\"obj\": \"mesh.obj\", \"ply\": \"ascii.ply\"}");
    cr_assert(!scene_desc_load(both, &d, &err));
    cr_assert(strstr(err.message, "objects[0]") && strstr(err.message, "both"), "%s", err.message);
    Error err2 = {0};
    cr_assert(!scene_desc_load(write_scene(dir, "d.json", "{\"material\": \"x\"}"), &d, &err2));
    cr_assert(strstr(err2.message, "objects[0]") && strstr(err2.message, "missing"), "%s", err2.message);
    Error err3 = {0};
    cr_assert(!scene_load(write_scene(dir, "e.json", "{\"ply\": \"mesh.obj\"}"), &scene, &err3));
    cr_assert(strstr(err3.message, "mesh.obj") && strstr(err3.message, "not a PLY file"), "%s", err3.message);
    Error err4 = {0};
    cr_assert(scene_desc_load(write_ascii(dir), &d, &err4), "%s", err4.message);
    cr_assert_eq(d.num_objects, 1);
    cr_assert_eq(d.object_formats[0], MESH_PLY);
    cr_assert(!d.camera_given);
    scene_desc_free(&d);
}

/* The same mesh as OBJ and as binary PLY, placed by the same transform, renders bit for bit the
 * same: the same triangles in the same order. */
Test(ply, renders_like_the_obj)
{
    const char *dir = test_temp_dir();
    write_obj(dir);
    write_binary(dir, true);
    const char *placement = "\"smooth\": true, \"transform\": [{\"rotate\": {\"axis\": [0, 1, 0], "
                            "\"angle\": 20}}, {\"translate\": [0.2, 0, 0]}]";
    char object[512];
    snprintf(object, sizeof object, "{\"obj\": \"mesh.obj\", %s}", placement);
    char obj_scene[1024], ply_scene[1024];
    snprintf(obj_scene, sizeof obj_scene, "%s", write_scene(dir, "obj.json", object));
    snprintf(object, sizeof object, "{\"ply\": \"big.ply\", %s}", placement);
    snprintf(ply_scene, sizeof ply_scene, "%s", write_scene(dir, "ply.json", object));
    float *images[2];
    const char *scenes[2] = {obj_scene, ply_scene};
    for (int i = 0; i < 2; i++) {
        RenderFixture f;
        render_fixture_open(&f, scenes[i], 0, 0);
        images[i] = render_fixture_render(&f, (RenderSettings){.spp = 4, .max_depth = 3, .seed = 5}, NULL);
        render_fixture_close(&f);
    }
    size_t n = 3 * 24 * 16;
    float sum = 0.0f;
    for (size_t k = 0; k < n; k++)
        sum += images[0][k];
    cr_assert(sum < 0.99f * (float)n, "the mesh is not in view (the image is all background)");
    cr_assert(!memcmp(images[0], images[1], n * sizeof(float)), "the PLY renders differently");
    free(images[0]);
    free(images[1]);
}

/* Corners of triangle t of a loaded mesh (position indices). */
static void expect_triangle(const Mesh *m, size_t t, int a, int b, int c)
{
    const int32_t *k = m->corners + 9 * t;
    cr_expect(k[0] == a && k[3] == b && k[6] == c, "triangle %zu is %d %d %d, expected %d %d %d", t,
              k[0], k[3], k[6], a, b, c);
}

/* tristrips (Cyberware scans): each index after two makes a triangle, every other one swapped so
 * that all wind like the first; -1 restarts; repeated corners make no triangle. The same strip
 * in ascii and binary big-endian (the scans' order). */
Test(ply, tristrips_with_restarts_keep_their_winding)
{
    const char *dir = test_temp_dir();
    static const int strip[] = {0, 1, 2, 3, 4, -1, 5, 1, 1, 2, 3};
    const int n = sizeof strip / sizeof strip[0];
    char text[2048];
    int len = snprintf(text, sizeof text, "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\n"
                       "property float y\nproperty float z\nelement tristrips 1\n"
                       "property list int int vertex_indices\nend_header\n");
    for (int v = 0; v < 6; v++)
        len += snprintf(text + len, sizeof text - len, "%d %d 0\n", v % 3, v / 3);
    len += snprintf(text + len, sizeof text - len, "%d", n);
    for (int i = 0; i < n; i++)
        len += snprintf(text + len, sizeof text - len, " %d", strip[i]);
    snprintf(text + len, sizeof text - len, "\n");
    char path[1024];
    snprintf(path, sizeof path, "%s/big.ply", dir);
    FILE *f = fopen(path, "wb");
    cr_assert(f);
    fprintf(f, "ply\nformat binary_big_endian 1.0\nelement vertex 6\nproperty float x\nproperty float y\n"
            "property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n");
    for (int v = 0; v < 6; v++) {
        float xyz[3] = {(float)(v % 3), (float)(v / 3), 0};
        for (int c = 0; c < 3; c++) {
            uint32_t bits;
            memcpy(&bits, &xyz[c], 4);
            unsigned char be[4] = {bits >> 24, bits >> 16, bits >> 8, bits};
            fwrite(be, 1, 4, f);
        }
    }
    for (int i = -1; i < n; i++) {
        uint32_t value = (uint32_t)(i < 0 ? n : strip[i]);
        unsigned char be[4] = {value >> 24, value >> 16, value >> 8, value};
        fwrite(be, 1, 4, f);
    }
    fclose(f);
    const char *paths[] = {test_write_file(dir, "strip.ply", text), path};
    for (int i = 0; i < 2; i++) {
        Mesh m;
        load_ply_ok(paths[i], &m);
        /* 0 1 2 3 4: (0 1 2) (2 1 3) (2 3 4); restart 5 1 1 2 3: (5 1 1) and (1 1 2) are
         * degenerate (not drawn, but they count for the winding), then (1 2 3) at even parity. */
        cr_assert_eq(m.num_triangles, 4, "%s: %zu triangles", paths[i], m.num_triangles);
        expect_triangle(&m, 0, 0, 1, 2);
        expect_triangle(&m, 1, 2, 1, 3);
        expect_triangle(&m, 2, 2, 3, 4);
        expect_triangle(&m, 3, 1, 2, 3);
        mesh_free(&m);
    }
    expect_error("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 "property float z\nelement tristrips 1\nproperty list int int vertex_indices\n"
                 "end_header\n" TRI "4 0 1 2 -2\n", ERR_OBJ_INDEX, "tristrips 0: vertex index -2");
}

/* Header lines of other writers (Blender 2.47's "Created by ...", one over 255 bytes) are
 * ignored; a point cloud's message is in PLY's words, not OBJ's records. */
Test(ply, unknown_header_lines_are_ignored_and_point_clouds_named)
{
    const char *dir = test_temp_dir();
    char long_line[400];
    memset(long_line, 'x', sizeof long_line - 1);
    long_line[sizeof long_line - 1] = '\0';
    char text[1024];
    snprintf(text, sizeof text, "ply\nformat ascii 1.0\nCreated by Blender3D 247 - www.blender.org, "
             "source file: 'x.blend'\n%s\n" HEAD FACE "end_header\n" TRI "3 0 1 2\n", long_line);
    Mesh m;
    load_ply_ok(test_write_file(dir, "blender.ply", text), &m);
    cr_expect_eq(m.num_triangles, 1);
    mesh_free(&m);
    const char *cloud = test_write_file(dir, "cloud.ply", HEAD "end_header\n" TRI);
    Scene s;
    Error err = {0};
    cr_assert_not(scene_load(cloud, &s, &err));
    cr_expect(strstr(err.message, "a point cloud: 3 vertices and no face or tristrips element") &&
              !strstr(err.message, "'f'"), "%s", err.message);
}