/* SPDX-License-Identifier: MIT */
/* volume_grid.c: the bricked grid (volume_grid.h) and its builder (volume_grid_build.h), shared by
 * the .vol and .nvdb readers. Bricks are allocated on first write, so a sparse NanoVDB grid never
 * exists densely in memory; finishing checks the values, drops the bricks that stayed all zero and
 * computes each table entry's majorant from its brick and the facing voxels of its 26 neighbours
 * (a trilinear lookup in the brick's box reads one voxel past it on every side). */
#include "io/volume_grid.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"
#include "base/shared_types.h"
#include "io/volume_grid_build.h"

/* The brick table's limit (entries; the majorants take as much again): a thin grid (1 x 1 x 2^31)
 * is within the voxel limit but would need a table of 2^28 entries. */
#define VOLUME_GRID_MAX_TABLE ((uint64_t)1 << 26)

static const char *grid_name(const VolumeGridBuilder *b)
{
    return b->path[0] ? b->path : "volume grid";
}

static size_t table_cell(const VolumeGrid *g, uint32_t bx, uint32_t by, uint32_t bz)
{
    return bx + (size_t)g->bricks[0] * (by + (size_t)g->bricks[1] * bz);
}

static size_t table_size(const VolumeGrid *g)
{
    return (size_t)g->bricks[0] * g->bricks[1] * g->bricks[2];
}

static uint32_t voxel_in_brick(uint32_t x, uint32_t y, uint32_t z)
{
    return (x % MEDIUM_BRICK) + MEDIUM_BRICK * ((y % MEDIUM_BRICK) + MEDIUM_BRICK * (z % MEDIUM_BRICK));
}

bool volume_grid_begin(VolumeGridBuilder *b, VolumeGrid *grid, const uint32_t res[3],
                       const char *path, Error *err)
{
    memset(grid, 0, sizeof *grid);
    *b = (VolumeGridBuilder){.grid = grid, .path = path ? path : "", .capacity = 0};
    uint64_t voxels = 1, entries = 1;
    for (int a = 0; a < 3; a++) {
        voxels *= res[a]; /* at most 2^31 * 2^32 before the check below: no overflow */
        if (voxels > VOLUME_GRID_MAX_VOXELS)
            break;
        grid->res[a] = res[a];
        grid->bricks[a] = (res[a] + MEDIUM_BRICK - 1) / MEDIUM_BRICK;
        entries *= grid->bricks[a];
    }
    if (voxels == 0) {
        error_set(err, ERR_FILE_READ, b->path, 0, "%s: the grid is empty (%u x %u x %u voxels)",
                  grid_name(b), res[0], res[1], res[2]);
        return false;
    }
    if (voxels > VOLUME_GRID_MAX_VOXELS || entries > VOLUME_GRID_MAX_TABLE) {
        error_set(err, ERR_TOO_LARGE, b->path, 0,
                  "%s: a grid of %u x %u x %u voxels is over the limit of 2^31 voxels (and 2^26 "
                  "bricks of 8^3)", grid_name(b), res[0], res[1], res[2]);
        return false;
    }
    grid->brick_table = malloc(entries * sizeof(uint32_t));
    if (!grid->brick_table) {
        error_set(err, ERR_OUT_OF_MEMORY, b->path, 0, "%s: out of memory for the brick table",
                  grid_name(b));
        return false;
    }
    memset(grid->brick_table, 0xff, entries * sizeof(uint32_t)); /* MEDIUM_NO_BRICK */
    for (int a = 0; a < 3; a++)
        grid->index_to_object[5 * a] = 1.0 / res[a]; /* [0, res] onto the unit cube */
    return true;
}

