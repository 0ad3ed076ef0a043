// SPDX-License-Identifier: MIT
/* PLY import (host/io/ply_reader.c): one mesh with normals, uvs, a quad and a concave pentagon,
 * written as OBJ and as PLY ascii, binary little- and big-endian (with properties and an element
 * to skip), loads to the same triangles as the OBJ; each bad input gives its one-line error;
 * mutated files load or fail cleanly; scenes name PLY files with "ply" and render like the OBJ. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/obj_loader.h"
#include "io/ply_reader.h"
#include "scene/scene.h"
#include "support.h"
#include "xorshift.h"

#define NV 10
/* Values exact in binary and decimal, so every writer gives the same floats. */
static const float P[NV][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},    {0, 1, 0},   {2, 0, 0},
                               {4, 0, 0}, {4, 2, 0}, {3, 0.5f, 0}, {2, 2, 0},   {0, 0, 1}};
static const int FACES[][5] = {{0, 1, 2, 3, -1}, {4, 5, 6, 7, 8}, {0, 1, 9, -1, -1}};
#define NF 3

static float normal(int v, int k) { return k == 2 ? 1.0f : 0.125f * (float)(v % 4) * (k ? -1 : 1); }
static float uv(int v, int k) { return k ? 0.25f * (float)(v % 4) : 0.0625f * (float)v; }
static int face_size(int f) { return FACES[f][3] < 0 ? 3 : FACES[f][4] < 0 ? 4 : 5; }

static const char *write_obj(const char *dir)
{
    char text[4096];
    size_t n = 0;
    for (int v = 0; v < NV; v++)
        n += (size_t)snprintf(text + n, sizeof text - n, "v %g %g %g\nvt %g %g\nvn %g %g %g\n",
                              P[v][0], P[v][1], P[v][2], uv(v, 0), uv(v, 1), normal(v, 0),
                              normal(v, 1), normal(v, 2));
    for (int f = 0; f < NF; f++) {
        n += (size_t)snprintf(text + n, sizeof text - n, "f");
        for (int k = 0; k < face_size(f); k++)
            n += (size_t)snprintf(text + n, sizeof text - n, " %d/%d/%d", FACES[f][k] + 1,
                                  FACES[f][k] + 1, FACES[f][k] + 1);
        n += (size_t)snprintf(text + n, sizeof text - n, "\n");
    }
    return test_write_file(dir, "mesh.obj", text);
}

static const char *write_ascii(const char *dir)
{
    char text[4096];
    size_t n = (size_t)snprintf(
        text, sizeof text,
        "ply\r\nformat ascii 1.0\ncomment made by test_ply\nobj_info nothing\n"
        "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty float nx\nproperty float ny\nproperty float nz\n"
        "property list uchar int extra\nproperty float s\nproperty float t\n"
        "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
        "element face %d\nproperty uchar intensity\nproperty list uchar int vertex_indices\n"
        "end_header\n",
        NV, NF);
    for (int v = 0; v < NV; v++)
        n += (size_t)snprintf(text + n, sizeof text - n, "%g %g %g 255 %g %g %g 2 7 8 %g %g\n",
                              P[v][0], P[v][1], P[v][2], normal(v, 0), normal(v, 1), normal(v, 2),
                              uv(v, 0), uv(v, 1));
    n += (size_t)snprintf(text + n, sizeof text - n, "0 1\n");
    for (int f = 0; f < NF; f++) {
        n += (size_t)snprintf(text + n, sizeof text - n, "9 %d", face_size(f));
        for (int k = 0; k < face_size(f); k++)
            n += (size_t)snprintf(text + n, sizeof text - n, " %d", FACES[f][k]);
        n += (size_t)snprintf(text + n, sizeof text - n, "\n");
    }
    return test_write_file(dir, "ascii.ply", text);
}

static void put(FILE *f, const void *value, size_t size, bool big)
{
    const unsigned char *b = value;
    for (size_t i = 0; i < size; i++) /* the host is little-endian (x86, arm64) */
        fputc(b[big ? size - 1 - i : i], f);
}

