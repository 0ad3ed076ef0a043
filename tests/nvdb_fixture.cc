// SPDX-License-Identifier: MIT
/* nvdb_fixture.cc: NanoVDB files and their reference values (tests/nvdb_fixture.h). */
#include "nvdb_fixture.h"

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/Primitives.h>

#include <cstdlib>
#include <exception>
#include <vector>

namespace {

using Handle = nanovdb::GridHandle<nanovdb::HostBuffer>;

bool write(const char *path, const std::vector<Handle> &handles)
{
    try {
        nanovdb::io::writeGrids<nanovdb::HostBuffer, std::vector>(path, handles);
        return true;
    } catch (const std::exception &) {
        return false;
    }
}

Handle sphere(const char *name, float radius, const double center[3], double voxel_size,
              const double origin[3])
{
    return nanovdb::createFogVolumeSphere<float>(
        radius, nanovdb::Vec3f(float(center[0]), float(center[1]), float(center[2])), voxel_size, 3.0,
        nanovdb::Vec3d(origin[0], origin[1], origin[2]), name);
}

} // namespace

extern "C" bool nvdb_fixture_write_sphere(const char *path, const char *name, float radius,
                                          const double center[3], double voxel_size,
                                          const double origin[3])
{
    std::vector<Handle> handles;
    handles.push_back(sphere(name, radius, center, voxel_size, origin));
    return write(path, handles);
}

extern "C" bool nvdb_fixture_write_voxels(const char *path, const char *name, int count,
                                          const int *ijk, const float *values,
                                          const double *matrix, const double translation[3])
{
    nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
    auto acc = builder.getAccessor();
    for (int v = 0; v < count; v++)
        acc.setValue(nanovdb::Coord(ijk[3 * v], ijk[3 * v + 1], ijk[3 * v + 2]), values[v]);
    /* Map::set takes OpenVDB's transposed (column-vector-as-row) matrices. */
    double mat[3][3], inv[3][3];
    double m[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int i = 0; matrix && i < 9; i++)
        m[i] = matrix[i];
    double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                 m[2] * (m[3] * m[7] - m[4] * m[6]);
    double adj[9] = {m[4] * m[8] - m[5] * m[7], m[2] * m[7] - m[1] * m[8], m[1] * m[5] - m[2] * m[4],
                     m[5] * m[6] - m[3] * m[8], m[0] * m[8] - m[2] * m[6], m[2] * m[3] - m[0] * m[5],
                     m[3] * m[7] - m[4] * m[6], m[1] * m[6] - m[0] * m[7], m[0] * m[4] - m[1] * m[3]};
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            mat[c][r] = m[3 * r + c];
            inv[c][r] = adj[3 * r + c] / det;
        }
    nanovdb::Map map;
    map.set(mat, inv, nanovdb::Vec3d(translation[0], translation[1], translation[2]), 1.0);
    std::vector<Handle> handles;
    handles.push_back(builder.getHandle(map, name));
    return write(path, handles);
}

extern "C" bool nvdb_fixture_write_box(const char *path, const char *name, const int lo[3],
                                       const int hi[3], float value, const int spot[3])
{
    nanovdb::GridBuilder<float> builder(0.0f, nanovdb::GridClass::FogVolume);
    builder([value](const nanovdb::Coord &) { return value; },
            nanovdb::CoordBBox(nanovdb::Coord(lo[0], lo[1], lo[2]), nanovdb::Coord(hi[0], hi[1], hi[2])));
    builder.getAccessor().setValue(nanovdb::Coord(spot[0], spot[1], spot[2]), 3.0f);
    std::vector<Handle> handles;
    handles.push_back(builder.getHandle(1.0, nanovdb::Vec3d(0.0), name));
    return write(path, handles);
}

extern "C" bool nvdb_fixture_write_mixed(const char *path)
{
    nanovdb::GridBuilder<double> temperature(0.0, nanovdb::GridClass::Unknown);
    temperature.getAccessor().setValue(nanovdb::Coord(1, 2, 3), 300.0);
    nanovdb::GridBuilder<float> flame(0.0f, nanovdb::GridClass::FogVolume);
    flame.getAccessor().setValue(nanovdb::Coord(-4, 0, 9), 2.5f);
    const double zero[3] = {0, 0, 0};
    std::vector<Handle> handles;
    handles.push_back(temperature.getHandle(1.0, nanovdb::Vec3d(0.0), "temperature"));
    handles.push_back(sphere("density", 5.0f, zero, 0.5, zero));
    handles.push_back(flame.getHandle(1.0, nanovdb::Vec3d(0.0), "flame"));
    return write(path, handles);
}

extern "C" bool nvdb_fixture_reference(const char *path, const char *name, NvdbReference *out)
{
    try {
        auto handle = nanovdb::io::readGrid<nanovdb::HostBuffer>(path, name);
        const nanovdb::NanoGrid<float> *grid = handle.grid<float>();
        if (!grid)
            return false;
        const nanovdb::CoordBBox &box = grid->tree().root().bbox();
        for (int a = 0; a < 3; a++)
            out->lo[a] = box.min()[a], out->hi[a] = box.max()[a];
        size_t nx = size_t(out->hi[0] - out->lo[0] + 1), ny = size_t(out->hi[1] - out->lo[1] + 1),
               nz = size_t(out->hi[2] - out->lo[2] + 1);
        out->values = static_cast<float *>(malloc(nx * ny * nz * sizeof(float)));
        if (!out->values)
            return false;
        auto acc = grid->getAccessor();
        for (size_t z = 0; z < nz; z++)
            for (size_t y = 0; y < ny; y++)
                for (size_t x = 0; x < nx; x++)
                    out->values[x + nx * (y + ny * z)] = acc.getValue(
                        nanovdb::Coord(out->lo[0] + int(x), out->lo[1] + int(y), out->lo[2] + int(z)));
        const auto &tree = grid->tree();
        for (uint32_t level = 1; level <= 3; level++)
            out->active_tiles[level - 1] = tree.activeTileCount(level);
        return true;
    } catch (const std::exception &) {
        return false;
    }
}

extern "C" bool nvdb_fixture_index_to_world(const char *path, const char *name, const double ijk[3],
                                            double world[3])
{
    try {
        auto handle = nanovdb::io::readGrid<nanovdb::HostBuffer>(path, name);
        const nanovdb::NanoGrid<float> *grid = handle.grid<float>();
        if (!grid)
            return false;
        nanovdb::Vec3d p = grid->indexToWorld(nanovdb::Vec3d(ijk[0], ijk[1], ijk[2]));
        for (int a = 0; a < 3; a++)
            world[a] = p[a];
        return true;
    } catch (const std::exception &) {
        return false;
    }
}
