/* SPDX-License-Identifier: MIT */
/* volume_grid_check.h: what the grid tests (test_volume_grid.c, test_volume_nvdb.c) assert about a
 * VolumeGrid, computed independently of host/io/volume_grid.c: voxels read through the brick
 * table equal the dense values, absent bricks are exactly the all-zero ones, the padding past res
 * is zero, and each majorant bounds every trilinear lookup in its brick's box (the kernel's rule,
 * cl/medium/medium_grid.cl, re-implemented here) and equals the brute-force maximum of the brick's
 * voxels and their one-voxel neighbours (tight). Header-only, for Criterion tests. */
#ifndef PT_TEST_VOLUME_GRID_CHECK_H
#define PT_TEST_VOLUME_GRID_CHECK_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "base/shared_types.h"
#include "io/volume_grid.h"
#include "xorshift.h"

static inline float check_voxel(const VolumeGrid *g, int64_t x, int64_t y, int64_t z)
{
    x = x < 0 ? 0 : x >= g->res[0] ? g->res[0] - 1 : x; /* clamped to the edge, as the kernel */
    y = y < 0 ? 0 : y >= g->res[1] ? g->res[1] - 1 : y;
    z = z < 0 ? 0 : z >= g->res[2] ? g->res[2] - 1 : z;
    size_t cell = (size_t)(x / 8) + g->bricks[0] * ((size_t)(y / 8) + (size_t)g->bricks[1] * (size_t)(z / 8));
    uint32_t brick = g->brick_table[cell];
    if (brick == MEDIUM_NO_BRICK)
        return 0.0f;
    return g->values[(size_t)brick * MEDIUM_BRICK_VOXELS + (size_t)(x % 8 + 8 * (y % 8 + 8 * (z % 8)))];
}

/* The trilinear density at index point q (voxel centres at i + 0.5), as the kernel computes it. */
static inline double check_density(const VolumeGrid *g, const double q[3])
{
    double s[3], f[3];
    int64_t base[3];
    for (int a = 0; a < 3; a++) {
        s[a] = q[a] - 0.5;
        base[a] = (int64_t)floor(s[a]);
        f[a] = s[a] - (double)base[a];
    }
    double sum = 0.0;
    for (int corner = 0; corner < 8; corner++) {
        double w = 1.0;
        int64_t c[3];
        for (int a = 0; a < 3; a++) {
            int bit = corner >> a & 1;
            c[a] = base[a] + bit;
            w *= bit ? f[a] : 1.0 - f[a];
        }
        sum += w * check_voxel(g, c[0], c[1], c[2]);
    }
    return sum;
}

/* Every voxel equals dense[] (x fastest); a brick is absent exactly when all its voxels are 0;
 * padding voxels are 0; max_value is the largest voxel. */
static inline void check_grid_equals_dense(const VolumeGrid *g, const float *dense, const uint32_t res[3])
{
    float max_value = 0.0f;
    for (int a = 0; a < 3; a++) {
        cr_assert_eq(g->res[a], res[a]);
        cr_assert_eq(g->bricks[a], (res[a] + 7) / 8);
    }
    uint32_t present = 0;
    for (uint32_t bz = 0; bz < g->bricks[2]; bz++)
        for (uint32_t by = 0; by < g->bricks[1]; by++)
            for (uint32_t bx = 0; bx < g->bricks[0]; bx++) {
                uint32_t id = g->brick_table[bx + g->bricks[0] * (by + g->bricks[1] * bz)];
                bool any = false;
                for (uint32_t v = 0; v < MEDIUM_BRICK_VOXELS; v++) {
                    uint32_t x = bx * 8 + v % 8, y = by * 8 + v / 8 % 8, z = bz * 8 + v / 64;
                    bool inside = x < res[0] && y < res[1] && z < res[2];
                    float want = inside ? dense[x + (size_t)res[0] * (y + (size_t)res[1] * z)] : 0.0f;
                    any |= want != 0.0f;
                    max_value = want > max_value ? want : max_value;
                    float got = id == MEDIUM_NO_BRICK ? 0.0f : g->values[(size_t)id * 512 + v];
                    cr_assert_eq(got, want, "voxel (%u, %u, %u): %g, not %g", x, y, z, got, want);
                }
                cr_assert_eq(id != MEDIUM_NO_BRICK, any, "brick (%u, %u, %u) present: %d", bx, by, bz,
                             id != MEDIUM_NO_BRICK);
                if (id != MEDIUM_NO_BRICK) {
                    cr_assert_lt(id, g->num_bricks);
                    present++;
                }
            }
    cr_assert_eq(present, g->num_bricks, "%u bricks in the table, num_bricks %u", present, g->num_bricks);
    cr_assert_eq(g->max_value, max_value);
}

