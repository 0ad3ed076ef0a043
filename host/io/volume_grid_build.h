/* SPDX-License-Identifier: MIT */
/* volume_grid_build.h: how the grid readers (volume_vol.c, volume_nvdb.cc) fill a VolumeGrid
 * (volume_grid.h) without a dense copy of the whole grid: begin with the resolution (size limits
 * checked), write voxels brick by brick (a brick is allocated, zeroed, on its first write), then
 * finish (values checked, all-zero bricks dropped, majorants and max_value computed). Messages
 * name `path` ("" for in-memory grids). Internal to host/io. */
#ifndef PT_VOLUME_GRID_BUILD_H
#define PT_VOLUME_GRID_BUILD_H

#include <stddef.h>

#include "io/volume_grid.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The limits on one grid: voxels in its box, and memory for its bricks. */
#define VOLUME_GRID_MAX_VOXELS ((uint64_t)1 << 31)
#define VOLUME_GRID_MAX_BRICK_BYTES ((uint64_t)4 << 30)

typedef struct {
    VolumeGrid *grid;
    const char *path;
    uint32_t capacity; /* bricks allocated in grid->values */
} VolumeGridBuilder;

/* Zeroes *grid and allocates its brick table (every entry MEDIUM_NO_BRICK); index_to_object maps
 * [0, res] onto the unit cube. ERR_TOO_LARGE for an empty or too large box. */
bool volume_grid_begin(VolumeGridBuilder *b, VolumeGrid *grid, const uint32_t res[3],
                       const char *path, Error *err);
/* The values of brick (bx, by, bz) (MEDIUM_BRICK_VOXELS floats, x fastest), allocated zeroed on
 * first use; NULL with err set past the memory limit. Voxels past res must stay 0. */
float *volume_grid_brick(VolumeGridBuilder *b, uint32_t bx, uint32_t by, uint32_t bz, Error *err);
/* Checks every value (finite, >= 0: the first bad voxel is named), drops all-zero bricks and
 * computes majorants and max_value. On failure the grid is freed. */
bool volume_grid_finish(VolumeGridBuilder *b, Error *err);
/* Copies z-slices [z0, z0 + count) of dense values (res[0] * res[1] per slice, x fastest) into
 * the bricks; count <= MEDIUM_BRICK and z0 a multiple of it (one layer of bricks). Bricks whose
 * part is all zeros are not allocated. */
bool volume_grid_put_layer(VolumeGridBuilder *b, const float *slices, uint32_t z0, uint32_t count,
                           Error *err);

/* Voxel (x, y, z) (inside res) = value; and every voxel of the box [lo, hi) (clipped to res) =
 * value: NanoVDB's leaves and constant tiles. False with err set past the memory limit. */
bool volume_grid_set_voxel(VolumeGridBuilder *b, uint32_t x, uint32_t y, uint32_t z, float value,
                           Error *err);
bool volume_grid_fill_box(VolumeGridBuilder *b, const uint32_t lo[3], const uint32_t hi[3],
                          float value, Error *err);

/* The two file formats' readers, which volume_grid_read picks by extension. */
bool volume_vol_read(const char *path, const char *grid_name, VolumeGrid *out, Error *err);
bool volume_nvdb_read(const char *path, const char *grid_name, VolumeGrid *out, Error *err);

#ifdef __cplusplus
}
#endif

#endif
