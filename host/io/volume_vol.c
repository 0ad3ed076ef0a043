/* SPDX-License-Identifier: MIT */
/* volume_vol.c: Mitsuba 3's .vol grid files (src/render/volumegrid.cpp), little-endian:
 *   "VOL", version byte 3, int32 encoding (1 = float32), int32 xres, yres, zres, int32 channels,
 *   float32 bbox (xmin, ymin, zmin, xmax, ymax, zmax), then xres * yres * zres * channels float32,
 *   x fastest, then y, then z, channels innermost.
 * Only one float32 channel is read (a density). Every size is checked against the file's length
 * before anything is allocated, and the values are streamed one layer of bricks (8 z-slices) at a
 * time into the builder, so a grid never exists twice in memory. The grid spans the header's box,
 * as Mitsuba's gridvolume with use_grid_bbox (shared/DESIGN.md "Media"). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/shared_types.h"
#include "io/input_file.h"
#include "io/volume_grid_build.h"

#define VOL_HEADER_BYTES 48
#define VOL_FLOAT32 1

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float le_float(const unsigned char *p)
{
    uint32_t bits = le32(p);
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* Reads exactly size bytes at offset; false on a short read (the file shrank) or an error. */
static bool read_at(int fd, void *buf, size_t size, long long offset)
{
    size_t got = 0;
    while (got < size) {
        ssize_t n = pread(fd, (char *)buf + got, size - got, (off_t)(offset + (long long)got));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        got += (size_t)n;
    }
    return true;
}

static const char *encoding_name(int32_t encoding)
{
    switch (encoding) {
    case 1: return "float32";
    case 2: return "float16";
    case 3: return "uint8";
    case 4: return "quantized directions";
    default: return "unknown";
    }
}

typedef struct {
    int32_t encoding, res[3], channels;
    float bbox[6];
} VolHeader;

/* The header's fields, each checked; false with err set. */
static bool parse_header(const char *path, const unsigned char *h, VolHeader *out, Error *err)
{
    if (memcmp(h, "VOL", 3) != 0) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: not a Mitsuba .vol file (no 'VOL' at its start)", path);
        return false;
    }
    if (h[3] != 3) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: .vol version %u (pt reads version 3)", path, h[3]);
        return false;
    }
    out->encoding = (int32_t)le32(h + 4);
    for (int a = 0; a < 3; a++)
        out->res[a] = (int32_t)le32(h + 8 + 4 * a);
    out->channels = (int32_t)le32(h + 20);
    for (int i = 0; i < 6; i++)
        out->bbox[i] = le_float(h + 24 + 4 * i);
    if (out->encoding != VOL_FLOAT32) {
        error_set(err, ERR_FILE_READ, path, 0,
                  "%s: .vol encoding %d (%s); pt reads only encoding 1 (float32)", path,
                  out->encoding, encoding_name(out->encoding));
        return false;
    }
    if (out->channels != 1) {
        error_set(err, ERR_FILE_READ, path, 0,
                  "%s: .vol with %d channels; a density grid has exactly 1", path, out->channels);
        return false;
    }
    if (out->res[0] <= 0 || out->res[1] <= 0 || out->res[2] <= 0) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: .vol resolution %d x %d x %d (each must be >= 1)",
                  path, out->res[0], out->res[1], out->res[2]);
        return false;
    }
    for (int a = 0; a < 3; a++)
        if (!isfinite(out->bbox[a]) || !isfinite(out->bbox[a + 3]) ||
            !(out->bbox[a] < out->bbox[a + 3])) {
            error_set(err, ERR_FILE_READ, path, 0,
                      "%s: .vol bounding box [%g, %g] along %c is empty or not finite", path,
                      (double)out->bbox[a], (double)out->bbox[a + 3], "xyz"[a]);
            return false;
        }
    return true;
}

