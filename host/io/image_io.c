// SPDX-License-Identifier: MIT
/* image_io.c: film output and EXR input.
 *
 * EXR files are written through OpenEXR's C API (OpenEXRCore) as single-part scanline images with
 * 32-bit float channels R, G, B and ZIP compression: lossless, so renders and reference images
 * round-trip bit-exactly, and every EXR reader supports it. ZIP deflates 16-line blocks, which
 * beats ZIPS's single lines on smooth images (40% vs 52% of raw on the Kerner HDR photo); on noisy
 * 32-bit renders no lossless codec saves more than a few percent.
 *
 * Every file is written to "<path>.tmp-<pid>" in the same folder, flushed to disk and renamed over
 * the target, so an interrupted or failed write never leaves a half-written file at `path`. */
#include "io/image_io.h"
#include "io/display_curve.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <openexr.h>
#include <stb_image_write.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum { RGB_CHANNELS = 3 };

/* ---- OpenEXR error reporting ------------------------------------------------------------- */

/* OpenEXR reports the detail of a failure (e.g. the strerror of a failed open) through a callback
 * and would print it to stderr by default; keep the latest one so the Error can carry it. */
static _Thread_local char exr_last_message[256];

static void exr_capture_message(exr_const_context_t ctxt, exr_result_t code, const char *message)
{
    (void)ctxt;
    (void)code;
    snprintf(exr_last_message, sizeof exr_last_message, "%s", message ? message : "");
}

static exr_context_initializer_t exr_quiet_initializer(void)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = exr_capture_message;
    exr_last_message[0] = '\0';
    return init;
}

/* Turns a failed exr_* call into an Error naming the file, the step, the error code and detail. */
static bool exr_ok(exr_result_t result, const char *step, const char *path, ErrorCode code,
                   Error *err)
{
    if (result == EXR_ERR_SUCCESS)
        return true;
    const char *detail =
        exr_last_message[0] ? exr_last_message : exr_get_default_error_message(result);
    error_set(err, code, path, 0, "%s: %s failed: %s (%s)", path, step,
              exr_get_error_code_as_string(result), detail);
    return false;
}

/* ---- shared helpers ---------------------------------------------------------------------- */

static float finite_or_zero(float value) { return isfinite(value) ? value : 0.0f; }

static bool check_image_args(const char *path, const float *rgb, int width, int height, Error *err)
{
    if (!rgb || width <= 0 || height <= 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot write an empty image (%dx%d)",
                  path ? path : "(null)", width, height);
        return false;
    }
    return true;
}

/* Splits off the folder of `path` ("." when it has none). */
static bool folder_of(const char *path, char *folder, size_t size)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return snprintf(folder, size, ".") < (int)size;
    size_t length = slash == path ? 1 : (size_t)(slash - path);
    if (length >= size)
        return false;
    memcpy(folder, path, length);
    folder[length] = '\0';
    return true;
}

bool image_check_writable(const char *path, Error *err)
{
    if (!path || !path[0]) {
        error_set(err, ERR_OUTPUT, "", 0, "output path is empty");
        return false;
    }
    char folder[PATH_MAX];
    /* Room for the ".tmp-<pid>" suffix of the temporary file. */
    if (strlen(path) + 32 >= sizeof folder || !folder_of(path, folder, sizeof folder)) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: output path is too long", path);
        return false;
    }
    struct stat info;
    size_t length = strlen(path);
    if (path[length - 1] == '/' || (stat(path, &info) == 0 && S_ISDIR(info.st_mode))) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: output path is a directory", path);
        return false;
    }
    if (stat(folder, &info) != 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: folder %s does not exist (%s)", path, folder,
                  strerror(errno));
        return false;
    }
    if (!S_ISDIR(info.st_mode)) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: %s is not a folder", path, folder);
        return false;
    }
    if (access(folder, W_OK | X_OK) != 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: folder %s is not writable (%s)", path, folder,
                  strerror(errno));
        return false;
    }
    return true;
}

static void temp_path_for(const char *path, char *temp, size_t size)
{
    snprintf(temp, size, "%s.tmp-%ld", path, (long)getpid());
}

/* Flushes the finished temporary file to disk, then renames it over the target: rename() is
 * atomic, and the flush keeps a crash from leaving a renamed but empty file. */
