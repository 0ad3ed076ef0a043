// SPDX-License-Identifier: MIT
/* volume_nvdb_grid.cc: one NanoVDB float grid's buffer (volume_nvdb_internal.h), read as hostile
 * input: its grid and tree headers are checked (magic, version, size, type, a finite invertible map,
 * every node array inside the buffer and 32-byte aligned) before any node is looked at; then it is
 * densified by walking the node arrays, never the tree's child links (NanoVDB follows those
 * unchecked): every leaf (its origin and 512 values: NanoVDB's value of a voxel in a leaf, active
 * or not) and the active constant tiles of the lower and upper internal nodes and of the root.
 * Inactive tiles and the background count as 0 (the empty space of a fog volume); the grid spans
 * the active voxels' bounding box. */
#include <algorithm>
#include <cmath>

#include "io/volume_nvdb_internal.h"

namespace volume_nvdb {

namespace {

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

} // namespace

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

namespace {

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

} // namespace

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

} // namespace volume_nvdb
