// SPDX-License-Identifier: MIT
/* WIP: implemented by the checkpoint work. */
#include "render/checkpoint.h"

#include <stdio.h>

uint64_t render_identity(const Scene *scene, const RenderSettings *settings, const UnitGrid *grid)
{
    (void)scene, (void)settings, (void)grid;
    return 0;
}

void checkpoint_path(const char *output, char *out, size_t size)
{
    snprintf(out, size, "%s.ptckpt", output);
}

bool checkpoint_write(const char *path, uint64_t identity, UnitFilm *f, Error *err)
{
    (void)identity, (void)f;
    error_set(err, ERR_OUTPUT, path, 0, "%s: checkpoints are not written yet", path);
    return false;
}

bool checkpoint_read(const char *path, uint64_t identity, UnitFilm *f, Error *err)
{
    (void)identity, (void)f;
    error_set(err, ERR_FILE_READ, path, 0, "%s: checkpoints are not read yet", path);
    return false;
}
