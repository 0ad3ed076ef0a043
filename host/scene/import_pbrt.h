/* SPDX-License-Identifier: MIT */
/* import_pbrt.h: pbrt-v4 scene files (.pbrt) as a pt JSON scene plus in-memory meshes
 * (scene/scene_import.h). What maps exactly, what maps approximately and what is dropped with a
 * warning is listed in README.md "pbrt-v4 scenes". */
#ifndef PT_IMPORT_PBRT_H
#define PT_IMPORT_PBRT_H

#include <stdbool.h>

#include "scene/scene_import.h"

bool import_pbrt(const char *path, ImportedScene *out, Error *err);

#endif
