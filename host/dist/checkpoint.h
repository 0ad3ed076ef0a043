/* SPDX-License-Identifier: MIT */
/* checkpoint.h: a render's film saved so that a crash costs at most the last interval: the exact
 * film sums and the finished units (dist/unit_film.h) with the identity of the render (a hash of
 * the scene as flattened and every setting the image depends on). Written atomically beside the
 * output (OUTPUT.ptckpt: a temporary file in the same folder, fsync, rename: base/fs.h), read back
 * by --resume, which refuses a checkpoint of another scene, other settings, another version of the
 * format, or a damaged file, with one message naming the file and what differs.
 *
 * The file (every field little-endian, whatever the host):
 *   0  "PTCKPT\r\n"   magic (the \r\n catches a text-mode copy)
 *   8  u32 version    CHECKPOINT_VERSION
 *  12  u32 80         bytes of this header
 *  16  u64 scene      scene_hash (scene/scene_hash.h)
 *  24  u32 max_depth, seed, first_sample, flags (1: no_nee, 2: sobol), f32 clamp_indirect
 *  44  u32 width, height, spp, unit_spp, unit_rows, count  the unit grid (dist/work_units.h)
 *  68  u32 units_done (the bits set below), film_words (FILM_WORDS), reserved 0
 *  80  the done bitmap: (count + 7) / 8 bytes (unit_bitmap_*), zero-padded to a multiple of 8
 *  ..  the film sums: width * height * film_words u64 (render/film.h)
 *  ..  u64 checksum: hash64 (scene/scene_hash.h) of every byte before it
 * A file of any other length is truncated or has trailing bytes. */
#ifndef PT_CHECKPOINT_H
#define PT_CHECKPOINT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "dist/unit_film.h"
#include "render/wavefront.h"
#include "scene/scene.h"

#define CHECKPOINT_VERSION 1u
#define CHECKPOINT_HEADER_BYTES 80u

/* What the image is a function of, kept in parts so that a refusal can say what differs: the
 * scene (its flattened data: geometry, materials, textures, lights, instances, motion, black
 * holes, camera, film, background), the settings that change samples, and the unit grid (the
 * finished-unit set is in its numbering). Not the device: a render resumed on another device is
 * equal within float rounding (README). Not the order or the split of the units. */
typedef struct {
    uint64_t scene;
    uint32_t max_depth, seed, first_sample;
    bool no_nee;
    bool sobol; /* the sampler (sampler_resolve of the settings and the scene) */
    float clamp_indirect;
    UnitGrid grid;
} RenderIdentity;

RenderIdentity render_identity(const Scene *scene, const RenderSettings *settings,
                               const UnitGrid *grid);

/* OUTPUT.ptckpt (out holds size bytes). */
void checkpoint_path(const char *output, char *out, size_t size);

/* Saves f (its lock held while writing) atomically to path. */
bool checkpoint_write(const char *path, RenderIdentity identity, UnitFilm *f, Error *err);

/* Loads path into f (empty, made for identity.grid). False with one message naming path when
 * there is no checkpoint, it is truncated, damaged or of another format version, or of another
 * render (the message says what differs); f is left empty then. */
bool checkpoint_read(const char *path, RenderIdentity identity, UnitFilm *f, Error *err);

#endif
