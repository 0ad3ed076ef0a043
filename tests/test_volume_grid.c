// SPDX-License-Identifier: MIT
/* Volume grids (host/io/volume_grid.c, volume_vol.c): dense values to bricks and back, every voxel
 * equal; majorants that bound every trilinear lookup in their brick's box and are tight; Mitsuba 3
 * .vol files the test writes (layout, header box); and bad input, one line each: missing,
 * truncated, bad magic, version, encoding, channels, NaN or negative voxels, too large. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "support.h"
#include "volume_grid_check.h"
#include "xorshift.h"

/* Sparse smoke: a few soft blobs (exact zeros outside them, so some bricks are empty), and one
 * lone voxel in a corner. */
static float *make_smoke(const uint32_t res[3], uint64_t seed)
{
    size_t n = (size_t)res[0] * res[1] * res[2];
    float *v = calloc(n, sizeof(float));
    uint64_t rng = seed | 1;
    double centre[3][3], radius[3];
    for (int b = 0; b < 3; b++) {
        for (int a = 0; a < 3; a++)
            centre[b][a] = res[a] * (xorshift_next(&rng) / 4294967296.0);
        radius[b] = 1.5 + 4.0 * (xorshift_next(&rng) / 4294967296.0);
    }
    for (uint32_t z = 0; z < res[2]; z++)
        for (uint32_t y = 0; y < res[1]; y++)
            for (uint32_t x = 0; x < res[0]; x++) {
                double d = 0.0;
                for (int b = 0; b < 3; b++) {
                    double dx = x - centre[b][0], dy = y - centre[b][1], dz = z - centre[b][2];
                    double r = sqrt(dx * dx + dy * dy + dz * dz) / radius[b];
                    d += r < 1.0 ? (1.0 - r) * (1.0 + (xorshift_next(&rng) % 100) / 50.0) : 0.0;
                }
                v[x + (size_t)res[0] * (y + (size_t)res[1] * z)] = (float)d;
            }
    v[n - 1] = 7.5f; /* the far corner: a partial brick's last voxel */
    return v;
}

static const uint32_t RESOLUTIONS[][3] = {{1, 1, 1}, {8, 8, 8}, {13, 9, 17}, {40, 3, 9}, {30, 30, 30}};

Test(volume_grid, dense_round_trip)
{
    for (size_t r = 0; r < sizeof RESOLUTIONS / sizeof RESOLUTIONS[0]; r++) {
        float *dense = make_smoke(RESOLUTIONS[r], 17 + r);
        VolumeGrid grid;
        Error err = {0};
        cr_assert(volume_grid_from_dense(dense, RESOLUTIONS[r], &grid, &err), "%s", err.message);
        check_grid_equals_dense(&grid, dense, RESOLUTIONS[r]);
        /* The unit cube: index point res maps to (1, 1, 1), the origin to 0. */
        for (int row = 0; row < 3; row++)
            for (int c = 0; c < 4; c++)
                cr_assert_float_eq(grid.index_to_object[4 * row + c],
                                   row == c ? 1.0 / RESOLUTIONS[r][row] : 0.0, 1e-15);
        volume_grid_free(&grid);
        free(dense);
    }
}

Test(volume_grid, majorants_bound_trilinear_lookups_and_are_tight)
{
    for (size_t r = 0; r < sizeof RESOLUTIONS / sizeof RESOLUTIONS[0]; r++) {
        float *dense = make_smoke(RESOLUTIONS[r], 99 + r);
        VolumeGrid grid;
        Error err = {0};
        cr_assert(volume_grid_from_dense(dense, RESOLUTIONS[r], &grid, &err), "%s", err.message);
        check_majorants(&grid, 1234 + r, 400);
        volume_grid_free(&grid);
        free(dense);
    }
    /* One voxel at a brick's corner: all eight bricks around that corner see it, no other. */
    uint32_t res[3] = {24, 24, 24};
    float *dense = calloc(24 * 24 * 24, sizeof(float));
    dense[8 + 24 * (8 + 24 * 8)] = 3.0f;
    VolumeGrid grid;
    Error err = {0};
    cr_assert(volume_grid_from_dense(dense, res, &grid, &err), "%s", err.message);
    cr_assert_eq(grid.num_bricks, 1);
    for (uint32_t c = 0; c < 27; c++) {
        uint32_t bx = c % 3, by = c / 3 % 3, bz = c / 9;
        bool sees = bx <= 1 && by <= 1 && bz <= 1;
        cr_assert_eq(grid.majorants[c], sees ? 3.0f : 0.0f, "brick (%u, %u, %u)", bx, by, bz);
    }
    volume_grid_free(&grid);
    free(dense);
}

