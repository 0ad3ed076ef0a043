// SPDX-License-Identifier: MIT
/* libFuzzer target: the checkpoint reader (host/dist/checkpoint.c). The input is the file, read
 * twice: as it is (the checksum stops almost everything), then with its last 8 bytes replaced by
 * the right checksum, so that the fuzzer reaches the checks behind it. The identity is fixed (the
 * seeds of corpus_checkpoint.py are made for it). Accepted: the film must be consistent; refused:
 * a message, and the film left empty. */
#include "fuzz_input.h"

#include "dist/checkpoint.h"
#include "render/film.h"
#include "scene/scene_hash.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(const char *path, RenderIdentity id)
{
    UnitFilm f;
    Error err = {0};
    if (!unit_film_init(&f, &id.grid, &err))
        abort();
    if (checkpoint_read(path, id, &f, &err)) {
        uint32_t units = 0;
        for (uint32_t u = 0; u < f.grid.count; u++)
            units += unit_bitmap_get(f.done, u);
        if (units != f.units_done)
            abort();
        /* No bit beyond the grid's units. */
        for (uint32_t u = f.grid.count; u < unit_bitmap_bytes(f.grid.count) * 8; u++)
            if (unit_bitmap_get(f.done, u))
                abort();
    } else {
        if (!err.message[0])
            abort();
        for (size_t i = 0; i < f.num_pixels * FILM_WORDS; i++)
            if (f.sums[i])
                abort();
        if (f.units_done)
            abort();
    }
    unit_film_free(&f);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    RenderIdentity id = {.scene = 0x0123456789abcdefull, .max_depth = 8, .seed = 7, .sobol = true};
    Error err = {0};
    if (!unit_grid_init(&id.grid, 5, 6, 4, 1, 2, &err))
        abort();
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path("x.ptckpt"));
    fuzz_write(path, data, size);
    check(path, id);
    if (size >= 8) {
        uint8_t *fixed = malloc(size);
        memcpy(fixed, data, size);
        uint64_t checksum = hash64(fixed, size - 8);
        for (int i = 0; i < 8; i++)
            fixed[size - 8 + i] = (uint8_t)(checksum >> 8 * i);
        fuzz_write(path, fixed, size);
        free(fixed);
        check(path, id);
    }
    return 0;
}
