/* SPDX-License-Identifier: MIT */
/* volume_nvdb_internal.h (C++, io/ only): what the NanoVDB reader's two files share: the file's
 * part (volume_nvdb.cc: segments, grid metadata, the chosen grid's bytes) hands one grid buffer to
 * the grid's part (volume_nvdb_grid.cc: its headers checked, then densified from its node arrays). */
#ifndef PT_VOLUME_NVDB_INTERNAL_H
#define PT_VOLUME_NVDB_INTERNAL_H

#include <nanovdb/NanoVDB.h>

#include <cstdint>
#include <string>

/* base/ is C11: its _Noreturn has this C++11 spelling. */
#define _Noreturn [[noreturn]]
extern "C" {
#include "io/volume_grid_build.h"
}
#undef _Noreturn

namespace volume_nvdb {

using LeafData = nanovdb::LeafData<float, nanovdb::Coord, nanovdb::Mask, 3>;
using LowerData = nanovdb::InternalData<nanovdb::NanoLeaf<float>, 4>;
using UpperData = nanovdb::InternalData<nanovdb::NanoLower<float>, 5>;
using RootData = nanovdb::RootData<nanovdb::NanoUpper<float>>;
using TreeData = nanovdb::TreeData<3>;
using GridData = nanovdb::GridData;

constexpr uint32_t FORMAT_MAJOR = NANOVDB_MAJOR_VERSION_NUMBER;

/* One grid of the file, from its segment's metadata. */
struct GridEntry {
    std::string name; /* printable (control bytes replaced), for messages */
    std::string raw_name;
    uint32_t type;
    uint64_t offset, size;
};

/* The open file. */
struct Reader {
    const char *path;
    int fd;
    uint64_t file_size;
    Error *err;
};

/* Sets r.err to "PATH: <fmt>" and returns false. */
bool fail(const Reader &r, ErrorCode code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
const char *type_name(uint32_t type);
std::string version_text(uint32_t v);

/* The grid's headers (magic, version, size, type, map, node arrays inside the buffer and
 * aligned), before any node is read. buf: g.size bytes, 32-byte aligned, at least the grid, tree
 * and root headers. */
bool check_grid(const Reader &r, const GridEntry &g, const unsigned char *buf);
/* The checked grid into *out (the active voxels' box, leaves and active tiles). */
bool densify(const Reader &r, const GridEntry &g, const unsigned char *buf, VolumeGrid *out);

} // namespace volume_nvdb

#endif
