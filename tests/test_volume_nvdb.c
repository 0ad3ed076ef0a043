// SPDX-License-Identifier: MIT
/* NanoVDB grids (host/io/volume_nvdb.cc) from files NanoVDB's own builder writes
 * (tests/nvdb_fixture.cc): every voxel equals what NanoVDB's accessor returns (leaves and active
 * tiles), index_to_object matches the builder's voxel size and origin and a general affine map
 * (half a voxel and the box's minimum accounted for), grids are chosen by name; and hostile files
 * (patched headers, counts, offsets, truncations) fail with one line, never a crash. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "nvdb_fixture.h"
#include "support.h"
#include "volume_grid_check.h"

/* A single-grid file named "density": the grid's bytes start after the segment header (16), the
 * grid's metadata (176) and its name (8); its tree after the grid header (672). */
#define GRID_AT 200
#define TREE_AT (GRID_AT + 672)

/* Object point of our index point q = NanoVDB index ijk - lo + 0.5 (voxel ijk's centre). */
static void object_point(const VolumeGrid *g, const double q[3], double out[3])
{
    for (int row = 0; row < 3; row++)
        out[row] = g->index_to_object[4 * row] * q[0] + g->index_to_object[4 * row + 1] * q[1] +
                   g->index_to_object[4 * row + 2] * q[2] + g->index_to_object[4 * row + 3];
}

/* Reads grid `name` of path and checks it against NanoVDB's reference; returns the reference box
 * min in lo (the grid is freed). */
static void check_against_reference(const char *path, const char *name, const char *ask, int lo[3])
{
    NvdbReference ref;
    cr_assert(nvdb_fixture_reference(path, name, &ref));
    VolumeGrid grid;
    Error err = {0};
    cr_assert(volume_grid_read(path, ask, &grid, &err), "%s", err.message);
    uint32_t res[3];
    for (int a = 0; a < 3; a++) {
        res[a] = (uint32_t)(ref.hi[a] - ref.lo[a] + 1);
        lo[a] = ref.lo[a];
    }
    check_grid_equals_dense(&grid, ref.values, res);
    check_majorants(&grid, 3, 20);
    /* The box's corners and centre: our index point of voxel ijk lands where NanoVDB puts ijk. */
    for (int corner = 0; corner < 9; corner++) {
        double ijk[3], q[3], ours[3], theirs[3];
        for (int a = 0; a < 3; a++) {
            ijk[a] = corner == 8 ? (ref.lo[a] + ref.hi[a]) / 2 : (corner >> a & 1) ? ref.hi[a] : ref.lo[a];
            q[a] = ijk[a] - ref.lo[a] + 0.5;
        }
        object_point(&grid, q, ours);
        cr_assert(nvdb_fixture_index_to_world(path, name, ijk, theirs));
        for (int a = 0; a < 3; a++)
            cr_assert_float_eq(ours[a], theirs[a], 1e-9, "voxel (%g, %g, %g) axis %d: %g, NanoVDB %g",
                               ijk[0], ijk[1], ijk[2], a, ours[a], theirs[a]);
    }
    volume_grid_free(&grid);
    free(ref.values);
}

Test(volume_nvdb, fog_sphere_round_trip)
{
    const char *dir = test_temp_dir();
    char path[600];
    snprintf(path, sizeof path, "%s/sphere.nvdb", dir);
    const double center[3] = {1.0, -2.0, 3.5}, origin[3] = {0.3, -1.1, 2.0}, voxel = 0.25;
    cr_assert(nvdb_fixture_write_sphere(path, "density", 4.0f, center, voxel, origin));
    NvdbReference ref;
    cr_assert(nvdb_fixture_reference(path, "density", &ref));
    cr_assert_gt(ref.active_tiles[0], 0, "the sphere has no constant tiles: the tile path goes untested");
    free(ref.values);
    int lo[3];
    check_against_reference(path, "density", "density", lo);
    /* And against what the builder was told: index ijk at origin + voxel * ijk. */
    VolumeGrid grid;
    Error err = {0};
    cr_assert(volume_grid_read(path, "", &grid, &err), "%s", err.message);
    double q[3] = {0.5, 0.5, 0.5}, p[3];
    object_point(&grid, q, p);
    for (int a = 0; a < 3; a++) {
        cr_assert_float_eq(p[a], origin[a] + voxel * lo[a], 1e-9);
        cr_assert_float_eq(grid.index_to_object[5 * a], voxel, 1e-12);
    }
    cr_assert_float_eq(grid.max_value, 1.0f, 0.0f);
    volume_grid_free(&grid);
    unlink(path);
    rmdir(dir);
}

