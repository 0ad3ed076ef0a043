// SPDX-License-Identifier: MIT
/* exr_write.c: film output through OpenEXR's C API (OpenEXRCore) as single-part scanline images
 * with 32-bit float channels R, G, B and ZIP compression: lossless, so renders and reference
 * images round-trip bit-exactly, and every EXR reader supports it. ZIP deflates 16-line blocks,
 * which beats ZIPS's single lines on smooth images (40% vs 52% of raw on the Kerner HDR photo); on
 * noisy 32-bit renders no lossless codec saves more than a few percent. */
#include "io/image_io.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>

#include "base/fs.h"
#include "io/exr_common.h"
#include "io/image_write.h"

/* Defines the header: one scanline part, data window = display window = the whole image. */
static bool exr_define_header(exr_context_t ctxt, int *part, int width, int height,
                              const char *path, Error *err)
{
    static const char *const channel_names[RGB_CHANNELS] = {"R", "G", "B"};
    exr_attr_box2i_t window = {.min = {.x = 0, .y = 0}, .max = {.x = width - 1, .y = height - 1}};
    exr_attr_v2f_t screen_center = {.x = 0.0f, .y = 0.0f};
    if (!exr_ok(exr_add_part(ctxt, NULL, EXR_STORAGE_SCANLINE, part), "exr_add_part", path,
                ERR_OUTPUT, err) ||
        !exr_ok(exr_initialize_required_attr(ctxt, *part, &window, &window, 1.0f, &screen_center,
                                             1.0f, EXR_LINEORDER_INCREASING_Y,
                                             EXR_COMPRESSION_ZIP),
                "exr_initialize_required_attr", path, ERR_OUTPUT, err) ||
        !exr_ok(exr_set_compression(ctxt, *part, EXR_COMPRESSION_ZIP), "exr_set_compression",
                path, ERR_OUTPUT, err))
        return false;
    for (int c = 0; c < RGB_CHANNELS; c++) {
        /* Perceptual treatment only matters to the lossy B44 codecs. */
        if (!exr_ok(exr_add_channel(ctxt, *part, channel_names[c], EXR_PIXEL_FLOAT,
                                    EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
                    "exr_add_channel", path, ERR_OUTPUT, err))
            return false;
    }
    return exr_ok(exr_write_header(ctxt), "exr_write_header", path, ERR_OUTPUT, err);
}

/* Copies the chunk's lines into one plane per channel, non-finite values replaced by 0: this is
 * the last guard before the file, and planar input is the encoder's fast path. */
static void fill_chunk_planes(float *planes, size_t plane_size, const float *rgb, int width,
                              int first_line, int line_count)
{
    for (int line = 0; line < line_count; line++) {
        const float *row = rgb + ((size_t)(first_line + line) * (size_t)width) * RGB_CHANNELS;
        for (int x = 0; x < width; x++) {
            size_t pixel = (size_t)line * (size_t)width + (size_t)x;
            for (int c = 0; c < RGB_CHANNELS; c++)
                planes[c * plane_size + pixel] = image_finite_or_zero(row[x * RGB_CHANNELS + c]);
        }
    }
}

/* Encodes and writes every scanline chunk of part 0. */
static bool exr_write_chunks(exr_context_t ctxt, int part, const float *rgb, int width, int height,
                             const char *path, Error *err)
{
    int32_t lines_per_chunk = 0;
    if (!exr_ok(exr_get_scanlines_per_chunk(ctxt, part, &lines_per_chunk),
                "exr_get_scanlines_per_chunk", path, ERR_OUTPUT, err))
        return false;
    size_t plane_size = (size_t)width * (size_t)lines_per_chunk;
    float *planes = malloc(plane_size * RGB_CHANNELS * sizeof *planes);
    if (!planes) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: out of memory for a %dx%d chunk", path, width,
                  lines_per_chunk);
        return false;
    }
    exr_encode_pipeline_t encoder = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool encoder_ready = false;
    bool ok = true;
    for (int y = 0; ok && y < height; y += lines_per_chunk) {
        exr_chunk_info_t chunk;
        bool first_chunk = !encoder_ready;
        ok = exr_ok(exr_write_scanline_chunk_info(ctxt, part, y, &chunk),
                    "exr_write_scanline_chunk_info", path, ERR_OUTPUT, err);
        if (ok && first_chunk) {
            ok = exr_ok(exr_encoding_initialize(ctxt, part, &chunk, &encoder),
                        "exr_encoding_initialize", path, ERR_OUTPUT, err);
            encoder_ready = ok;
        } else if (ok) {
            ok = exr_ok(exr_encoding_update(ctxt, part, &chunk, &encoder), "exr_encoding_update",
                        path, ERR_OUTPUT, err);
        }
        if (!ok)
            break;
        fill_chunk_planes(planes, plane_size, rgb, width, chunk.start_y, chunk.height);
        for (int i = 0; i < encoder.channel_count; i++) {
            exr_coding_channel_info_t *channel = &encoder.channels[i];
            int c = exr_rgb_index(channel->channel_name);
            channel->encode_from_ptr = (const uint8_t *)(planes + (size_t)c * plane_size);
            channel->user_pixel_stride = (int32_t)sizeof(float);
            channel->user_line_stride = (int32_t)(sizeof(float) * (size_t)width);
            channel->user_bytes_per_element = (int16_t)sizeof(float);
            channel->user_data_type = EXR_PIXEL_FLOAT;
        }
        /* The pack routine depends only on the channel layout, the same for every chunk. */
        if (first_chunk)
            ok = exr_ok(exr_encoding_choose_default_routines(ctxt, part, &encoder),
                        "exr_encoding_choose_default_routines", path, ERR_OUTPUT, err);
        ok = ok && exr_ok(exr_encoding_run(ctxt, part, &encoder), "exr_encoding_run", path,
                          ERR_OUTPUT, err);
    }
    if (encoder_ready && !exr_ok(exr_encoding_destroy(ctxt, &encoder), "exr_encoding_destroy",
                                 path, ERR_OUTPUT, err))
        ok = false;
    free(planes);
    return ok;
}

static bool exr_write_file(const char *temp, const char *path, const float *rgb, int width,
                           int height, Error *err)
{
    exr_context_initializer_t init = exr_quiet_initializer();
    exr_context_t ctxt = NULL;
    /* We manage the temporary name ourselves, so OpenEXR writes the file it is given. */
    bool ok = exr_ok(exr_start_write(&ctxt, temp, EXR_WRITE_FILE_DIRECTLY, &init),
                     "exr_start_write", path, ERR_OUTPUT, err);
    int part = 0;
    ok = ok && exr_define_header(ctxt, &part, width, height, path, err);
    ok = ok && exr_write_chunks(ctxt, part, rgb, width, height, path, err);
    /* exr_finish writes the chunk offset table, so its result decides whether the file is whole. */
    if (ctxt && !exr_ok(exr_finish(&ctxt), "exr_finish", path, ERR_OUTPUT, err))
        ok = false;
    return ok;
}

bool image_write_exr(const char *path, const float *rgb, int width, int height, Error *err)
{
    if (!image_check_args(path, rgb, width, height, err) || !fs_check_writable(path, err))
        return false;
    char temp[PATH_MAX];
    fs_temp_path(path, temp, sizeof temp);
    bool written = exr_write_file(temp, path, rgb, width, height, err);
    return fs_finish_atomic_write(temp, path, written, err);
}
