// SPDX-License-Identifier: MIT
/* exr_read.c: RGB(A) EXR input, scanline or tiled (level 0), written by us or another tool. */
#include "io/image_io.h"

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "io/exr_common.h"

typedef struct {
    exr_context_t ctxt;
    const char *path;
    exr_attr_box2i_t data_window;
    int width, height;
    float *rgb;
    exr_decode_pipeline_t decoder;
    bool decoder_ready;
} ExrReader;

/* Points the decoder's R, G, B outputs at the chunk's place in the interleaved image; every other
 * channel (A, Z, ...) is left NULL, which the decoder skips. */
static void point_decoder_at(ExrReader *reader, int pixel_x, int pixel_y)
{
    float *origin =
        reader->rgb + ((size_t)pixel_y * (size_t)reader->width + (size_t)pixel_x) * RGB_CHANNELS;
    for (int i = 0; i < reader->decoder.channel_count; i++) {
        exr_coding_channel_info_t *channel = &reader->decoder.channels[i];
        int c = exr_rgb_index(channel->channel_name);
        channel->decode_to_ptr = c < 0 ? NULL : (uint8_t *)(origin + c);
        channel->user_pixel_stride = (int32_t)(sizeof(float) * RGB_CHANNELS);
        channel->user_line_stride = (int32_t)(sizeof(float) * RGB_CHANNELS * (size_t)reader->width);
        channel->user_bytes_per_element = (int16_t)sizeof(float);
        channel->user_data_type = EXR_PIXEL_FLOAT;
    }
}

/* Decodes one chunk (scanline block or tile) whose top-left pixel is (pixel_x, pixel_y) relative to
 * the data window. */
static bool exr_decode_chunk(ExrReader *reader, const exr_chunk_info_t *chunk, int pixel_x,
                             int pixel_y, Error *err)
{
    if (pixel_x < 0 || pixel_y < 0 || pixel_x + chunk->width > reader->width ||
        pixel_y + chunk->height > reader->height) {
        error_set(err, ERR_FILE_READ, reader->path, 0,
                  "%s: chunk at (%d, %d) lies outside the image", reader->path, pixel_x, pixel_y);
        return false;
    }
    bool ok;
    if (!reader->decoder_ready) {
        ok = exr_ok(exr_decoding_initialize(reader->ctxt, 0, chunk, &reader->decoder),
                    "exr_decoding_initialize", reader->path, ERR_FILE_READ, err);
        reader->decoder_ready = ok;
    } else {
        ok = exr_ok(exr_decoding_update(reader->ctxt, 0, chunk, &reader->decoder),
                    "exr_decoding_update", reader->path, ERR_FILE_READ, err);
    }
    if (!ok)
        return false;
    point_decoder_at(reader, pixel_x, pixel_y);
    /* Chosen per chunk: the best routine depends on the chunk (e.g. a short last block). */
    return exr_ok(exr_decoding_choose_default_routines(reader->ctxt, 0, &reader->decoder),
                  "exr_decoding_choose_default_routines", reader->path, ERR_FILE_READ, err) &&
           exr_ok(exr_decoding_run(reader->ctxt, 0, &reader->decoder), "exr_decoding_run",
                  reader->path, ERR_FILE_READ, err);
}

static bool exr_read_scanlines(ExrReader *reader, Error *err)
{
    int32_t lines_per_chunk = 0;
    if (!exr_ok(exr_get_scanlines_per_chunk(reader->ctxt, 0, &lines_per_chunk),
                "exr_get_scanlines_per_chunk", reader->path, ERR_FILE_READ, err))
        return false;
    for (int y = reader->data_window.min.y; y <= reader->data_window.max.y; y += lines_per_chunk) {
        exr_chunk_info_t chunk;
        if (!exr_ok(exr_read_scanline_chunk_info(reader->ctxt, 0, y, &chunk),
                    "exr_read_scanline_chunk_info", reader->path, ERR_FILE_READ, err) ||
            !exr_decode_chunk(reader, &chunk, chunk.start_x - reader->data_window.min.x,
                              chunk.start_y - reader->data_window.min.y, err))
            return false;
    }
    return true;
}