float *volume_grid_brick(VolumeGridBuilder *b, uint32_t bx, uint32_t by, uint32_t bz, Error *err)
{
    VolumeGrid *g = b->grid;
    uint32_t *entry = &g->brick_table[table_cell(g, bx, by, bz)];
    if (*entry == MEDIUM_NO_BRICK) {
        const uint64_t limit = VOLUME_GRID_MAX_BRICK_BYTES / (MEDIUM_BRICK_VOXELS * sizeof(float));
        if (g->num_bricks == b->capacity) {
            if (b->capacity >= limit) {
                error_set(err, ERR_TOO_LARGE, b->path, 0,
                          "%s: the grid's non-zero bricks need more than the limit of %llu GiB",
                          grid_name(b), (unsigned long long)(VOLUME_GRID_MAX_BRICK_BYTES >> 30));
                return NULL;
            }
            uint64_t grown = b->capacity ? 2 * (uint64_t)b->capacity : 64;
            grown = grown < limit ? grown : limit;
            float *values = realloc(g->values, grown * MEDIUM_BRICK_VOXELS * sizeof(float));
            if (!values) {
                error_set(err, ERR_OUT_OF_MEMORY, b->path, 0, "%s: out of memory for %llu bricks",
                          grid_name(b), (unsigned long long)grown);
                return NULL;
            }
            g->values = values;
            b->capacity = (uint32_t)grown;
        }
        *entry = g->num_bricks++;
        memset(g->values + (size_t)*entry * MEDIUM_BRICK_VOXELS, 0,
               MEDIUM_BRICK_VOXELS * sizeof(float));
    }
    return g->values + (size_t)*entry * MEDIUM_BRICK_VOXELS;
}

bool volume_grid_set_voxel(VolumeGridBuilder *b, uint32_t x, uint32_t y, uint32_t z, float value,
                           Error *err)
{
    const VolumeGrid *g = b->grid;
    uint32_t bx = x / MEDIUM_BRICK, by = y / MEDIUM_BRICK, bz = z / MEDIUM_BRICK;
    if (value == 0.0f && g->brick_table[table_cell(g, bx, by, bz)] == MEDIUM_NO_BRICK)
        return true; /* stays an absent brick of zeros */
    float *brick = volume_grid_brick(b, bx, by, bz, err);
    if (!brick)
        return false;
    brick[voxel_in_brick(x, y, z)] = value;
    return true;
}

bool volume_grid_fill_box(VolumeGridBuilder *b, const uint32_t lo[3], const uint32_t hi[3],
                          float value, Error *err)
{
    const VolumeGrid *g = b->grid;
    uint32_t end[3];
    for (int a = 0; a < 3; a++) {
        end[a] = hi[a] < g->res[a] ? hi[a] : g->res[a];
        if (lo[a] >= end[a])
            return true;
    }
    for (uint32_t bz = lo[2] / MEDIUM_BRICK; bz <= (end[2] - 1) / MEDIUM_BRICK; bz++)
        for (uint32_t by = lo[1] / MEDIUM_BRICK; by <= (end[1] - 1) / MEDIUM_BRICK; by++)
            for (uint32_t bx = lo[0] / MEDIUM_BRICK; bx <= (end[0] - 1) / MEDIUM_BRICK; bx++) {
                if (value == 0.0f && g->brick_table[table_cell(g, bx, by, bz)] == MEDIUM_NO_BRICK)
                    continue;
                float *brick = volume_grid_brick(b, bx, by, bz, err);
                if (!brick)
                    return false;
                /* The part of this brick inside the box. */
                uint32_t from[3] = {bx * MEDIUM_BRICK, by * MEDIUM_BRICK, bz * MEDIUM_BRICK};
                uint32_t to[3];
                for (int a = 0; a < 3; a++) {
                    to[a] = from[a] + MEDIUM_BRICK < end[a] ? from[a] + MEDIUM_BRICK : end[a];
                    from[a] = from[a] > lo[a] ? from[a] : lo[a];
                }
                for (uint32_t z = from[2]; z < to[2]; z++)
                    for (uint32_t y = from[1]; y < to[1]; y++)
                        for (uint32_t x = from[0]; x < to[0]; x++)
                            brick[voxel_in_brick(x, y, z)] = value;
            }
    return true;
}

bool volume_grid_put_layer(VolumeGridBuilder *b, const float *slices, uint32_t z0, uint32_t count,
                           Error *err)
{
    const VolumeGrid *g = b->grid;
    const size_t row = g->res[0], slice = (size_t)g->res[0] * g->res[1];
    for (uint32_t by = 0; by < g->bricks[1]; by++)
        for (uint32_t bx = 0; bx < g->bricks[0]; bx++) {
            uint32_t x0 = bx * MEDIUM_BRICK, y0 = by * MEDIUM_BRICK;
            uint32_t nx = g->res[0] - x0 < MEDIUM_BRICK ? g->res[0] - x0 : MEDIUM_BRICK;
            uint32_t ny = g->res[1] - y0 < MEDIUM_BRICK ? g->res[1] - y0 : MEDIUM_BRICK;
            /* Bitwise "not all zero": NaN and negative values make a brick too (finish names them). */
            bool any = false;
            for (uint32_t z = 0; z < count && !any; z++)
                for (uint32_t y = 0; y < ny && !any; y++)
                    for (uint32_t x = 0; x < nx && !any; x++)
                        any = slices[z * slice + (y0 + y) * row + x0 + x] != 0.0f;
            if (!any)
                continue;
            float *brick = volume_grid_brick(b, bx, by, z0 / MEDIUM_BRICK, err);
            if (!brick)
                return false;
            for (uint32_t z = 0; z < count; z++)
                for (uint32_t y = 0; y < ny; y++)
                    memcpy(brick + MEDIUM_BRICK * (y + MEDIUM_BRICK * z),
                           slices + z * slice + (y0 + y) * row + x0, nx * sizeof(float));
        }
    return true;
}

