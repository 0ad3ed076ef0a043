// SPDX-License-Identifier: MIT
/* OBJ parsing (host/io/obj_loader.cc, host/io/obj_lines.c) on small files the tests write: each
 * kind of bad input gives its own error naming the file and the line, byte-mutated files load or
 * fail cleanly, and the accepted quirks (missing texcoords or normals, concave n-gons, forward
 * references, short faces) load as documented. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "io/obj_lines.h"
#include "io/obj_loader.h"
#include "support.h"

/* Loads quietly; fails the test with the error message if it does not load. */
static void load_ok(const char *path, Mesh *mesh)
{
    Error err = {0};
    warnings_set_quiet(true);
    cr_assert(obj_load(path, mesh, &err), "%s: %s", path, err.message);
}

/* Loading must fail with this code, naming the file and the line (0: no line to check). */
static void expect_error(const char *text, ErrorCode code, int line, const char *mentions)
{
    const char *dir = test_temp_dir();
    const char *path = test_write_file(dir, "bad.obj", text);
    Mesh mesh;
    Error err = {0};
    warnings_set_quiet(true);
    bool loaded = obj_load(path, &mesh, &err);
    cr_assert_not(loaded, "loaded:\n%s", text);
    cr_expect_eq(err.code, code, "%s instead of %s for:\n%s\nmessage: %s",
                 error_code_name(err.code), error_code_name(code), text, err.message);
    cr_expect(strstr(err.message, "bad.obj") != NULL, "message without file name: %s", err.message);
    if (line > 0) {
        char at_line[32];
        snprintf(at_line, sizeof at_line, ":%d:", line);
        cr_expect_eq(err.line, line, "line %d instead of %d: %s", err.line, line, err.message);
        cr_expect(strstr(err.message, at_line) != NULL, "message without %s: %s", at_line,
                  err.message);
    }
    if (mentions)
        cr_expect(strstr(err.message, mentions) != NULL, "message without '%s': %s", mentions,
                  err.message);
    cr_expect(strchr(err.message, '\n') == NULL, "message is not one line: %s", err.message);
    cr_expect_null(mesh.corners);
    remove(path);
    rmdir(dir);
}

#define TRIANGLE_V "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

Test(obj_errors, missing_file)
{
    Mesh mesh;
    Error err = {0};
    cr_assert_not(obj_load("/nonexistent/folder/bad.obj", &mesh, &err));
    cr_expect_eq(err.code, ERR_FILE_MISSING);
    cr_expect(strstr(err.message, "/nonexistent/folder/bad.obj: no such file") != NULL, "%s",
              err.message);
}

Test(obj_errors, face_index_out_of_range)
{
    expect_error("# three vertices\n" TRIANGLE_V "f 1 2 99\n", ERR_OBJ_INDEX, 5, "99");
    expect_error(TRIANGLE_V "f 1 2 3\nf 0 1 2\n", ERR_OBJ_INDEX, 5, "index 0");
    expect_error(TRIANGLE_V "f -1 -2 -4\n", ERR_OBJ_INDEX, 4, "-4");
    expect_error("f -1 -2 -3\n" TRIANGLE_V, ERR_OBJ_INDEX, 1, "-1");
    expect_error(TRIANGLE_V "vt 0 0\nf 1/1 2/5 3/1\n", ERR_OBJ_INDEX, 5, "texcoord index 5");
    expect_error(TRIANGLE_V "vt 0 0\nf 1/1 2/-2 3/1\n", ERR_OBJ_INDEX, 5, "-2");
    expect_error(TRIANGLE_V "vn 0 0 1\nf 1//1 2//1 3//2\n", ERR_OBJ_INDEX, 5, "normal index 2");
    expect_error(TRIANGLE_V "vn 0 0 1\nf 1/1/1 2/1/1 3/1/1\n", ERR_OBJ_INDEX, 5, "texcoord");
}

Test(obj_errors, line_numbers_count_crlf_and_cr_line_ends)
{
    expect_error("v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\n\r\nf 1 2 7\r\n", ERR_OBJ_INDEX, 5, "7");
    expect_error("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\rf 1 2 8\r", ERR_OBJ_INDEX, 5, "8");
}