Test(volume_nvdb, general_affine_map_and_negative_coordinates)
{
    const char *dir = test_temp_dir();
    char path[600];
    snprintf(path, sizeof path, "%s/rotated.nvdb", dir);
    const double c = cos(0.5), s = sin(0.5);
    const double matrix[9] = {0.5 * c, -2.0 * s, 0.1, 0.5 * s, 2.0 * c, 0.0, 0.0, 0.3, 1.5};
    const int ijk[] = {-20, -3, 7, -19, -3, 7, 0, 0, 0, 13, 9, -30, 40, -41, 5};
    const float values[] = {0.5f, 2.0f, 1.0f, 4.0f, 0.0625f};
    cr_assert(nvdb_fixture_write_voxels(path, "density", 5, ijk, values, matrix, (const double[3]){1, 2, 3}));
    int lo[3];
    check_against_reference(path, "density", "", lo);
    cr_assert_eq(lo[0], -20);
    cr_assert_eq(lo[1], -41);
    cr_assert_eq(lo[2], -30);
    unlink(path);
    rmdir(dir);
}

static char last_message[1024];

Test(volume_nvdb, upper_node_tiles)
{
    const char *dir = test_temp_dir();
    char path[600];
    snprintf(path, sizeof path, "%s/box.nvdb", dir);
    cr_assert(nvdb_fixture_write_box(path, "density", (const int[3]){128, 0, -128},
                                     (const int[3]){255, 127, -1}, 0.75f, (const int[3]){259, 3, -2}));
    NvdbReference ref;
    cr_assert(nvdb_fixture_reference(path, "density", &ref));
    cr_assert_eq(ref.active_tiles[1], 1, "the box is not one upper-node tile (%u lower, %u upper)",
                 ref.active_tiles[0], ref.active_tiles[1]);
    free(ref.values);
    int lo[3];
    check_against_reference(path, "density", "", lo);

    /* Hostile: the lower node (the spot's) moved into the box and made all active tiles, which
     * overlap the upper node's tile: refused before the work of filling them twice. */
    char bad[600];
    snprintf(bad, sizeof bad, "%s/overlap.nvdb", dir);
    size_t length;
    unsigned char *data = (unsigned char *)test_read_file(path, &length);
    uint32_t lower_at;
    memcpy(&lower_at, data + TREE_AT + 8, 4);
    lower_at += TREE_AT;
    const int32_t inside[3] = {128, 0, -128};
    memcpy(data + lower_at, inside, sizeof inside);
    memset(data + lower_at + 32, 0xff, 512); /* value mask */
    memset(data + lower_at + 32 + 512, 0, 512); /* child mask */
    FILE *f = fopen(bad, "wb");
    fwrite(data, 1, length, f);
    fclose(f);
    free(data);
    VolumeGrid grid;
    Error err = {0};
    cr_assert_not(volume_grid_read(bad, "", &grid, &err));
    cr_assert(strstr(err.message, "its active tiles overlap"), "%s", err.message);
    unlink(bad);
    unlink(path);
    rmdir(dir);
}

static void expect_nvdb_error(const char *path, const char *grid_name, ErrorCode code, const char *needle)
{
    expect_grid_read_error(path, grid_name, code, needle, last_message, sizeof last_message);
}

Test(volume_nvdb, grids_by_name_and_type)
{
    const char *dir = test_temp_dir();
    char path[600];
    snprintf(path, sizeof path, "%s/mixed.nvdb", dir);
    cr_assert(nvdb_fixture_write_mixed(path));
    int lo[3];
    check_against_reference(path, "density", "", lo); /* "": the first float grid */
    check_against_reference(path, "flame", "flame", lo);
    expect_nvdb_error(path, "smoke", ERR_JSON_VALUE,
                      "no grid named 'smoke'; the file holds 'temperature' (double), 'density' (float), 'flame' (float)");
    expect_nvdb_error(path, "temperature", ERR_JSON_VALUE, "grid 'temperature' holds double values; a density grid must be float");
    unlink(path);
    rmdir(dir);
}

/* Copies the good file to path with `size` bytes of `bytes` written at offset (size 0: the file
 * cut at offset). */
static void patch(const char *good, const char *path, long offset, const void *bytes, size_t size)
{
    size_t length;
    char *data = test_read_file(good, &length);
    cr_assert(data);
    if (size == 0)
        length = (size_t)offset;
    else
        memcpy(data + offset, bytes, size);
    FILE *f = fopen(path, "wb");
    cr_assert(f);
    fwrite(data, 1, length, f);
    fclose(f);
    free(data);
}

static uint32_t read_u32(const char *file, long offset)
{
    size_t length;
    char *data = test_read_file(file, &length);
    uint32_t v;
    memcpy(&v, data + offset, 4);
    free(data);
    return v;
}

