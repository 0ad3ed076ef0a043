// SPDX-License-Identifier: MIT
/* volume_nvdb.cc: NanoVDB (.nvdb) files, read as hostile input: every segment header and grid
 * metadata record is checked against the file's length (magic, version, uncompressed, sizes), the
 * grid is chosen by name (or the first float grid), and its bytes are read into a 32-byte aligned
 * buffer, which volume_nvdb_grid.cc checks and densifies. No NanoVDB reader or accessor runs:
 * they trust the file. */
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/IO.h>

#include <cerrno>
#include <cstdarg>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <unistd.h>

#include "io/volume_nvdb_internal.h"

/* base/ is C11: its _Noreturn has this C++11 spelling. */
#define _Noreturn [[noreturn]]
extern "C" {
#include "io/input_file.h"
}
#undef _Noreturn

namespace volume_nvdb {

namespace {

using FileHeader = nanovdb::io::Header;
using FileMeta = nanovdb::io::MetaData;

/* The largest grid buffer read (the bricks have their own limit, VOLUME_GRID_MAX_BRICK_BYTES). */
constexpr uint64_t MAX_GRID_BYTES = uint64_t(8) << 30;
constexpr uint32_t MAX_NAME_BYTES = 1u << 16;

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

std::string printable(const char *s, size_t n)
{
    std::string out;
    for (size_t i = 0; i < n && s[i] && out.size() < 64; i++)
        out += (unsigned char)s[i] < 0x20 || s[i] == 0x7f ? '?' : s[i];
    return out;
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

const char *type_name(uint32_t type)
{
    return type < uint32_t(nanovdb::GridType::End) ? nanovdb::toStr(nanovdb::GridType(type)) : "unknown";
}

std::string version_text(uint32_t v)
{
    return std::to_string(v >> 21) + "." + std::to_string((v >> 10) & 0x7ff) + "." +
           std::to_string(v & 0x3ff);
}

} // namespace volume_nvdb


extern "C" bool volume_nvdb_read(const char *path, const char *grid_name, VolumeGrid *out, Error *err)
{
    *out = VolumeGrid();
    long long size = 0;
    int fd = input_file_open(path, "a NanoVDB file", &size, err);
    if (fd < 0)
        return false;
    volume_nvdb::Reader r = {path, fd, uint64_t(size), err};
    bool ok = volume_nvdb::read_grid(r, grid_name, out);
    close(fd);
    return ok;
}
