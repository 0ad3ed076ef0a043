/* SPDX-License-Identifier: MIT */
/* draco_fixture.h: a UV sphere written twice as glTF 2.0 with libdraco's encoder: plain
 * (float accessors in a .bin) and with KHR_draco_mesh_compression (positions quantised to
 * `position_bits`, normals to 12 bits, uvs to 14), for tests/test_gltf_draco.c and the load-time
 * measurement of tools (make_draco_gltf). */
#ifndef PT_TEST_DRACO_FIXTURE_H
#define PT_TEST_DRACO_FIXTURE_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Writes dir/plain.gltf + plain.bin and dir/draco.gltf + draco.bin: a sphere of radius 1 at the
 * origin with `around` segments (around / 2 rings; 2 * around * around / 2 triangles). */
bool draco_fixture_write(const char *dir, int around, int position_bits);

#ifdef __cplusplus
}
#endif

#endif
