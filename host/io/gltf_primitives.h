/* SPDX-License-Identifier: MIT */
/* gltf_primitives.h (C++, io/ only): decoding a glTF mesh primitive from the parsed model into an
 * Mesh (host/io/gltf_primitives.cc): accessors of every component type (normalized integers as
 * the specification decodes them), byteStride, sparse substitution, range checks of accessor,
 * buffer view and buffer, and strips and fans to triangle lists. */
#ifndef PT_GLTF_PRIMITIVES_H
#define PT_GLTF_PRIMITIVES_H

#include <tiny_gltf.h>

/* base/ is C11: its _Noreturn and _Static_assert have these C++11 spellings. */
#define _Noreturn [[noreturn]]
#define _Static_assert static_assert
extern "C" {
#include "base/error.h"
#include "io/gltf_loader.h"
}
#undef _Static_assert
#undef _Noreturn

namespace gltf_io {

/* Decodes meshes[mesh].primitives[primitive] of model into *out (empty on entry). Errors name
 * path and the JSON path, e.g. "meshes[2].primitives[0].indices (accessors[4])". */
bool decode_primitive(const tinygltf::Model &model, int mesh, int primitive, const char *path,
                      Mesh *out, Error *err);

} // namespace gltf_io

#endif