Test(volume_nvdb, hostile_files_fail_with_one_line)
{
    const char *dir = test_temp_dir();
    char good[600], bad[600];
    snprintf(good, sizeof good, "%s/good.nvdb", dir);
    snprintf(bad, sizeof bad, "%s/bad.nvdb", dir);
    const double zero[3] = {0, 0, 0};
    cr_assert(nvdb_fixture_write_sphere(good, "density", 3.0f, zero, 0.5, zero));
    const uint64_t swapped = 0x4e616e6f56444230ull; /* "NanoVDB0" read the other way round */
    const uint32_t old_version = 31u << 21, huge = 0xffffffffu, huge_aligned = 0xffffffe0u, one = 1, two = 2;
    const uint16_t zip = 1, blosc = 2;
    const int32_t wide_box[6] = {-(1 << 30), -(1 << 30), -(1 << 30), 1 << 30, 1 << 30, 1 << 30};
    const int32_t empty_box[6] = {5, 5, 5, 4, 4, 4};
    const double zeros[9] = {0};
    uint32_t root_at = TREE_AT + read_u32(good, TREE_AT + 24);
    uint32_t leaf_offset = read_u32(good, TREE_AT) - 24; /* inside the grid, misaligned */

    expect_nvdb_error(bad, "", ERR_FILE_MISSING, "no such file");
    patch(good, bad, 0, NULL, 0);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "empty file");
    patch(good, bad, 14, &zip, 2);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "compressed with ZIP; pt reads uncompressed NanoVDB files");
    patch(good, bad, 14, &blosc, 2);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "compressed with BLOSC");
    patch(good, bad, 0, "NanoVDB1", 8);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "not a NanoVDB file");
    patch(good, bad, 0, &swapped, 8);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "big-endian");
    patch(good, bad, 8, &old_version, 4);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "NanoVDB file format 31.0.0; pt reads version 32.x");
    patch(good, bad, 100, NULL, 0);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "truncated in the metadata of grid 0");
    patch(good, bad, 5000, NULL, 0);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "truncated: grid 'density' needs");
    patch(good, bad, 16 + 136, &huge, 4); /* the name's size */
    expect_nvdb_error(bad, "", ERR_FILE_READ, "name of 4294967295 bytes does not fit");
    patch(good, bad, 16 + 8, &huge, 4); /* size on disk != size */
    expect_nvdb_error(bad, "", ERR_FILE_READ, "bytes on disk for a grid of");
    patch(good, bad, GRID_AT, "NanoVDB1", 8);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "grid 'density': bad magic in its grid header");
    patch(good, bad, GRID_AT + 636, &two, 4); /* the grid header says double, the metadata float */
    expect_nvdb_error(bad, "", ERR_JSON_VALUE, "holds double values");
    patch(good, bad, GRID_AT + 32, &one, 4);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "its header says");
    patch(good, bad, GRID_AT + 296 + 88, zeros, sizeof zeros); /* the double 3x3 */
    expect_nvdb_error(bad, "", ERR_FILE_READ, "index-to-world map is singular");
    patch(good, bad, TREE_AT + 32, &huge, 4); /* leaf count */
    expect_nvdb_error(bad, "", ERR_FILE_READ, "4294967295 leaf nodes at tree offset");
    patch(good, bad, TREE_AT, &leaf_offset, 4);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "leaf nodes at tree offset");
    cr_expect(strstr(last_message, "not 32-byte aligned"), "%s", last_message);
    patch(good, bad, TREE_AT + 36, &huge, 4); /* lower node count */
    expect_nvdb_error(bad, "", ERR_FILE_READ, "lower internal nodes");
    patch(good, bad, TREE_AT + 24, &huge_aligned, 4); /* root offset */
    expect_nvdb_error(bad, "", ERR_FILE_READ, "root nodes at tree offset");
    patch(good, bad, root_at + 24, &huge, 4); /* root tile count */
    expect_nvdb_error(bad, "", ERR_FILE_READ, "the root's 4294967295 tiles do not fit");
    patch(good, bad, root_at, wide_box, sizeof wide_box);
    expect_nvdb_error(bad, "", ERR_TOO_LARGE, "over the limit of 2^31 voxels");
    patch(good, bad, root_at, empty_box, sizeof empty_box);
    expect_nvdb_error(bad, "", ERR_FILE_READ, "grid 'density' has no active voxels");

    /* Values: NaN and negative densities name the voxel (our index: ijk - the box's min). */
    const int ijk[] = {0, 0, 0, 5, 6, 7};
    const float negative[] = {1.0f, -2.0f}, nan_value[] = {NAN, 1.0f};
    cr_assert(nvdb_fixture_write_voxels(bad, "density", 2, ijk, negative, NULL, zero));
    expect_nvdb_error(bad, "", ERR_FILE_READ, "voxel (5, 6, 7) is -2");
    cr_assert(nvdb_fixture_write_voxels(bad, "density", 2, ijk, nan_value, NULL, zero));
    expect_nvdb_error(bad, "", ERR_FILE_READ, "voxel (0, 0, 0) is nan");
    unlink(good);
    unlink(bad);
    rmdir(dir);
}
