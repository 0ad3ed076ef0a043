// SPDX-License-Identifier: MIT
/* volume_nvdb.cc: NanoVDB (.nvdb) float grids, read as hostile input. NanoVDB trusts its buffers
 * (its accessors follow child offsets unchecked), so none of its accessors or tree walks run here.
 * The file's segment headers and grid metadata are checked against the file's length, the chosen
 * grid's bytes are read into an aligned buffer, and its grid and tree headers are checked (magic,
 * version, size, each node array inside the buffer and aligned) before any node is looked at.
 * Then the grid is densified by walking the node arrays, never the tree's child links: every leaf
 * (origin, 512 values: NanoVDB's value of a voxel in a leaf, active or not) and the active constant
 * tiles of the lower and upper internal nodes and the root. Inactive tiles and the background
 * count as 0 (the empty space of a fog volume). The grid spans the active voxels' bounding box. */
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/IO.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <unistd.h>

/* base/ is C11: its _Noreturn has this C++11 spelling. */
#define _Noreturn [[noreturn]]
extern "C" {
#include "io/input_file.h"
#include "io/volume_grid_build.h"
}
#undef _Noreturn

namespace {

using LeafData = nanovdb::LeafData<float, nanovdb::Coord, nanovdb::Mask, 3>;
using LowerData = nanovdb::InternalData<nanovdb::NanoLeaf<float>, 4>;
using UpperData = nanovdb::InternalData<nanovdb::NanoLower<float>, 5>;
using RootData = nanovdb::RootData<nanovdb::NanoUpper<float>>;
using TreeData = nanovdb::TreeData<3>;
using GridData = nanovdb::GridData;
using FileHeader = nanovdb::io::Header;
using FileMeta = nanovdb::io::MetaData;

/* The largest grid buffer read (the bricks have their own limit, VOLUME_GRID_MAX_BRICK_BYTES). */
constexpr uint64_t MAX_GRID_BYTES = uint64_t(8) << 30;
constexpr uint32_t MAX_NAME_BYTES = 1u << 16;
constexpr uint32_t FORMAT_MAJOR = NANOVDB_MAJOR_VERSION_NUMBER;

/* One grid of the file, from its segment's metadata. */
struct GridEntry {
    std::string name; /* printable (control bytes replaced), for messages */
    std::string raw_name;
    uint32_t type;
    uint64_t offset, size;
};

struct Reader {
    const char *path;
    int fd;
    uint64_t file_size;
    Error *err;
};

bool fail(const Reader &r, ErrorCode code, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
bool fail(const Reader &r, ErrorCode code, const char *fmt, ...)
{
    char what[900];
    va_list args;
    va_start(args, fmt);
    vsnprintf(what, sizeof what, fmt, args);
    va_end(args);
    error_set(r.err, code, r.path, 0, "%s: %s", r.path, what);
    return false;
}

bool read_at(const Reader &r, void *buf, uint64_t size, uint64_t offset)
{
    uint64_t got = 0;
    while (got < size) {
        ssize_t n = pread(r.fd, static_cast<char *>(buf) + got, size - got, off_t(offset + got));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return fail(r, ERR_FILE_READ, "read failed at byte %llu (the file changed?)",
                        (unsigned long long)(offset + got));
        got += uint64_t(n);
    }
    return true;
}

const char *type_name(uint32_t type)
{
    return type < uint32_t(nanovdb::GridType::End) ? nanovdb::toStr(nanovdb::GridType(type)) : "unknown";
}

std::string printable(const char *s, size_t n)
{
    std::string out;
    for (size_t i = 0; i < n && s[i] && out.size() < 64; i++)
        out += (unsigned char)s[i] < 0x20 || s[i] == 0x7f ? '?' : s[i];
    return out;
}

std::string version_text(uint32_t v)
{
    return std::to_string(v >> 21) + "." + std::to_string((v >> 10) & 0x7ff) + "." +
           std::to_string(v & 0x3ff);
}

/* One segment's header and metadata at *pos; appends its grids and moves *pos past their data. */
bool read_segment(const Reader &r, uint64_t *pos, std::vector<GridEntry> &grids)
{
    unsigned char head[sizeof(FileHeader)];
    if (r.file_size - *pos < sizeof head)
        return fail(r, ERR_FILE_READ, "truncated: %llu bytes at byte %llu, not a NanoVDB segment header",
                    (unsigned long long)(r.file_size - *pos), (unsigned long long)*pos);
    if (!read_at(r, head, sizeof head, *pos))
        return false;
    uint64_t magic;
    uint32_t version;
    uint16_t count, codec;
    memcpy(&magic, head + offsetof(FileHeader, magic), 8);
    memcpy(&version, head + offsetof(FileHeader, version), 4);
    memcpy(&count, head + offsetof(FileHeader, gridCount), 2);
    memcpy(&codec, head + offsetof(FileHeader, codec), 2);
    if (magic == __builtin_bswap64(uint64_t(NANOVDB_MAGIC_NUMBER)))
        return fail(r, ERR_FILE_READ, "a big-endian NanoVDB file (pt reads little-endian ones)");
    if (magic != uint64_t(NANOVDB_MAGIC_NUMBER))
        return fail(r, ERR_FILE_READ, "not a NanoVDB file (no 'NanoVDB0' magic at byte %llu)",
                    (unsigned long long)*pos);
    if (version >> 21 != FORMAT_MAJOR)
        return fail(r, ERR_FILE_READ, "NanoVDB file format %s; pt reads version %u.x",
                    version_text(version).c_str(), FORMAT_MAJOR);
    if (codec != uint16_t(nanovdb::io::Codec::NONE))
        return fail(r, ERR_FILE_READ, "compressed with %s; pt reads uncompressed NanoVDB files "
                    "(write them with codec NONE)",
                    codec == 1 ? "ZIP" : codec == 2 ? "BLOSC" : "an unknown codec");
    if (count == 0)
        return fail(r, ERR_FILE_READ, "the segment at byte %llu holds no grids", (unsigned long long)*pos);
    *pos += sizeof head;
    size_t first = grids.size();
    for (uint32_t g = 0; g < count; g++) {
        unsigned char meta[sizeof(FileMeta)];
        if (r.file_size - *pos < sizeof meta)
            return fail(r, ERR_FILE_READ, "truncated in the metadata of grid %u at byte %llu", g,
                        (unsigned long long)*pos);
        if (!read_at(r, meta, sizeof meta, *pos))
            return false;
        GridEntry e;
        uint64_t file_bytes;
        uint32_t name_size;
        memcpy(&e.size, meta + offsetof(FileMeta, gridSize), 8);
        memcpy(&file_bytes, meta + offsetof(FileMeta, fileSize), 8);
        memcpy(&e.type, meta + offsetof(FileMeta, gridType), 4);
        memcpy(&name_size, meta + offsetof(FileMeta, nameSize), 4);
        *pos += sizeof meta;
        if (name_size == 0 || name_size > MAX_NAME_BYTES || r.file_size - *pos < name_size)
            return fail(r, ERR_FILE_READ, "grid %u's name of %u bytes does not fit the file", g, name_size);
        std::vector<char> name(name_size + 1, '\0');
        if (!read_at(r, name.data(), name_size, *pos))
            return false;
        *pos += name_size;
        e.raw_name.assign(name.data());
        e.name = printable(name.data(), name_size);
        if (file_bytes != e.size)
            return fail(r, ERR_FILE_READ, "grid '%s': %llu bytes on disk for a grid of %llu bytes",
                        e.name.c_str(), (unsigned long long)file_bytes, (unsigned long long)e.size);
        grids.push_back(e);
    }
    /* The grids' data follow the segment's metadata, in the same order. */
    for (size_t g = first; g < grids.size(); g++) {
        if (r.file_size - *pos < grids[g].size)
            return fail(r, ERR_FILE_READ, "truncated: grid '%s' needs %llu bytes at byte %llu, the "
                        "file has %llu", grids[g].name.c_str(), (unsigned long long)grids[g].size,
                        (unsigned long long)*pos, (unsigned long long)r.file_size);
        grids[g].offset = *pos;
        *pos += grids[g].size;
    }
    return true;
}

std::string grid_list(const std::vector<GridEntry> &grids)
{
    std::string list;
    for (const GridEntry &g : grids) {
        if (list.size() > 400) {
            list += ", ...";
            break;
        }
        list += (list.empty() ? "'" : ", '") + g.name + "' (" + type_name(g.type) + ")";
    }
    return list;
}

/* The grid named `want` ("" = the first float grid); NULL with err set. */
const GridEntry *choose_grid(const Reader &r, const std::vector<GridEntry> &grids, const char *want)
{
    for (const GridEntry &g : grids) {
        if (want[0] ? g.raw_name != want : g.type != uint32_t(nanovdb::GridType::Float))
            continue;
        if (g.type == uint32_t(nanovdb::GridType::Float))
            return &g;
        fail(r, ERR_JSON_VALUE, "grid '%s' holds %s values; a density grid must be float",
             g.name.c_str(), type_name(g.type));
        return nullptr;
    }
    if (want[0])
        fail(r, ERR_JSON_VALUE, "no grid named '%s'; the file holds %s",
             printable(want, strlen(want)).c_str(), grid_list(grids).c_str());
    else
        fail(r, ERR_JSON_VALUE, "no float grid; the file holds %s", grid_list(grids).c_str());
    return nullptr;
}

/* Node array `level` (count nodes of node_size bytes at the tree's offset) lies inside the grid
 * buffer and is 32-byte aligned (the buffer is, and so must NanoVDB's nodes be). */
bool check_nodes(const Reader &r, const GridEntry &g, const TreeData *tree, int level,
                 uint64_t count, uint64_t node_size)
{
    static const char *const names[] = {"leaf", "lower internal", "upper internal", "root"};
    if (count == 0)
        return true;
    uint64_t tree_bytes = g.size - sizeof(GridData), offset = tree->mNodeOffset[level];
    if (offset % 32 != 0)
        return fail(r, ERR_FILE_READ, "grid '%s': its %s nodes at tree offset %llu are not 32-byte "
                    "aligned", g.name.c_str(), names[level], (unsigned long long)offset);
    if (offset > tree_bytes || (tree_bytes - offset) / node_size < count)
        return fail(r, ERR_FILE_READ, "grid '%s': %llu %s nodes at tree offset %llu do not fit "
                    "its %llu bytes", g.name.c_str(), (unsigned long long)count, names[level],
                    (unsigned long long)offset, (unsigned long long)g.size);
    return true;
}

/* The grid's headers, before any node is read (read_grid checked that they fit). */
bool check_grid(const Reader &r, const GridEntry &g, const unsigned char *buf)
{
    const GridData *grid = reinterpret_cast<const GridData *>(buf);
    if (grid->mMagic != uint64_t(NANOVDB_MAGIC_NUMBER))
        return fail(r, ERR_FILE_READ, "grid '%s': bad magic in its grid header", g.name.c_str());
    if (grid->mVersion.getMajor() != FORMAT_MAJOR)
        return fail(r, ERR_FILE_READ, "grid '%s': NanoVDB version %s; pt reads version %u.x",
                    g.name.c_str(), version_text(grid->mVersion.id()).c_str(), FORMAT_MAJOR);
    if (grid->mGridSize != g.size)
        return fail(r, ERR_FILE_READ, "grid '%s': its header says %llu bytes, the file %llu",
                    g.name.c_str(), (unsigned long long)grid->mGridSize, (unsigned long long)g.size);
    if (grid->mGridType != nanovdb::GridType::Float)
        return fail(r, ERR_JSON_VALUE, "grid '%s' holds %s values; a density grid must be float",
                    g.name.c_str(), type_name(uint32_t(grid->mGridType)));
    const double *m = grid->mMap.mMatD, *t = grid->mMap.mVecD;
    double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                 m[2] * (m[3] * m[7] - m[4] * m[6]);
    if (!std::isfinite(det) || det == 0.0 || !std::isfinite(t[0]) || !std::isfinite(t[1]) ||
        !std::isfinite(t[2]))
        return fail(r, ERR_FILE_READ, "grid '%s': its index-to-world map is singular or not finite",
                    g.name.c_str());
    const TreeData *tree = reinterpret_cast<const TreeData *>(grid + 1);
    if (!check_nodes(r, g, tree, 0, tree->mNodeCount[0], sizeof(LeafData)) ||
        !check_nodes(r, g, tree, 1, tree->mNodeCount[1], sizeof(LowerData)) ||
        !check_nodes(r, g, tree, 2, tree->mNodeCount[2], sizeof(UpperData)) ||
        !check_nodes(r, g, tree, 3, 1, sizeof(RootData)))
        return false;
    const RootData *root =
        reinterpret_cast<const RootData *>(reinterpret_cast<const char *>(tree) + tree->mNodeOffset[3]);
    uint64_t after_root = g.size - sizeof(GridData) - tree->mNodeOffset[3] - sizeof(RootData);
    if (after_root / sizeof(RootData::Tile) < root->mTableSize)
        return fail(r, ERR_FILE_READ, "grid '%s': the root's %u tiles do not fit the grid",
                    g.name.c_str(), root->mTableSize);
    return true;
}

/* What the walk writes into: the builder and the grid's index box [lo, hi] (inclusive). Tiles of a
 * valid grid do not overlap, so together they cover at most the box: tile_budget (its voxel
 * count) bounds the work a hostile file of many overlapping large tiles could ask for. */
struct Densify {
    VolumeGridBuilder builder;
    int64_t lo[3], hi[3];
    uint64_t tile_budget;
    const Reader *reader;
    const GridEntry *grid;
};

/* Voxels [origin, origin + size)^3 (NanoVDB index space) = value, clipped to the box. */
bool fill_tile(Densify &d, const nanovdb::Coord &origin, int64_t size, float value)
{
    uint32_t from[3], to[3];
    uint64_t voxels = 1;
    for (int a = 0; a < 3; a++) {
        int64_t start = std::max<int64_t>(origin[a], d.lo[a]);
        int64_t end = std::min<int64_t>(int64_t(origin[a]) + size - 1, d.hi[a]);
        if (start > end)
            return true;
        from[a] = uint32_t(start - d.lo[a]);
        to[a] = uint32_t(end - d.lo[a] + 1);
        voxels *= uint64_t(to[a] - from[a]);
    }
    if (voxels > d.tile_budget)
        return fail(*d.reader, ERR_FILE_READ, "grid '%s': its active tiles overlap (they cover more "
                    "voxels than its box holds)", d.grid->name.c_str());
    d.tile_budget -= voxels;
    return volume_grid_fill_box(&d.builder, from, to, value, d.reader->err);
}

bool put_leaves(Densify &d, const TreeData *tree)
{
    if (tree->mNodeCount[0] == 0)
        return true; /* its offset is unchecked then (check_nodes): not even added to a pointer */
    const char *base = reinterpret_cast<const char *>(tree) + tree->mNodeOffset[0];
    for (uint32_t i = 0; i < tree->mNodeCount[0]; i++) {
        const LeafData *leaf = reinterpret_cast<const LeafData *>(base + uint64_t(i) * sizeof(LeafData));
        int64_t origin[3] = {leaf->mBBoxMin[0] & ~7, leaf->mBBoxMin[1] & ~7, leaf->mBBoxMin[2] & ~7};
        for (uint32_t n = 0; n < 512; n++) {
            /* NanoVDB's leaf offsets run z fastest: n = x * 64 + y * 8 + z. */
            int64_t ijk[3] = {origin[0] + (n >> 6), origin[1] + ((n >> 3) & 7), origin[2] + (n & 7)};
            if (ijk[0] < d.lo[0] || ijk[1] < d.lo[1] || ijk[2] < d.lo[2] || ijk[0] > d.hi[0] ||
                ijk[1] > d.hi[1] || ijk[2] > d.hi[2])
                continue;
            if (!volume_grid_set_voxel(&d.builder, uint32_t(ijk[0] - d.lo[0]), uint32_t(ijk[1] - d.lo[1]),
                                       uint32_t(ijk[2] - d.lo[2]), leaf->mValues[n], d.reader->err))
                return false;
        }
    }
    return true;
}

/* The active tiles of the internal nodes of one level (Node: LowerData or UpperData). */
template <typename Node, uint32_t LOG2DIM, uint32_t CHILD_LOG2>
bool put_internal_tiles(Densify &d, const TreeData *tree, int level)
{
    if (tree->mNodeCount[level] == 0)
        return true;
    const char *base = reinterpret_cast<const char *>(tree) + tree->mNodeOffset[level];
    constexpr uint32_t DIM = 1u << LOG2DIM, SIZE = DIM * DIM * DIM;
    constexpr int32_t NODE_MASK = (1 << (LOG2DIM + CHILD_LOG2)) - 1;
    for (uint32_t i = 0; i < tree->mNodeCount[level]; i++) {
        const Node *node = reinterpret_cast<const Node *>(base + uint64_t(i) * sizeof(Node));
        const nanovdb::Coord &min = node->mBBox[0];
        for (uint32_t n = 0; n < SIZE; n++) {
            if (node->mChildMask.isOn(n) || !node->mValueMask.isOn(n))
                continue;
            /* Offsets run z fastest, as in the leaves. */
            nanovdb::Coord origin((min[0] & ~NODE_MASK) + int32_t((n >> (2 * LOG2DIM)) << CHILD_LOG2),
                                  (min[1] & ~NODE_MASK) + int32_t(((n >> LOG2DIM) & (DIM - 1)) << CHILD_LOG2),
                                  (min[2] & ~NODE_MASK) + int32_t((n & (DIM - 1)) << CHILD_LOG2));
            if (!fill_tile(d, origin, int64_t(1) << CHILD_LOG2, node->mTable[n].value))
                return false;
        }
    }
    return true;
}

bool put_root_tiles(Densify &d, const RootData *root)
{
    const RootData::Tile *tiles = reinterpret_cast<const RootData::Tile *>(root + 1);
    for (uint32_t i = 0; i < root->mTableSize; i++) {
        const RootData::Tile &tile = tiles[i];
        if (tile.child == 0 && tile.state &&
            !fill_tile(d, RootData::KeyToCoord(tile.key), int64_t(1) << 12, tile.value))
            return false;
    }
    return true;
}

/* Index space: NanoVDB's voxel ijk sits at index point ijk, ours (i = ijk - lo) at i + 0.5. False
 * when the result is not finite (a huge map times a far box). */
bool set_index_to_object(VolumeGrid *out, const GridData *grid, const int64_t lo[3])
{
    const double *m = grid->mMap.mMatD, *t = grid->mMap.mVecD;
    for (int row = 0; row < 3; row++) {
        double translation = t[row];
        for (int c = 0; c < 3; c++) {
            out->index_to_object[4 * row + c] = m[3 * row + c];
            translation += m[3 * row + c] * (double(lo[c]) - 0.5);
        }
        out->index_to_object[4 * row + 3] = translation;
    }
    for (double v : out->index_to_object)
        if (!std::isfinite(v))
            return false;
    return true;
}

bool densify(const Reader &r, const GridEntry &g, const unsigned char *buf, VolumeGrid *out)
{
    const GridData *grid = reinterpret_cast<const GridData *>(buf);
    const TreeData *tree = reinterpret_cast<const TreeData *>(grid + 1);
    const RootData *root =
        reinterpret_cast<const RootData *>(reinterpret_cast<const char *>(tree) + tree->mNodeOffset[3]);
    Densify d;
    d.reader = &r;
    d.grid = &g;
    uint32_t res[3];
    for (int a = 0; a < 3; a++) {
        d.lo[a] = root->mBBox[0][a], d.hi[a] = root->mBBox[1][a];
        if (d.lo[a] > d.hi[a])
            return fail(r, ERR_FILE_READ, "grid '%s' has no active voxels", g.name.c_str());
        int64_t n = d.hi[a] - d.lo[a] + 1;
        res[a] = n > int64_t(VOLUME_GRID_MAX_VOXELS) ? uint32_t(VOLUME_GRID_MAX_VOXELS) + 1 : uint32_t(n);
    }
    if (!volume_grid_begin(&d.builder, out, res, r.path, r.err))
        return false;
    d.tile_budget = uint64_t(res[0]) * res[1] * res[2]; /* within 2^31: begin checked */
    bool ok = put_leaves(d, tree) &&
              put_internal_tiles<LowerData, 4, 3>(d, tree, 1) &&
              put_internal_tiles<UpperData, 5, 7>(d, tree, 2) && put_root_tiles(d, root);
    if (!ok) {
        volume_grid_free(out);
        return false;
    }
    if (!volume_grid_finish(&d.builder, r.err))
        return false;
    if (!set_index_to_object(out, grid, d.lo)) {
        volume_grid_free(out);
        return fail(r, ERR_FILE_READ, "grid '%s': its index-to-world map overflows at its box",
                    g.name.c_str());
    }
    return true;
}

bool read_grid(const Reader &r, const char *grid_name, VolumeGrid *out)
{
    std::vector<GridEntry> grids;
    for (uint64_t pos = 0; pos < r.file_size;)
        if (!read_segment(r, &pos, grids))
            return false;
    if (grids.empty())
        return fail(r, ERR_FILE_READ, "empty file: not a NanoVDB file");
    const GridEntry *g = choose_grid(r, grids, grid_name);
    if (!g)
        return false;
    if (g->size < sizeof(GridData) + sizeof(TreeData) + sizeof(RootData))
        return fail(r, ERR_FILE_READ, "grid '%s': %llu bytes is too small for a NanoVDB grid",
                    g->name.c_str(), (unsigned long long)g->size);
    if (g->size > MAX_GRID_BYTES)
        return fail(r, ERR_TOO_LARGE, "grid '%s' of %llu bytes is over the limit of %llu GiB",
                    g->name.c_str(), (unsigned long long)g->size, (unsigned long long)(MAX_GRID_BYTES >> 30));
    /* Aligned as NanoVDB lays out its nodes (32 bytes), which the file's offsets are not. */
    unsigned char *buf = static_cast<unsigned char *>(aligned_alloc(32, (g->size + 31) & ~uint64_t(31)));
    if (!buf)
        return fail(r, ERR_OUT_OF_MEMORY, "out of memory for grid '%s' (%llu bytes)", g->name.c_str(),
                    (unsigned long long)g->size);
    bool ok = read_at(r, buf, g->size, g->offset) && check_grid(r, *g, buf) && densify(r, *g, buf, out);
    free(buf);
    return ok;
}

} // namespace

extern "C" bool volume_nvdb_read(const char *path, const char *grid_name, VolumeGrid *out, Error *err)
{
    *out = VolumeGrid();
    long long size = 0;
    int fd = input_file_open(path, "a NanoVDB file", &size, err);
    if (fd < 0)
        return false;
    Reader r = {path, fd, uint64_t(size), err};
    bool ok = read_grid(r, grid_name, out);
    close(fd);
    return ok;
}
