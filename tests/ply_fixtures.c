// SPDX-License-Identifier: MIT
/* ply_fixtures.c: the PLY tests' shared mesh, written as OBJ and as PLY ascii and binary of
 * either byte order, and their checks of loads and one-line errors (ply_fixtures.h). */
#include "ply_fixtures.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/ply_reader.h"
#include "support.h"
#define NV 10
/* Values exact in binary and decimal, so every writer gives the same floats. */
static const float P[NV][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},    {0, 1, 0},   {2, 0, 0},
                               {4, 0, 0}, {4, 2, 0}, {3, 0.5f, 0}, {2, 2, 0},   {0, 0, 1}};
static const int FACES[][5] = {{0, 1, 2, 3, -1}, {4, 5, 6, 7, 8}, {0, 1, 9, -1, -1}};
#define NF 3

static float normal(int v, int k) { return k == 2 ? 1.0f : 0.125f * (float)(v % 4) * (k ? -1 : 1); }
static float uv(int v, int k) { return k ? 0.25f * (float)(v % 4) : 0.0625f * (float)v; }
static int face_size(int f) { return FACES[f][3] < 0 ? 3 : FACES[f][4] < 0 ? 4 : 5; }

const char *write_obj(const char *dir)
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

const char *write_ascii(const char *dir)
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
const char *write_binary(const char *dir, bool big)
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

void load_ply_ok(const char *path, Mesh *mesh)
{
    Error err = {0};
    cr_assert(ply_load(path, mesh, &err), "%s: %s", path, err.message);
}

/* Loading must fail with this code and a message holding `mentions` (and the file's name). */
void expect_error_file(const char *path, ErrorCode code, const char *mentions)
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

void expect_error(const char *text, ErrorCode code, const char *mentions)
{
    expect_error_file(test_write_file(test_temp_dir(), "bad.ply", text), code, mentions);
}