/* The first voxel (in table order, then x fastest in its brick) that is not a density. */
static bool check_values(const VolumeGridBuilder *b, Error *err)
{
    const VolumeGrid *g = b->grid;
    for (uint32_t bz = 0; bz < g->bricks[2]; bz++)
        for (uint32_t by = 0; by < g->bricks[1]; by++)
            for (uint32_t bx = 0; bx < g->bricks[0]; bx++) {
                uint32_t id = g->brick_table[table_cell(g, bx, by, bz)];
                if (id == MEDIUM_NO_BRICK)
                    continue;
                const float *brick = g->values + (size_t)id * MEDIUM_BRICK_VOXELS;
                for (uint32_t v = 0; v < MEDIUM_BRICK_VOXELS; v++) {
                    float value = brick[v];
                    if (value >= 0.0f && isfinite(value))
                        continue;
                    uint32_t x = bx * MEDIUM_BRICK + v % MEDIUM_BRICK;
                    uint32_t y = by * MEDIUM_BRICK + v / MEDIUM_BRICK % MEDIUM_BRICK;
                    uint32_t z = bz * MEDIUM_BRICK + v / (MEDIUM_BRICK * MEDIUM_BRICK);
                    error_set(err, ERR_FILE_READ, b->path, 0,
                              "%s: voxel (%u, %u, %u) is %g: a density must be finite and >= 0",
                              grid_name(b), x, y, z, (double)value);
                    return false;
                }
            }
    return true;
}

static float brick_max(const float *brick)
{
    float m = 0.0f;
    for (uint32_t v = 0; v < MEDIUM_BRICK_VOXELS; v++)
        m = brick[v] > m ? brick[v] : m;
    return m;
}

/* Drops the bricks that are all zeros (a cleared voxel, a zero tile) and packs the others in the
 * order they were made; fills brick_maxima[] (one per kept brick). */
static void drop_zero_bricks(VolumeGrid *g, float *brick_maxima)
{
    uint32_t *renumber = malloc((g->num_bricks ? g->num_bricks : 1) * sizeof(uint32_t));
    uint32_t kept = 0;
    for (uint32_t id = 0; id < g->num_bricks && renumber; id++) {
        const float *brick = g->values + (size_t)id * MEDIUM_BRICK_VOXELS;
        float m = brick_max(brick);
        renumber[id] = m > 0.0f ? kept : MEDIUM_NO_BRICK;
        if (m > 0.0f) {
            memmove(g->values + (size_t)kept * MEDIUM_BRICK_VOXELS, brick,
                    MEDIUM_BRICK_VOXELS * sizeof(float));
            brick_maxima[kept++] = m;
        }
    }
    if (!renumber) { /* keep them all: correct, only larger */
        for (uint32_t id = 0; id < g->num_bricks; id++)
            brick_maxima[id] = brick_max(g->values + (size_t)id * MEDIUM_BRICK_VOXELS);
        return;
    }
    for (size_t c = 0; c < table_size(g); c++)
        if (g->brick_table[c] != MEDIUM_NO_BRICK)
            g->brick_table[c] = renumber[g->brick_table[c]];
    g->num_bricks = kept;
    free(renumber);
}

/* The largest voxel of neighbour brick `brick` that faces the cell it is offset (dx, dy, dz) from:
 * its last layer along an axis where it lies below (-1), its first where above (+1). */