/* Binary PLY; the big-endian file uses the sized type names, a double and a vertex_index list. */
static const char *write_binary(const char *dir, bool big)
{
    static char path[1024];
    snprintf(path, sizeof path, "%s/%s.ply", dir, big ? "big" : "little");
    FILE *f = fopen(path, "wb");
    cr_assert(f);
    fprintf(f, "ply\nformat %s 1.0\nelement vertex %d\n", big ? "binary_big_endian" : "binary_little_endian", NV);
    fprintf(f, big ? "property float32 x\nproperty float32 y\nproperty float32 z\nproperty float64 confidence\n"
                     "property float32 nx\nproperty float32 ny\nproperty float32 nz\n"
                     "property float32 texture_u\nproperty float32 texture_v\n"
                   : "property float x\nproperty float y\nproperty float z\nproperty double confidence\n"
                     "property float nx\nproperty float ny\nproperty float nz\n"
                     "property float u\nproperty float v\n");
    fprintf(f, "element material 1\nproperty list ushort short names\n");
    fprintf(f, "element face %d\n%s\nproperty short flags\nend_header\n", NF,
            big ? "property list uint8 uint32 vertex_index" : "property list uchar int vertex_indices");
    for (int v = 0; v < NV; v++) {
        double confidence = 0.5;
        put(f, P[v], 4, big), put(f, P[v] + 1, 4, big), put(f, P[v] + 2, 4, big);
        put(f, &confidence, 8, big);
        for (int k = 0; k < 3; k++) {
            float x = normal(v, k);
            put(f, &x, 4, big);
        }
        for (int k = 0; k < 2; k++) {
            float x = uv(v, k);
            put(f, &x, 4, big);
        }
    }
    uint16_t two = 2;
    int16_t name = -3;
    put(f, &two, 2, big), put(f, &name, 2, big), put(f, &name, 2, big);
    for (int fa = 0; fa < NF; fa++) {
        uint8_t n = (uint8_t)face_size(fa);
        put(f, &n, 1, big);
        for (int k = 0; k < n; k++) {
            int32_t index = FACES[fa][k];
            put(f, &index, 4, big);
        }
        int16_t flags = -1;
        put(f, &flags, 2, big);
    }
    fclose(f);
    return path;
}

static void load_ply_ok(const char *path, Mesh *mesh)
{
    Error err = {0};
    cr_assert(ply_load(path, mesh, &err), "%s: %s", path, err.message);
}

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

/* Loading must fail with this code and a message holding `mentions` (and the file's name). */
static void expect_error_file(const char *path, ErrorCode code, const char *mentions)
{
    Mesh mesh;
    Error err = {0};
    cr_assert(!ply_load(path, &mesh, &err), "%s loaded; expected: %s", path, mentions);
    cr_assert_eq(err.code, code, "%s: code %s, expected %s (%s)", path, error_code_name(err.code),
                 error_code_name(code), err.message);
    cr_assert(strstr(err.message, path), "message does not name the file: %s", err.message);
    cr_assert(strstr(err.message, mentions), "message '%s' lacks '%s'", err.message, mentions);
    cr_assert(!strchr(err.message, '\n'), "not one line: %s", err.message);
    cr_assert_null(mesh.positions);
    cr_assert_null(mesh.corners);
}

static void expect_error(const char *text, ErrorCode code, const char *mentions)
{
    expect_error_file(test_write_file(test_temp_dir(), "bad.ply", text), code, mentions);
}

#define HEAD "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
#define TRI "0 0 0\n1 0 0\n0 1 0\n"
#define FACE "element face 1\nproperty list uchar int vertex_indices\n"

Test(ply, bad_header)
{
    expect_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float16 x\nend_header\n", ERR_OBJ_PARSE,
                 "line 4: unknown property type 'float16'");
    expect_error("PLY\nformat ascii 1.0\nend_header\n", ERR_OBJ_PARSE, "line 1: not a PLY file");
    expect_error("ply\nformat ascii 2.0\nend_header\n", ERR_OBJ_PARSE, "line 2: unsupported format version '2.0'");
    expect_error("ply\nformat binary_middle_endian 1.0\nend_header\n", ERR_OBJ_PARSE, "unknown format");
    expect_error(HEAD, ERR_OBJ_PARSE, "missing end_header");
    expect_error("ply\nelement vertex 0\nend_header\n", ERR_OBJ_PARSE, "end_header before any format");
    expect_error("ply\nformat ascii 1.0\nproperty float x\nend_header\n", ERR_OBJ_PARSE, "line 3: property before any element");
    expect_error("ply\nformat ascii 1.0\nelement vertex -3\nend_header\n", ERR_OBJ_PARSE, "line 3: element count '-3'");
    expect_error("ply\nformat ascii 1.0\nelement vertex 99999999999999999999\nend_header\n", ERR_OBJ_PARSE,
                 "element count '99999999999999999999'");
    /* A line of no PLY keyword is ignored (one warning): here the vertex element is lost. */
    expect_error("ply\nformat ascii 1.0\nelemental vertex 3\nend_header\n", ERR_OBJ_PARSE, "no 'vertex' element");
    expect_error(HEAD "property list float int vertex_indices\nend_header\n", ERR_OBJ_PARSE,
                 "list count type 'float' is not an integer type");
    expect_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
                 ERR_OBJ_PARSE, "lacks property x, y or z");
    expect_error(HEAD "element face 1\nproperty int vertex_indices\nend_header\n" TRI "0\n", ERR_OBJ_PARSE,
                 "lacks a vertex_indices list");
    expect_error("ply\nformat ascii 1.0\nelement face 0\nend_header\n", ERR_OBJ_PARSE, "no 'vertex' element");
}