static bool commit_temp_file(const char *temp, const char *path, Error *err)
{
    int fd = open(temp, O_RDONLY);
    if (fd < 0 || fsync(fd) != 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot flush %s (%s)", path, temp,
                  strerror(errno));
        if (fd >= 0)
            close(fd);
        return false;
    }
    close(fd);
    if (rename(temp, path) != 0) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot rename %s over it (%s)", path, temp,
                  strerror(errno));
        return false;
    }
    return true;
}

static void (*g_before_rename)(void);
void image_set_before_rename_hook(void (*hook)(void)) { g_before_rename = hook; }

/* Ends an atomic write: commit the temporary file when writing it worked, remove it otherwise. */
static bool finish_atomic_write(const char *temp, const char *path, bool written, Error *err)
{
    if (written && g_before_rename)
        g_before_rename();
    if (written && commit_temp_file(temp, path, err))
        return true;
    unlink(temp);
    return false;
}

/* ---- EXR output -------------------------------------------------------------------------- */

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

static int rgb_index_of_channel(const char *name)
{
    if (strcmp(name, "R") == 0)
        return 0;
    if (strcmp(name, "G") == 0)
        return 1;
    if (strcmp(name, "B") == 0)
        return 2;
    return -1;
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
                planes[c * plane_size + pixel] = finite_or_zero(row[x * RGB_CHANNELS + c]);
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
            int c = rgb_index_of_channel(channel->channel_name);
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
    if (!check_image_args(path, rgb, width, height, err) || !image_check_writable(path, err))
        return false;
    char temp[PATH_MAX];
    temp_path_for(path, temp, sizeof temp);
    bool written = exr_write_file(temp, path, rgb, width, height, err);
    return finish_atomic_write(temp, path, written, err);
}

/* ---- PNG output -------------------------------------------------------------------------- */

static unsigned char srgb8_from_linear(float linear)
{
    return (unsigned char)lrintf(display_srgb_from_linear(linear) * 255.0f);
}

typedef struct {
    FILE *file;
    bool failed;
} PngSink;

/* stbi_write_png ignores fwrite errors; writing through a callback lets us see them. */
static void png_sink_write(void *context, void *data, int size)
{
    PngSink *sink = context;
    if (fwrite(data, 1, (size_t)size, sink->file) != (size_t)size)
        sink->failed = true;
}

static bool png_write_file(const char *temp, const char *path, const unsigned char *pixels,
                           int width, int height, Error *err)
{
    PngSink sink = {.file = fopen(temp, "wb"), .failed = false};
    if (!sink.file) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: cannot create %s (%s)", path, temp,
                  strerror(errno));
        return false;
    }
    int encoded = stbi_write_png_to_func(png_sink_write, &sink, width, height, RGB_CHANNELS,
                                         pixels, width * RGB_CHANNELS);
    int saved_errno = errno;
    bool closed = fclose(sink.file) == 0;
    if (!encoded || sink.failed || !closed) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: PNG write failed (%s)", path,
                  encoded ? strerror(saved_errno) : "encoder error");
        return false;
    }
    return true;
}

bool image_write_png(const char *path, const float *rgb, int width, int height, float exposure,
                     Error *err)
{
    if (!check_image_args(path, rgb, width, height, err))
        return false;
    if (!isfinite(exposure)) {
        error_set(err, ERR_USAGE, path, 0, "%s: exposure %g is not finite", path, exposure);
        return false;
    }
    /* stb_image_write measures the image in int bytes. */
    size_t value_count = (size_t)width * (size_t)height * RGB_CHANNELS;
    if (value_count / (size_t)height / RGB_CHANNELS != (size_t)width || value_count > INT_MAX / 2) {
        error_set(err, ERR_TOO_LARGE, path, 0, "%s: %dx%d is too large for PNG output", path,
                  width, height);
        return false;
    }
    if (!image_check_writable(path, err))
        return false;
    unsigned char *pixels = malloc(value_count);
    if (!pixels) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: out of memory for %dx%d pixels", path, width,
                  height);
        return false;
    }
    float scale = exp2f(exposure);
    for (size_t i = 0; i < value_count; i++)
        pixels[i] = srgb8_from_linear(finite_or_zero(rgb[i]) * scale);
    char temp[PATH_MAX];
    temp_path_for(path, temp, sizeof temp);
    bool written = png_write_file(temp, path, pixels, width, height, err);
    free(pixels);
    return finish_atomic_write(temp, path, written, err);
}

/* ---- EXR input --------------------------------------------------------------------------- */

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
        int c = rgb_index_of_channel(channel->channel_name);
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
        int c = rgb_index_of_channel(channel->name.str);
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