/* Each table entry's majorant: >= the density at random points of its box (its faces included)
 * and equal to the maximum over its voxels dilated by one (clamped to the grid). */
static inline void check_majorants(const VolumeGrid *g, uint64_t seed, int points_per_brick)
{
    uint64_t rng = seed | 1;
    for (uint32_t bz = 0; bz < g->bricks[2]; bz++)
        for (uint32_t by = 0; by < g->bricks[1]; by++)
            for (uint32_t bx = 0; bx < g->bricks[0]; bx++) {
                float majorant = g->majorants[bx + g->bricks[0] * (by + g->bricks[1] * bz)];
                uint32_t b[3] = {bx, by, bz};
                double lo[3], hi[3];
                for (int a = 0; a < 3; a++) {
                    lo[a] = 8.0 * b[a];
                    hi[a] = fmin(8.0 * b[a] + 8.0, (double)g->res[a]);
                }
                float dilated = 0.0f;
                for (int64_t z = 8 * (int64_t)bz - 1; z <= 8 * (int64_t)bz + 8; z++)
                    for (int64_t y = 8 * (int64_t)by - 1; y <= 8 * (int64_t)by + 8; y++)
                        for (int64_t x = 8 * (int64_t)bx - 1; x <= 8 * (int64_t)bx + 8; x++) {
                            float v = check_voxel(g, x, y, z);
                            dilated = v > dilated ? v : dilated;
                        }
                cr_assert_eq(majorant, dilated, "brick (%u, %u, %u): majorant %g, dilated maximum %g",
                             bx, by, bz, majorant, dilated);
                for (int p = 0; p < points_per_brick; p++) {
                    double q[3];
                    for (int a = 0; a < 3; a++) {
                        /* A quarter of the coordinates on the box's faces, where lookups reach
                         * furthest into the neighbours. */
                        uint32_t r = xorshift_next(&rng);
                        q[a] = r % 4 == 0 ? (r & 4 ? lo[a] : hi[a])
                                          : lo[a] + (hi[a] - lo[a]) * (r >> 8) / 16777216.0;
                    }
                    double density = check_density(g, q);
                    cr_assert_leq(density, majorant * (1.0 + 1e-6),
                                  "brick (%u, %u, %u): density %g at (%g, %g, %g) over majorant %g", bx,
                                  by, bz, density, q[0], q[1], q[2], majorant);
                }
            }
}

/* Reading grid `grid_name` of path must fail with `code` and one line that names the file and
 * holds `needle`; the message is copied to message[size] when message is not NULL. */
static inline void expect_grid_read_error(const char *path, const char *grid_name, ErrorCode code,
                                          const char *needle, char *message, size_t size)
{
    VolumeGrid grid;
    Error err = {0};
    bool ok = volume_grid_read(path, grid_name, &grid, &err);
    if (message)
        snprintf(message, size, "%s", err.message);
    if (ok)
        volume_grid_free(&grid);
    cr_expect_not(ok, "%s (grid '%s') was read; wanted \"%s\"", path, grid_name, needle);
    cr_expect_eq(err.code, code, "%s: %s (%s)", path, error_code_name(err.code), err.message);
    cr_expect(strstr(err.message, needle), "\"%s\" does not say \"%s\"", err.message, needle);
    cr_expect(strstr(err.message, path), "\"%s\" does not name the file", err.message);
    cr_expect_null(strchr(err.message, '\n'));
}

#endif
