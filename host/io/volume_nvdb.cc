// SPDX-License-Identifier: MIT
/* volume_nvdb.cc: NanoVDB (.nvdb) float grids. (Being written: refuses every file for now.) */

/* base/ is C11: its _Noreturn has this C++11 spelling. */
#define _Noreturn [[noreturn]]
extern "C" {
#include "io/volume_grid_build.h"
}
#undef _Noreturn

extern "C" bool volume_nvdb_read(const char *path, const char *grid_name, VolumeGrid *out,
                                 Error *err)
{
    (void)grid_name;
    *out = VolumeGrid();
    error_set(err, ERR_FILE_READ, path, 0, "%s: NanoVDB grids are not read yet", path);
    return false;
}