static void expect_dense_error(const float *values, uint32_t x, uint32_t y, uint32_t z,
                               ErrorCode code, const char *needle)
{
    VolumeGrid grid;
    Error err = {0};
    cr_assert_not(volume_grid_from_dense(values, (const uint32_t[3]){x, y, z}, &grid, &err),
                  "%u x %u x %u accepted", x, y, z);
    cr_expect_eq(err.code, code, "%s: %s", error_code_name(err.code), err.message);
    cr_expect(strstr(err.message, needle), "\"%s\" does not say \"%s\"", err.message, needle);
    cr_expect_null(strchr(err.message, '\n'));
}

Test(volume_grid, limits_and_bad_values)
{
    float one = 1.0f; /* never read past: the limits are checked first */
    expect_dense_error(&one, 0, 4, 4, ERR_FILE_READ, "empty (0 x 4 x 4");
    expect_dense_error(&one, 1u << 16, 1u << 16, 1, ERR_TOO_LARGE, "65536 x 65536 x 1 voxels");
    expect_dense_error(&one, 1, 1, 1u << 30, ERR_TOO_LARGE, "over the limit"); /* a 2^27-brick table */
    /* 9^3 bricks of ones (2.8 MiB) over a limit of 1 MiB. */
    float *ones = malloc(72 * 72 * 72 * sizeof(float));
    for (int i = 0; i < 72 * 72 * 72; i++)
        ones[i] = 1.0f;
    volume_grid_set_brick_limit(1 << 20);
    expect_dense_error(ones, 72, 72, 72, ERR_TOO_LARGE, "bricks need more than the limit of 1 MiB");
    volume_grid_set_brick_limit(0);
    VolumeGrid grid;
    Error err = {0};
    cr_assert(volume_grid_from_dense(ones, (const uint32_t[3]){72, 72, 72}, &grid, &err), "%s", err.message);
    cr_assert_eq(grid.num_bricks, 729);
    volume_grid_free(&grid);
    free(ones);
    float bad[5 * 6 * 7] = {0};
    const float cases[] = {NAN, -1.0f, INFINITY};
    const char *names[] = {"voxel (3, 4, 5) is nan", "voxel (3, 4, 5) is -1", "voxel (3, 4, 5) is inf"};
    for (int c = 0; c < 3; c++) {
        bad[3 + 5 * (4 + 6 * 5)] = cases[c];
        expect_dense_error(bad, 5, 6, 7, ERR_FILE_READ, names[c]);
    }
}

/* A .vol file: header fields as given, then `count` float32 values. */
static void write_vol(const char *path, const char *magic, int version, int32_t encoding,
                      const int32_t res[3], int32_t channels, const float bbox[6],
                      const float *values, size_t count)
{
    FILE *f = fopen(path, "wb");
    cr_assert(f);
    fwrite(magic, 1, 3, f);
    fputc(version, f);
    fwrite(&encoding, 4, 1, f); /* the test machine is little-endian, as the format */
    fwrite(res, 4, 3, f);
    fwrite(&channels, 4, 1, f);
    fwrite(bbox, 4, 6, f);
    if (count)
        fwrite(values, 4, count, f);
    fclose(f);
}

static const float BOX[6] = {-1.0f, 0.0f, 2.0f, 3.0f, 0.5f, 4.0f};

Test(volume_vol, round_trip_spans_the_header_box)
{
    const char *dir = test_temp_dir();
    char path[600];
    snprintf(path, sizeof path, "%s/smoke.vol", dir);
    uint32_t res[3] = {11, 7, 21};
    float *dense = make_smoke(res, 5);
    for (uint32_t i = 0; i < 11 * 7 * 21; i++) /* dense where x < 6, sparse smoke elsewhere */
        dense[i] += i % 11 < 6 ? 0.125f * (float)(i % 13) : 0.0f;
    write_vol(path, "VOL", 3, 1, (const int32_t[3]){11, 7, 21}, 1, BOX, dense, 11 * 7 * 21);
    for (int named = 0; named < 2; named++) {
        VolumeGrid grid;
        Error err = {0};
        cr_assert(volume_grid_read(path, named ? "density" : "", &grid, &err), "%s", err.message);
        check_grid_equals_dense(&grid, dense, res);
        check_majorants(&grid, 7, 50);
        /* [0, res] onto the header's box, axis by axis. */
        for (int row = 0; row < 3; row++) {
            const double *m = grid.index_to_object + 4 * row;
            cr_assert_float_eq(m[3], BOX[row], 1e-6);
            cr_assert_float_eq(m[row] * res[row] + m[3], BOX[row + 3], 1e-6);
            cr_assert_float_eq(m[(row + 1) % 3], 0.0, 0.0);
            cr_assert_float_eq(m[(row + 2) % 3], 0.0, 0.0);
        }
        volume_grid_free(&grid);
    }
    unlink(path);
    rmdir(dir);
    free(dense);
}