Test(ply, absurd_counts_are_refused_before_allocating)
{
    /* 10^12 vertices (12 TB of floats) in a file of a few bytes: refused by the count check. */
    expect_error("ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\n"
                 "property float y\nproperty float z\nend_header\n0123456789ab",
                 ERR_OBJ_PARSE, "claims 1000000000000 'vertex' elements");
    expect_error(HEAD FACE "end_header\n" TRI "200 0 1 2\n", ERR_OBJ_PARSE, "face 0: list 'vertex_indices' has a bad length 200");
    expect_error(HEAD "element face 1\nproperty list ushort int vertex_indices\nend_header\n" TRI
                 "300 " /* followed by enough bytes to pass the length check */
                 "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 "
                 "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 "
                 "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 "
                 "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 "
                 "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 "
                 "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n",
                 ERR_TOO_LARGE, "face 0 has 300 vertices (the limit is 255)");
}

Test(ply, bad_data)
{
    expect_error(HEAD FACE "end_header\n" TRI "3 0 1 99\n", ERR_OBJ_INDEX,
                 "line 13: face 0: vertex index 99 out of range (3 vertices)");
    expect_error(HEAD FACE "end_header\n" TRI "3 0 -1 2\n", ERR_OBJ_INDEX, "vertex index -1 out of range");
    expect_error(HEAD FACE "end_header\n" TRI "3 0 1.5 2\n", ERR_OBJ_INDEX, "vertex index 1.5 out of range");
    expect_error(HEAD "end_header\n0 0 0\n1 nan 0\n0 1 0\n", ERR_OBJ_NONFINITE, "line 9: vertex 1: property y is not finite");
    expect_error(HEAD "end_header\n0 0 0\n1 0 1e39\n0 1 0\n", ERR_OBJ_NONFINITE, "vertex 1: property z is not finite");
    expect_error(HEAD "end_header\n0 0 0\n1 zero 0\n0 1 0\n", ERR_OBJ_PARSE, "line 9: bad number 'zero'");
    expect_error(HEAD "end_header\n0 0 0\n1 0 0\n", ERR_OBJ_PARSE, "unexpected end of data (vertex 2 of 3)");
    expect_error("ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty uchar x\nproperty uchar y\n"
                 "property uchar z\nproperty list uchar uchar extra\nend_header\nabc\x02xyde", ERR_OBJ_PARSE, "truncated binary data (vertex 1 of 2)");
    expect_error("ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty uchar x\nproperty uchar y\n"
                 "property uchar z\nelement face 1\nproperty list uchar uchar vertex_indices\nend_header\nabc\x03\x01",
                 ERR_OBJ_PARSE, "face 0: list 'vertex_indices' has a bad length 3");
    expect_error_file("/nonexistent/mesh.ply", ERR_FILE_MISSING, "mesh.ply");
    expect_error_file(test_temp_dir(), ERR_FILE_READ, "");
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

/* Random byte changes to the binary files: each loads or fails with a message, within bounds. */
Test(ply, mutated_files_load_or_fail_cleanly)
{
    const char *dir = test_temp_dir();
    const char *sources[] = {write_binary(dir, false), NULL};
    size_t size;
    char *original = test_read_file(sources[0], &size);
    cr_assert(original);
    uint64_t state = 0x9e3779b97f4a7c15ull;
    char path[1024];
    snprintf(path, sizeof path, "%s/mutated.ply", dir);
    for (int round = 0; round < 400; round++) {
        char *copy = malloc(size);
        memcpy(copy, original, size);
        for (int k = 0; k < 1 + round % 4; k++)
            copy[xorshift_next(&state) % size] = (char)xorshift_next(&state);
        size_t length = round % 5 == 4 ? xorshift_next(&state) % size : size;
        FILE *f = fopen(path, "wb");
        fwrite(copy, 1, length, f);
        fclose(f);
        Mesh mesh;
        Error err = {0};
        warnings_set_quiet(true);
        if (ply_load(path, &mesh, &err)) {
            for (size_t c = 0; c < 9 * mesh.num_triangles; c += 3)
                cr_assert(mesh.corners[c] >= 0 && (size_t)mesh.corners[c] < mesh.num_positions);
            mesh_free(&mesh);
        } else {
            cr_assert(err.message[0], "round %d failed without a message", round);
        }
        free(copy);
    }
    free(original);
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