Test(obj_errors, non_finite_vertices)
{
    expect_error(TRIANGLE_V "v nan 0 0\nf 1 2 3\n", ERR_OBJ_NONFINITE, 4, "nan");
    expect_error("v 0 0 0\nv inf 0 0\n", ERR_OBJ_NONFINITE, 2, "inf");
    expect_error("v 0 -Infinity 0\n", ERR_OBJ_NONFINITE, 1, NULL);
    expect_error(TRIANGLE_V "v 1e99 0 0\n", ERR_OBJ_NONFINITE, 4, "1e99");
    expect_error(TRIANGLE_V "vn 0 0 NaN\n", ERR_OBJ_NONFINITE, 4, NULL);
    expect_error(TRIANGLE_V "vt 0.5 1e40\n", ERR_OBJ_NONFINITE, 4, NULL);
}

Test(obj_errors, malformed_records)
{
    expect_error(TRIANGLE_V "v abc 0 0\n", ERR_OBJ_PARSE, 4, "abc");
    expect_error("v 0 0\n", ERR_OBJ_PARSE, 1, NULL);
    expect_error(TRIANGLE_V "f 1 2 x\n", ERR_OBJ_PARSE, 4, "'x'");
    expect_error(TRIANGLE_V "f 1/ 2/ 3/\n", ERR_OBJ_PARSE, 4, NULL);
    /* tinyobjloader itself rejects a line record with index 0; the message keeps its line. */
    expect_error(TRIANGLE_V "\nl 0 1\n", ERR_OBJ_PARSE, 5, NULL);
}

Test(obj_errors, face_with_too_many_corners)
{
    static char text[32768];
    size_t used = 0;
    for (int i = 0; i < 300; i++)
        used += (size_t)snprintf(text + used, sizeof text - used, "v %d %d 0\n", i % 17, i / 17);
    used += (size_t)snprintf(text + used, sizeof text - used, "f");
    for (int i = 1; i <= 300; i++)
        used += (size_t)snprintf(text + used, sizeof text - used, " %d", i);
    snprintf(text + used, sizeof text - used, "\n");
    expect_error(text, ERR_TOO_LARGE, 301, "300");
}

/* ---- accepted quirks and details ---------------------------------------------------------- */

static void load_text(const char *text, Mesh *mesh, const char **path_out)
{
    const char *dir = test_temp_dir();
    const char *path = test_write_file(dir, "ok.obj", text);
    if (path_out)
        *path_out = path;
    load_ok(path, mesh);
    remove(path);
    rmdir(dir);
}

Test(obj_details, corners_carry_position_texcoord_normal_or_minus_one)
{
    Mesh mesh;
    load_text(TRIANGLE_V "vt 0 0\nvt 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 3/2 2/1 1/2\nf -3 -2 -1\n",
              &mesh, NULL);
    cr_assert_eq(mesh.num_triangles, 3);
    const int32_t expected[3][9] = {{0, -1, 0, 1, -1, 0, 2, -1, 0},
                                    {2, 1, -1, 1, 0, -1, 0, 1, -1},
                                    {0, -1, -1, 1, -1, -1, 2, -1, -1}};
    for (int t = 0; t < 3; t++)
        for (int k = 0; k < 9; k++)
            cr_expect_eq(mesh.corners[9 * t + k], expected[t][k], "triangle %d value %d", t, k);
    mesh_free(&mesh);
}

Test(obj_details, concave_ngon_face_is_ear_clipped)
{
    /* An L-shaped hexagon, reflex corner last: a fan from corner 0 would flip a triangle. */
    Mesh mesh;
    load_text("v 0 3 0\nv 0 0 0\nv 3 0 0\nv 3 1 0\nv 1 1 0\nv 1 3 0\nf 1 2 3 4 5 6\n", &mesh, NULL);
    cr_assert_eq(mesh.num_faces, 1);
    cr_assert_eq(mesh.num_triangles, 4);
    double total = 0;
    for (size_t t = 0; t < 4; t++) {
        const int32_t *c = mesh.corners + 9 * t;
        const float *a = mesh.positions + 3 * c[0], *b = mesh.positions + 3 * c[3],
                    *d = mesh.positions + 3 * c[6];
        double z = ((double)b[0] - a[0]) * ((double)d[1] - a[1]) -
                   ((double)b[1] - a[1]) * ((double)d[0] - a[0]);
        cr_expect_gt(z, 0, "triangle %zu is flipped or degenerate", t);
        total += z / 2;
    }
    cr_expect_float_eq(total, 5.0, 1e-6, "L-shape area 5, got %g", total);
    mesh_free(&mesh);
}