static float facing_max(const float *brick, const int d[3])
{
    uint32_t from[3], to[3];
    for (int a = 0; a < 3; a++) {
        from[a] = d[a] < 0 ? MEDIUM_BRICK - 1 : 0;
        to[a] = d[a] > 0 ? 1 : MEDIUM_BRICK;
    }
    float m = 0.0f;
    for (uint32_t z = from[2]; z < to[2]; z++)
        for (uint32_t y = from[1]; y < to[1]; y++)
            for (uint32_t x = from[0]; x < to[0]; x++) {
                float v = brick[x + MEDIUM_BRICK * (y + MEDIUM_BRICK * z)];
                m = v > m ? v : m;
            }
    return m;
}

static float cell_majorant(const VolumeGrid *g, const float *brick_maxima, uint32_t bx,
                           uint32_t by, uint32_t bz)
{
    float m = 0.0f;
    for (int dz = -1; dz <= 1; dz++)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int64_t nx = (int64_t)bx + dx, ny = (int64_t)by + dy, nz = (int64_t)bz + dz;
                if (nx < 0 || ny < 0 || nz < 0 || nx >= g->bricks[0] || ny >= g->bricks[1] ||
                    nz >= g->bricks[2])
                    continue;
                uint32_t id = g->brick_table[table_cell(g, (uint32_t)nx, (uint32_t)ny, (uint32_t)nz)];
                if (id == MEDIUM_NO_BRICK)
                    continue;
                float v = dx == 0 && dy == 0 && dz == 0
                              ? brick_maxima[id]
                              : facing_max(g->values + (size_t)id * MEDIUM_BRICK_VOXELS,
                                           (const int[3]){dx, dy, dz});
                m = v > m ? v : m;
            }
    return m;
}

bool volume_grid_finish(VolumeGridBuilder *b, Error *err)
{
    VolumeGrid *g = b->grid;
    if (!check_values(b, err)) {
        volume_grid_free(g);
        return false;
    }
    float *brick_maxima = malloc((g->num_bricks ? g->num_bricks : 1) * sizeof(float));
    g->majorants = malloc(table_size(g) * sizeof(float));
    if (!brick_maxima || !g->majorants) {
        free(brick_maxima);
        volume_grid_free(g);
        error_set(err, ERR_OUT_OF_MEMORY, b->path, 0, "%s: out of memory for the majorants",
                  grid_name(b));
        return false;
    }
    drop_zero_bricks(g, brick_maxima);
    g->max_value = 0.0f;
    for (uint32_t id = 0; id < g->num_bricks; id++)
        g->max_value = brick_maxima[id] > g->max_value ? brick_maxima[id] : g->max_value;
    for (uint32_t bz = 0; bz < g->bricks[2]; bz++)
        for (uint32_t by = 0; by < g->bricks[1]; by++)
            for (uint32_t bx = 0; bx < g->bricks[0]; bx++)
                g->majorants[table_cell(g, bx, by, bz)] = cell_majorant(g, brick_maxima, bx, by, bz);
    free(brick_maxima);
    if (g->num_bricks == 0) { /* all zeros: no values array (callers may still read it as empty) */
        free(g->values);
        g->values = NULL;
    }
    return true;
}

bool volume_grid_from_dense(const float *values, const uint32_t res[3], VolumeGrid *out,
                            Error *err)
{
    VolumeGridBuilder b;
    if (!volume_grid_begin(&b, out, res, "", err))
        return false;
    const size_t slice = (size_t)res[0] * res[1];
    for (uint32_t z0 = 0; z0 < res[2]; z0 += MEDIUM_BRICK) {
        uint32_t count = res[2] - z0 < MEDIUM_BRICK ? res[2] - z0 : MEDIUM_BRICK;
        if (!volume_grid_put_layer(&b, values + z0 * slice, z0, count, err)) {
            volume_grid_free(out);
            return false;
        }
    }
    return volume_grid_finish(&b, err);
}

void volume_grid_free(VolumeGrid *grid)
{
    free(grid->brick_table);
    free(grid->values);
    free(grid->majorants);
    memset(grid, 0, sizeof *grid);
}

bool volume_grid_read(const char *path, const char *grid_name, VolumeGrid *out, Error *err)
{
    memset(out, 0, sizeof *out);
    if (fs_has_suffix(path, ".vol"))
        return volume_vol_read(path, grid_name ? grid_name : "", out, err);
    if (fs_has_suffix(path, ".nvdb"))
        return volume_nvdb_read(path, grid_name ? grid_name : "", out, err);
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    error_set(err, ERR_FILE_READ, path, 0,
              "%s: unknown grid file type '%s' (pt reads NanoVDB .nvdb and Mitsuba 3 .vol)", path,
              dot ? dot : "(no extension)");
    return false;
}