static void expect_read_error(const char *path, const char *grid_name, ErrorCode code, const char *needle)
{
    expect_grid_read_error(path, grid_name, code, needle, NULL, 0);
}

Test(volume_vol, bad_input_one_line_each)
{
    const char *dir = test_temp_dir();
    char path[600];
    snprintf(path, sizeof path, "%s/bad.vol", dir);
    const int32_t res[3] = {4, 5, 6};
    float values[4 * 5 * 6];
    for (int i = 0; i < 4 * 5 * 6; i++)
        values[i] = (float)(i % 7) * 0.25f;

    expect_read_error(path, "", ERR_FILE_MISSING, "no such file");
    write_vol(path, "VOL", 3, 1, res, 1, BOX, values, 0);
    expect_read_error(path, "", ERR_FILE_READ, "truncated: 4 x 5 x 6 voxels need 528 bytes, the file has 48");
    write_vol(path, "VOL", 3, 1, res, 1, BOX, values, 4 * 5 * 6 - 1);
    expect_read_error(path, "", ERR_FILE_READ, "truncated");
    FILE *f = fopen(path, "wb");
    fwrite("VOL\3", 1, 4, f);
    fclose(f);
    expect_read_error(path, "", ERR_FILE_READ, "shorter than a .vol header");
    write_vol(path, "VOX", 3, 1, res, 1, BOX, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, "not a Mitsuba .vol file");
    write_vol(path, "VOL", 2, 1, res, 1, BOX, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, ".vol version 2");
    write_vol(path, "VOL", 3, 2, res, 1, BOX, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, "encoding 2 (float16)");
    write_vol(path, "VOL", 3, 1, res, 3, BOX, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, "3 channels");
    write_vol(path, "VOL", 3, 1, (const int32_t[3]){4, -5, 6}, 1, BOX, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, "resolution 4 x -5 x 6");
    write_vol(path, "VOL", 3, 1, res, 1, (const float[6]){0, 0, 0, 1, 0, 1}, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, "bounding box [0, 0] along y");
    /* 2^42 voxels claimed in a 48-byte file: refused before any allocation. */
    write_vol(path, "VOL", 3, 1, (const int32_t[3]){1 << 20, 1 << 20, 4}, 1, BOX, values, 0);
    expect_read_error(path, "", ERR_TOO_LARGE, "1048576 x 1048576 x 4 voxels");
    values[1 + 4 * (2 + 5 * 3)] = NAN;
    write_vol(path, "VOL", 3, 1, res, 1, BOX, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, "voxel (1, 2, 3) is nan");
    values[1 + 4 * (2 + 5 * 3)] = -0.5f;
    write_vol(path, "VOL", 3, 1, res, 1, BOX, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, "voxel (1, 2, 3) is -0.5");
    values[1 + 4 * (2 + 5 * 3)] = 0.5f;
    write_vol(path, "VOL", 3, 1, res, 1, BOX, values, 120);
    expect_read_error(path, "temperature", ERR_JSON_VALUE, "no grid 'temperature'");
    unlink(path);

    snprintf(path, sizeof path, "%s/smoke.vdb", dir);
    write_vol(path, "VOL", 3, 1, res, 1, BOX, values, 120);
    expect_read_error(path, "", ERR_FILE_READ, "unknown grid file type '.vdb' (pt reads NanoVDB .nvdb and Mitsuba 3 .vol)");
    unlink(path);
    snprintf(path, sizeof path, "%s/folder.vol", dir);
    mkdir(path, 0700);
    expect_read_error(path, "", ERR_FILE_READ, "is a directory");
    rmdir(path);
    rmdir(dir);
}