Test(obj_details, positive_indices_may_refer_forward)
{
    /* tinyobjloader resolves positive indices after the whole file is read. */
    Mesh mesh;
    load_text("f 1 2 3\n" TRIANGLE_V, &mesh, NULL);
    cr_expect_eq(mesh.num_triangles, 1);
    mesh_free(&mesh);
}

Test(obj_details, short_face_is_skipped_with_a_warning)
{
    int before = warning_count();
    Mesh mesh;
    load_text(TRIANGLE_V "f 1 2\nf 1 2 3\n", &mesh, NULL);
    cr_expect_gt(warning_count(), before);
    cr_expect_eq(mesh.num_faces, 1);
    cr_expect_eq(mesh.num_triangles, 1);
    mesh_free(&mesh);
}

Test(obj_lines, find_record_counts_like_tinyobjloader)
{
    const char text[] =
        "# c\nv 0 0 0\n  v 1 0 0\r\nvt 0 0\rv 2 0 0\nf 1 2\nf 1 2 3\nvn 0 0 1\n\tf 3 2 1\n";
    size_t size = sizeof text - 1;
    cr_expect_eq(obj_lines_find_record(text, size, "v", 0), 2);
    cr_expect_eq(obj_lines_find_record(text, size, "v", 1), 3);
    cr_expect_eq(obj_lines_find_record(text, size, "v", 2), 5);
    cr_expect_eq(obj_lines_find_record(text, size, "v", 3), 0);
    cr_expect_eq(obj_lines_find_record(text, size, "vt", 0), 4);
    cr_expect_eq(obj_lines_find_record(text, size, "vn", 0), 8);
    cr_expect_eq(obj_lines_find_record(text, size, "f", 0), 7, "the 2-corner face is not counted");
    cr_expect_eq(obj_lines_find_record(text, size, "f", 1), 9);
}

/* Never crash: byte-mutated copies of a small OBJ either load with every index in range and every
 * position finite, or fail with a one-line message naming the file. */
Test(obj_errors, mutated_files_load_or_fail_cleanly)
{
    static const char original[] = "mtllib none.mtl\n# box\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                   "vt 0 0\nvt 1 0\nvn 0 0 1\nusemtl a\nf 1/1/1 2/2/1 3/1/1 4/2/1\n"
                                   "f -4 -3 -2\nf 1//1 3//1 4//1\n";
    static const char alphabet[] = "0123456789 -+/.\n\r\tvfenai#e";
    const char *dir = test_temp_dir();
    uint32_t state = 7;
    warnings_set_quiet(true);
    for (int trial = 0; trial < 400; trial++) {
        char text[sizeof original];
        memcpy(text, original, sizeof original);
        for (int m = 0; m < 1 + trial % 4; m++) {
            state = state * 1664525u + 1013904223u;
            size_t at = (state >> 8) % (sizeof original - 1);
            state = state * 1664525u + 1013904223u;
            text[at] = alphabet[(state >> 8) % (sizeof alphabet - 1)];
        }
        const char *path = test_write_file(dir, "mutant.obj", text);
        Mesh mesh;
        Error err = {0};
        if (!obj_load(path, &mesh, &err)) {
            cr_expect_neq(err.code, ERR_NONE);
            cr_expect(strstr(err.message, "mutant.obj") && !strchr(err.message, '\n'),
                      "trial %d: %s", trial, err.message);
            continue;
        }
        for (size_t i = 0; i < 3 * mesh.num_positions; i++)
            cr_assert(isfinite(mesh.positions[i]), "trial %d:\n%s", trial, text);
        for (size_t t = 0; t < mesh.num_triangles; t++)
            for (int k = 0; k < 3; k++) {
                const int32_t *c = mesh.corners + 9 * t + 3 * k;
                cr_assert(c[0] >= 0 && (size_t)c[0] < mesh.num_positions, "trial %d", trial);
                cr_assert(c[1] >= -1 && c[1] < (int32_t)mesh.num_texcoords, "trial %d", trial);
                cr_assert(c[2] >= -1 && c[2] < (int32_t)mesh.num_normals, "trial %d", trial);
            }
        mesh_free(&mesh);
    }
    remove(test_write_file(dir, "mutant.obj", ""));
    rmdir(dir);
}
