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

/* The mesh of decoded arrays (xyz positions; normals and uvs per position or NULL; glTF's uv,
 * v = 0 at the top; vertex indices of `mode`): decode_primitive's last step, shared with the
 * KHR_draco_mesh_compression decoder. `where` names the primitive in errors. */
bool mesh_from_arrays(const tinygltf::Model &model, const char *path, const char *where, int mode,
                      const std::vector<float> &pos, const std::vector<float> *normals,
                      const std::vector<float> *uvs, const std::vector<uint32_t> &idx, Mesh *out,
                      Error *err);

/* tinygltf refuses an index accessor without a buffer view, which is what a Draco primitive's
 * is (its indices are in the Draco data): for a file naming KHR_draco_mesh_compression, the
 * glTF (glb: a JSON chunk of a checked GLB) with those primitives' "indices" removed, in
 * `patched`; false when nothing needs changing. */
bool draco_prepare(const unsigned char *data, size_t size, bool glb, std::string &patched);

/* A primitive with KHR_draco_mesh_compression, decoded by libdraco (io/gltf_draco.cc). */
bool decode_draco_primitive(const tinygltf::Model &model, int mesh, int primitive,
                            const char *path, Mesh *out, Error *err);

/* Before tinygltf reads the JSON text (gltf_json_check.cc): its nesting depth (ERR_JSON_SYNTAX),
 * and the external URIs of buffers and images, which must stay inside path's folder
 * (ERR_PATH_ESCAPES naming "images[0].uri"). *uris_checked: false when the text is not JSON to
 * cJSON (tinygltf then says why), and no external file may be opened. */
bool check_json(const char *path, const char *json, size_t size, bool *uris_checked, Error *err);

/* The encoded bytes of every image stored in a buffer view, copied into image.image after the
 * view is checked against its buffer (tinygltf passes the view's bytes unchecked: the image
 * loader callback leaves them). Errors name "images[0].bufferView". */
bool read_image_views(tinygltf::Model &model, const char *path, Error *err);

} // namespace gltf_io

#endif