/* Reads level 0 of a tiled file (the full-resolution image of a mip or rip map). */
static bool exr_read_tiles(ExrReader *reader, Error *err)
{
    int32_t tile_width = 0, tile_height = 0, level_width = 0, level_height = 0;
    if (!exr_ok(exr_get_tile_sizes(reader->ctxt, 0, 0, 0, &tile_width, &tile_height),
                "exr_get_tile_sizes", reader->path, ERR_FILE_READ, err) ||
        !exr_ok(exr_get_level_sizes(reader->ctxt, 0, 0, 0, &level_width, &level_height),
                "exr_get_level_sizes", reader->path, ERR_FILE_READ, err))
        return false;
    int tiles_x = (level_width + tile_width - 1) / tile_width;
    int tiles_y = (level_height + tile_height - 1) / tile_height;
    for (int tile_y = 0; tile_y < tiles_y; tile_y++) {
        for (int tile_x = 0; tile_x < tiles_x; tile_x++) {
            exr_chunk_info_t chunk;
            if (!exr_ok(exr_read_tile_chunk_info(reader->ctxt, 0, tile_x, tile_y, 0, 0, &chunk),
                        "exr_read_tile_chunk_info", reader->path, ERR_FILE_READ, err) ||
                !exr_decode_chunk(reader, &chunk, tile_x * tile_width, tile_y * tile_height, err))
                return false;
        }
    }
    return true;
}

/* Checks that part 0 is a flat image with full-resolution R, G and B channels. */
static bool exr_check_layout(ExrReader *reader, exr_storage_t *storage, Error *err)
{
    const exr_attr_chlist_t *channels = NULL;
    if (!exr_ok(exr_get_storage(reader->ctxt, 0, storage), "exr_get_storage", reader->path,
                ERR_FILE_READ, err) ||
        !exr_ok(exr_get_data_window(reader->ctxt, 0, &reader->data_window), "exr_get_data_window",
                reader->path, ERR_FILE_READ, err) ||
        !exr_ok(exr_get_channels(reader->ctxt, 0, &channels), "exr_get_channels", reader->path,
                ERR_FILE_READ, err))
        return false;
    if (*storage != EXR_STORAGE_SCANLINE && *storage != EXR_STORAGE_TILED) {
        error_set(err, ERR_FILE_READ, reader->path, 0, "%s: deep EXR images are not supported",
                  reader->path);
        return false;
    }
    int found = 0;
    for (int i = 0; i < channels->num_channels; i++) {
        const exr_attr_chlist_entry_t *channel = &channels->entries[i];
        int c = exr_rgb_index(channel->name.str);
        if (c < 0)
            continue;
        if (channel->x_sampling != 1 || channel->y_sampling != 1) {
            error_set(err, ERR_FILE_READ, reader->path, 0,
                      "%s: channel %s is subsampled, which is not supported", reader->path,
                      channel->name.str);
            return false;
        }
        found |= 1 << c;
    }
    if (found != 7) {
        error_set(err, ERR_FILE_READ, reader->path, 0, "%s: no R, G and B channels in part 0",
                  reader->path);
        return false;
    }
    int64_t width = (int64_t)reader->data_window.max.x - reader->data_window.min.x + 1;
    int64_t height = (int64_t)reader->data_window.max.y - reader->data_window.min.y + 1;
    if (width <= 0 || height <= 0 || width * height > (int64_t)1 << 30) {
        error_set(err, ERR_TOO_LARGE, reader->path, 0, "%s: data window %lldx%lld is unusable",
                  reader->path, (long long)width, (long long)height);
        return false;
    }
    reader->width = (int)width;
    reader->height = (int)height;
    return true;
}

bool image_read_exr(const char *path, float **rgb, int *width, int *height, Error *err)
{
    *rgb = NULL;
    struct stat info;
    if (stat(path, &info) != 0) {
        error_set(err, ERR_FILE_MISSING, path, 0, "%s: %s", path, strerror(errno));
        return false;
    }
    ExrReader reader = {.path = path};
    exr_context_initializer_t init = exr_quiet_initializer();
    init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
    exr_storage_t storage = EXR_STORAGE_SCANLINE;
    bool ok = exr_ok(exr_start_read(&reader.ctxt, path, &init), "exr_start_read", path,
                     ERR_FILE_READ, err) &&
              exr_check_layout(&reader, &storage, err);
    if (ok) {
        /* calloc: pixels of a file with missing chunks would otherwise be uninitialised. */
        reader.rgb = calloc((size_t)reader.width * (size_t)reader.height * RGB_CHANNELS,
                            sizeof *reader.rgb);
        if (!reader.rgb) {
            error_set(err, ERR_TOO_LARGE, path, 0, "%s: out of memory for %dx%d pixels", path,
                      reader.width, reader.height);
            ok = false;
        }
    }
    if (ok)
        ok = storage == EXR_STORAGE_TILED ? exr_read_tiles(&reader, err)
                                          : exr_read_scanlines(&reader, err);
    if (reader.decoder_ready && !exr_ok(exr_decoding_destroy(reader.ctxt, &reader.decoder),
                                        "exr_decoding_destroy", path, ERR_FILE_READ, err))
        ok = false;
    if (reader.ctxt && !exr_ok(exr_finish(&reader.ctxt), "exr_finish", path, ERR_FILE_READ, err))
        ok = false;
    if (!ok) {
        free(reader.rgb);
        return false;
    }
    *rgb = reader.rgb;
    *width = reader.width;
    *height = reader.height;
    return true;
}
