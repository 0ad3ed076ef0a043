// SPDX-License-Identifier: MIT
/* libFuzzer target: the grid readers (host/io/volume_vol.c, volume_nvdb.cc, volume_grid.c). The
 * first byte is the mode: bit 0 picks the format (0: Mitsuba .vol, 1: NanoVDB .nvdb), bit 1 asks
 * for the grid "density" instead of the default; the rest is the file. A grid read must hold
 * together: table entries inside the bricks, densities finite and >= 0, majorants bounding their
 * bricks, a finite map. */
#include "fuzz_input.h"

#include <math.h>

#include "base/shared_types.h"
#include "io/volume_grid.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check_grid(const VolumeGrid *g)
{
    size_t table = (size_t)g->bricks[0] * g->bricks[1] * g->bricks[2];
    for (int a = 0; a < 3; a++)
        if (g->res[a] == 0 || g->bricks[a] != (g->res[a] + MEDIUM_BRICK - 1) / MEDIUM_BRICK)
            abort();
    for (size_t v = 0; v < (size_t)g->num_bricks * MEDIUM_BRICK_VOXELS; v++)
        if (!(g->values[v] >= 0.0f && isfinite(g->values[v]) && g->values[v] <= g->max_value))
            abort();
    for (size_t c = 0; c < table; c++) {
        uint32_t id = g->brick_table[c];
        if (!(g->majorants[c] >= 0.0f && g->majorants[c] <= g->max_value))
            abort();
        if (id == MEDIUM_NO_BRICK)
            continue;
        if (id >= g->num_bricks)
            abort();
        for (uint32_t v = 0; v < MEDIUM_BRICK_VOXELS; v++)
            if (g->values[(size_t)id * MEDIUM_BRICK_VOXELS + v] > g->majorants[c])
                abort();
    }
    for (int i = 0; i < 12; i++)
        if (!isfinite(g->index_to_object[i]))
            abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path(data[0] & 1 ? "x.nvdb" : "x.vol"));
    fuzz_write(path, data + 1, size - 1);
    /* Under libFuzzer's 2 GiB: a few bytes may describe a large constant box. */
    volume_grid_set_brick_limit((uint64_t)256 << 20);
    VolumeGrid grid;
    Error err = {0};
    if (volume_grid_read(path, data[0] & 2 ? "density" : "", &grid, &err)) {
        check_grid(&grid);
        volume_grid_free(&grid);
    } else if (!err.message[0] || strchr(err.message, '\n')) {
        abort();
    }
    return 0;
}
