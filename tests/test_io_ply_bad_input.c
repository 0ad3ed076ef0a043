// SPDX-License-Identifier: MIT
/* PLY import, bad input (host/io/ply_reader.c, ply_header.c, ply_faces.c): each bad header or
 * body gives its one-line error naming the file; absurd counts are refused before allocating;
 * randomly mutated binary files load or fail cleanly. */
#include <criterion/criterion.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/ply_reader.h"
#include "ply_fixtures.h"
#include "support.h"
#include "xorshift.h"


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