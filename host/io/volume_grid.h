/* SPDX-License-Identifier: MIT */
/* volume_grid.h: scalar voxel grids for grid media (shared/DESIGN.md "Media"), read from NanoVDB
 * (.nvdb) and Mitsuba (.vol) files into the bricked layout the kernels sample (shared/medium.h):
 * bricks of MEDIUM_BRICK^3 voxels, x fastest, found through a brick table (x fastest) whose entry
 * is a brick number or MEDIUM_NO_BRICK (all zeros), and one majorant per table entry. */
#ifndef PT_VOLUME_GRID_H
#define PT_VOLUME_GRID_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"

typedef struct {
    uint32_t res[3];         /* voxels per axis */
    uint32_t bricks[3];      /* brick table size: ceil(res / MEDIUM_BRICK) */
    uint32_t *brick_table;   /* bricks[0] * bricks[1] * bricks[2] entries */
    float *values;           /* num_bricks * MEDIUM_BRICK_VOXELS values (NULL when none) */
    uint32_t num_bricks;
    /* One per table entry: the largest value a trilinear lookup anywhere in that brick's index box
     * can return (the brick's voxels and their one-voxel neighbours), so that it bounds the density
     * for the majorant walk. */
    float *majorants;
    float max_value;         /* the largest voxel value */
    /* Index space to the file's object space: object = M (index point), rows of a 3x4 affine,
     * where voxel (i, j, k)'s value sits at index point (i + 0.5, j + 0.5, k + 0.5) and the grid
     * spans [0, res]. A .vol grid spans the bounding box in its header (shared/DESIGN.md
     * "Media": Mitsuba 3's gridvolume with use_grid_bbox); a NanoVDB grid spans its active
     * voxels' index box, placed by its index-to-world map (voxel ijk's value at map(ijk), as
     * NanoVDB's samplers have it); volume_grid_from_dense's grid spans the unit cube. */
    double index_to_object[12];
} VolumeGrid;

/* Reads grid `grid_name` (NanoVDB: the grid's name, "" = the first float grid; .vol: must be "" or
 * "density") of the file at path, chosen by its extension (.nvdb, .vol). Values must be finite and
 * >= 0 (a density). Errors: one line naming the file and what is wrong (ERR_FILE_MISSING,
 * ERR_FILE_READ for a corrupt or truncated file, ERR_JSON_VALUE for a grid name not in the file
 * (naming the grids that are) or of another value type, ERR_TOO_LARGE past the size limits: 2^31
 * voxels in the grid's box, 2^26 entries in its brick table, the brick memory limit below, and
 * 8 GiB for a NanoVDB grid's buffer). */
bool volume_grid_read(const char *path, const char *grid_name, VolumeGrid *out, Error *err);

/* The grid of dense values (res[0] * res[1] * res[2], x fastest), spanning the unit cube: for
 * tests and callers with values in memory (the readers stream into the same builder,
 * io/volume_grid_build.h). Errors as volume_grid_read's, naming "volume grid". */
bool volume_grid_from_dense(const float *values, const uint32_t res[3], VolumeGrid *out,
                            Error *err);

void volume_grid_free(VolumeGrid *grid);

/* The bounding box a Mitsuba .vol file's header gives its grid (xmin, ymin, zmin, xmax, ymax,
 * zmax), the header checked as volume_grid_read checks it; the values are not read. */
bool volume_vol_box(const char *path, double box[6], Error *err);

/* The memory one grid's non-zero bricks may take (ERR_TOO_LARGE past it): 4 GiB unless set. A
 * small file can describe a large constant box (a NanoVDB tile); the fuzz targets set less, to
 * stay inside libFuzzer's memory limit. 0 restores the default. */
void volume_grid_set_brick_limit(uint64_t bytes);

#endif
