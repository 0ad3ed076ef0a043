/* SPDX-License-Identifier: MIT */
/* nvdb_fixture.h: NanoVDB files written with NanoVDB's own builder and writer (GridBuilder,
 * createFogVolumeSphere, io::writeGrids), and read back with its own reader and accessors as the
 * reference, for tests/test_volume_grid.c and the fuzz corpus's seeds. The reference trusts the
 * file: use it only on files these writers made. */
#ifndef PT_TEST_NVDB_FIXTURE_H
#define PT_TEST_NVDB_FIXTURE_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A fog-volume sphere (1 inside, a ramp to 0 over 3 voxels at the surface): radius and centre in
 * world units, grid index (i, j, k) at world origin + voxel_size * (i, j, k). Its inside is made
 * of NanoVDB's constant tiles. */
bool nvdb_fixture_write_sphere(const char *path, const char *name, float radius,
                               const double center[3], double voxel_size, const double origin[3]);
/* A float grid of `count` voxels ijk[3 * v] = values[v] (background 0), whose index-to-world map
 * is the 3x3 `matrix` (row-major: world = matrix * ijk + translation; NULL = identity). */
bool nvdb_fixture_write_voxels(const char *path, const char *name, int count, const int *ijk,
                               const float *values, const double *matrix, const double translation[3]);
/* A constant box [lo, hi] of `value` (filled with the builder's functor, which prunes constant
 * leaves and lower nodes into tiles: a 128^3 box aligned to 128 becomes one upper-node tile) and
 * one voxel `spot` = 3. */
bool nvdb_fixture_write_box(const char *path, const char *name, const int lo[3], const int hi[3],
                            float value, const int spot[3]);
/* Three grids: a double grid "temperature", a float sphere "density", a float grid "flame". */
bool nvdb_fixture_write_mixed(const char *path);

/* The file's grid `name`: its active index box [lo, hi] and, over it, the values NanoVDB's
 * accessor returns (x fastest, malloc'ed), with the count of active tiles. */
typedef struct {
    int lo[3], hi[3];
    float *values;
    uint32_t active_tiles[3]; /* in lower nodes, upper nodes, the root */
} NvdbReference;
bool nvdb_fixture_reference(const char *path, const char *name, NvdbReference *out);
/* The world point of NanoVDB index point ijk (its Grid::indexToWorld). */
bool nvdb_fixture_index_to_world(const char *path, const char *name, const double ijk[3],
                                 double world[3]);

#ifdef __cplusplus
}
#endif

#endif