/* Streams the values, one layer of bricks at a time, into the builder. */
static bool read_values(int fd, VolumeGridBuilder *b, Error *err)
{
    const VolumeGrid *g = b->grid;
    const size_t slice = (size_t)g->res[0] * g->res[1];
    const uint32_t layer_slices = g->res[2] < MEDIUM_BRICK ? g->res[2] : MEDIUM_BRICK;
    float *layer = malloc(slice * layer_slices * sizeof(float));
    if (!layer) {
        error_set(err, ERR_OUT_OF_MEMORY, b->path, 0, "%s: out of memory for %zu voxels", b->path,
                  slice * layer_slices);
        return false;
    }
    bool ok = true;
    for (uint32_t z0 = 0; ok && z0 < g->res[2]; z0 += MEDIUM_BRICK) {
        uint32_t count = g->res[2] - z0 < MEDIUM_BRICK ? g->res[2] - z0 : MEDIUM_BRICK;
        size_t n = slice * count;
        if (!read_at(fd, layer, n * sizeof(float),
                     VOL_HEADER_BYTES + (long long)(z0 * slice * sizeof(float)))) {
            error_set(err, ERR_FILE_READ, b->path, 0, "%s: read failed at slice %u (file changed?)",
                      b->path, z0);
            ok = false;
            break;
        }
        /* Little-endian bytes to floats, in place (each value read before it is written). */
        for (size_t i = 0; i < n; i++)
            layer[i] = le_float((const unsigned char *)(layer + i));
        ok = volume_grid_put_layer(b, layer, z0, count, err);
    }
    free(layer);
    return ok;
}

/* Opens path and reads its checked header; returns the descriptor (-1 with err set). */
static int open_vol(const char *path, long long *file_size, VolHeader *h, Error *err)
{
    int fd = input_file_open(path, "a .vol grid", file_size, err);
    if (fd < 0)
        return -1;
    unsigned char header[VOL_HEADER_BYTES];
    if (*file_size < VOL_HEADER_BYTES || !read_at(fd, header, sizeof header, 0)) {
        error_set(err, ERR_FILE_READ, path, 0, "%s: truncated: %lld bytes, shorter than a .vol header (%d)",
                  path, *file_size, VOL_HEADER_BYTES);
    } else if (parse_header(path, header, h, err)) {
        return fd;
    }
    close(fd);
    return -1;
}

bool volume_vol_box(const char *path, double box[6], Error *err)
{
    long long file_size = 0;
    VolHeader h;
    int fd = open_vol(path, &file_size, &h, err);
    if (fd < 0)
        return false;
    close(fd);
    for (int i = 0; i < 6; i++)
        box[i] = h.bbox[i];
    return true;
}

bool volume_vol_read(const char *path, const char *grid_name, VolumeGrid *out, Error *err)
{
    memset(out, 0, sizeof *out);
    if (grid_name[0] && strcmp(grid_name, "density") != 0) {
        error_set(err, ERR_JSON_VALUE, path, 0,
                  "%s: a .vol file holds one grid, 'density'; there is no grid '%s'", path, grid_name);
        return false;
    }
    long long file_size = 0;
    VolHeader h;
    int fd = open_vol(path, &file_size, &h, err);
    if (fd < 0)
        return false;
    VolumeGridBuilder b;
    bool ok = false;
    if (volume_grid_begin(&b, out, (const uint32_t[3]){(uint32_t)h.res[0], (uint32_t)h.res[1],
                                                       (uint32_t)h.res[2]},
                          path, err)) {
        /* Within 2^31 voxels: the byte count below cannot overflow. */
        long long need = VOL_HEADER_BYTES + (long long)h.res[0] * h.res[1] * h.res[2] * 4;
        if (file_size < need)
            error_set(err, ERR_FILE_READ, path, 0,
                      "%s: truncated: %d x %d x %d voxels need %lld bytes, the file has %lld", path,
                      h.res[0], h.res[1], h.res[2], need, file_size);
        else
            ok = read_values(fd, &b, err) && volume_grid_finish(&b, err);
        if (!ok)
            volume_grid_free(out);
    }
    close(fd);
    if (ok) {
        /* [0, res] onto the header's box: the finish kept the unit-cube map's zeros elsewhere. */
        for (int a = 0; a < 3; a++) {
            out->index_to_object[5 * a] = ((double)h.bbox[a + 3] - h.bbox[a]) / out->res[a];
            out->index_to_object[4 * a + 3] = h.bbox[a];
        }
    }
    return ok;
}
