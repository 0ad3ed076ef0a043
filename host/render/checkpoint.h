/* SPDX-License-Identifier: MIT */
/* checkpoint.h: a render's film saved so that a crash costs at most the last interval: the exact
 * film sums and the finished units (render/unit_film.h) with the identity of the render (a hash of
 * the scene as flattened and of every setting the image depends on). Written atomically beside
 * the output (OUTPUT.ptckpt: a temporary file, fsync, rename), read back by --resume, which
 * refuses a checkpoint of another scene, other settings, another version of the format, or a
 * damaged file, with a message naming the file and what differs. */
#ifndef PT_CHECKPOINT_H
#define PT_CHECKPOINT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "render/unit_film.h"
#include "render/wavefront.h"
#include "scene/scene.h"

/* What the image is a function of: the scene (its flattened data: geometry, materials, textures,
 * lights, camera, film), the settings that change samples (spp, max depth, seed, no_nee, clamp)
 * and the unit grid (the finished-unit set is in its numbering). Not the device: a render resumed
 * on another device is equal within float rounding (README). */
uint64_t render_identity(const Scene *scene, const RenderSettings *settings, const UnitGrid *grid);

/* OUTPUT.ptckpt (out holds size bytes). */
void checkpoint_path(const char *output, char *out, size_t size);

/* Saves f (its lock held while copying) atomically to path. */
bool checkpoint_write(const char *path, uint64_t identity, UnitFilm *f, Error *err);

/* Loads path into f (which must be empty, for the same grid). False with a message naming path
 * when there is no checkpoint, it is truncated or damaged, of another format version, or of
 * another render (identity differs). */
bool checkpoint_read(const char *path, uint64_t identity, UnitFilm *f, Error *err);

#endif
