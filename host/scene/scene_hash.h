/* SPDX-License-Identifier: MIT */
/* scene_hash.h: a 64-bit hash of the scene as the devices see it (every flattened array of
 * SceneData, the camera, the film size, the background, the black holes), for the identity of a
 * checkpoint (dist/checkpoint.h); and the streaming 64-bit hash it is made of, which the
 * checkpoint file's checksum uses too.
 *
 * The hash takes 8-byte little-endian words: word' = (w * K1) ^ >> 31, h = (h ^ word') * K2, a
 * splitmix64 finish over h and the length. It is not cryptographic (a crafted collision is easy),
 * but for inputs that differ by accident two hashes agree with a chance of about 2^-64: among a
 * million different scenes the odds of any pair colliding are about 3e-8. */
#ifndef PT_SCENE_HASH_H
#define PT_SCENE_HASH_H

#include <stddef.h>
#include <stdint.h>

#include "scene/scene.h"

typedef struct {
    uint64_t h;
    uint64_t length; /* bytes hashed so far */
    uint8_t tail[8]; /* length % 8 bytes not yet hashed */
} Hash64;

void hash64_init(Hash64 *s);
void hash64_bytes(Hash64 *s, const void *data, size_t size);
void hash64_u32(Hash64 *s, uint32_t v);
void hash64_u64(Hash64 *s, uint64_t v);
/* A float by its bits (-0 and 0 differ, as they may in the image). */
void hash64_float(Hash64 *s, float v);
uint64_t hash64_finish(const Hash64 *s);
/* hash64_init + hash64_bytes + hash64_finish. */
uint64_t hash64(const void *data, size_t size);

/* Everything of scene that the image depends on (device-independent: not its BVH, which each
 * device builds for its own layout from the same triangles). Two loads of one scene file give the
 * same hash; a change to any triangle, material, texel, light, instance, motion, black hole, the
 * camera, the film size or the background gives another. */
uint64_t scene_hash(const Scene *scene);

#endif
