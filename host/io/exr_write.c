// SPDX-License-Identifier: MIT
/* exr_write.c: film output through OpenEXR's C API (OpenEXRCore) as single-part scanline images
 * with 32-bit float channels and ZIP compression: lossless, so renders and reference images
 * round-trip bit-exactly, and every EXR reader supports it. ZIP deflates 16-line blocks, which
 * beats ZIPS's single lines on smooth images (40% vs 52% of raw on the Kerner HDR photo); on noisy
 * 32-bit renders no lossless codec saves more than a few percent. The beauty is R, G, B; each
 * layer adds "<layer>.<letter>" channels (OpenEXR keeps the channel list sorted by name, so the
 * file lists them alphabetically); attributes go into the header. */
#include "io/image_io.h"

#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fs.h"
#include "base/parallel_for.h"
#include "io/exr_common.h"
#include "io/image_write.h"

/* Longer names are legal in OpenEXR 2+, but 31 bytes keeps the file readable by OpenEXR 1.x. */
#define EXR_CHANNEL_NAME_MAX 32

/* Where one channel's values are: pixels[stride * pixel]. */
typedef struct {
    char name[EXR_CHANNEL_NAME_MAX];
    const float *pixels;
    int stride;
} ChannelSource;

/* The beauty's R, G, B and every layer's channels; false (ERR_OUTPUT) for a name that is empty,
 * too long or lacks its pixels. *sources is malloc'ed. */
static bool collect_channels(const ExrImage *image, const char *path, ChannelSource **sources,
                             int *count, Error *err)
{
    int total = RGB_CHANNELS + (image->alpha ? 1 : 0);
    for (int l = 0; l < image->layer_count; l++)
        total += (int)strlen(image->layers[l].channels ? image->layers[l].channels : "");
    *sources = calloc((size_t)total, sizeof **sources);
    if (!*sources) {
        error_set(err, ERR_OUTPUT, path, 0, "%s: out of memory for %d channels", path, total);
        return false;
    }
    static const char *const beauty[RGB_CHANNELS] = {"R", "G", "B"};
    int n = 0;
    for (int c = 0; c < RGB_CHANNELS; c++, n++) {
        (*sources)[n] = (ChannelSource){.pixels = image->rgb + c, .stride = RGB_CHANNELS};
        snprintf((*sources)[n].name, EXR_CHANNEL_NAME_MAX, "%s", beauty[c]);
    }
    if (image->alpha) {
        (*sources)[n] = (ChannelSource){.pixels = image->alpha, .stride = 1};
        snprintf((*sources)[n++].name, EXR_CHANNEL_NAME_MAX, "A");
    }
    for (int l = 0; l < image->layer_count; l++) {
        const ImageLayer *layer = &image->layers[l];
        const char *letters = layer->channels ? layer->channels : "";
        int stride = (int)strlen(letters);
        if (!layer->name || !layer->name[0] || !layer->pixels || stride == 0 ||
            strlen(layer->name) + 2 >= EXR_CHANNEL_NAME_MAX) {
            error_set(err, ERR_OUTPUT, path, 0, "%s: layer %d ('%s') has no name, channels or pixels",
                      path, l, layer->name ? layer->name : "");
            free(*sources);
            return false;
        }
        for (int c = 0; c < stride; c++, n++) {
            (*sources)[n] = (ChannelSource){.pixels = layer->pixels + c, .stride = stride};
            snprintf((*sources)[n].name, EXR_CHANNEL_NAME_MAX, "%s.%c", layer->name, letters[c]);
        }
    }
    *count = n;
    return true;
}

static bool exr_set_attribute(exr_context_t ctxt, int part, const ImageAttribute *a,
                              const char *path, Error *err)
{
    exr_result_t result;
    switch (a->type) {
    case IMAGE_ATTR_INT:
        result = exr_attr_set_int(ctxt, part, a->name, a->int_value);
        break;
    case IMAGE_ATTR_FLOAT:
        result = exr_attr_set_float(ctxt, part, a->name, a->float_value);
        break;
    default:
        result = exr_attr_set_string(ctxt, part, a->name, a->string_value ? a->string_value : "");
        break;
    }
    char step[128];
    snprintf(step, sizeof step, "setting header attribute '%s'", a->name);
    return exr_ok(result, step, path, ERR_OUTPUT, err);
}

/* Defines the header: one scanline part, data window = display window = the whole image, the
 * channels and the attributes. */
static bool exr_define_header(exr_context_t ctxt, int *part, const ExrImage *image,
                              const ChannelSource *sources, int channel_count, const char *path,
                              Error *err)
{
    exr_attr_box2i_t window = {.min = {.x = 0, .y = 0},
                               .max = {.x = image->width - 1, .y = image->height - 1}};
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
    for (int c = 0; c < channel_count; c++) {
        /* Perceptual treatment only matters to the lossy B44 codecs. */
        if (!exr_ok(exr_add_channel(ctxt, *part, sources[c].name, EXR_PIXEL_FLOAT,
                                    EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1),
                    "exr_add_channel", path, ERR_OUTPUT, err))
            return false;
    }
    for (int a = 0; a < image->attribute_count; a++)
        if (!exr_set_attribute(ctxt, *part, &image->attributes[a], path, err))
            return false;
    return exr_ok(exr_write_header(ctxt), "exr_write_header", path, ERR_OUTPUT, err);
}

/* Copies the chunk's lines into one plane per channel, non-finite values replaced by 0: this is
 * the last guard before the file, and planar input is the encoder's fast path. */
static void fill_chunk_planes(float *planes, size_t plane_size, const ChannelSource *sources,
                              int channel_count, int width, int first_line, int line_count)
{
    for (int c = 0; c < channel_count; c++) {
        const ChannelSource *source = &sources[c];
        for (int line = 0; line < line_count; line++) {
            size_t row = (size_t)(first_line + line) * (size_t)width;
            float *plane = planes + (size_t)c * plane_size + (size_t)line * (size_t)width;
            for (int x = 0; x < width; x++)
                plane[x] = image_finite_or_zero(
                    source->pixels[(row + (size_t)x) * (size_t)source->stride]);
        }
    }
}

static int channel_source_index(const ChannelSource *sources, int channel_count, const char *name)
{
    for (int c = 0; c < channel_count; c++)
        if (!strcmp(sources[c].name, name))
            return c;
    return -1;
}

/* Chunks are encoded a batch at a time on the host's cores (base/parallel_for.h) and written in
 * order by the calling thread. OpenEXRCore's encode pipeline locks the file only to pack a chunk,
 * so compression (zlib: most of the time) runs in parallel; its write step is replaced by a copy
 * into the chunk's slot. The bytes are the serial writer's: each chunk compresses the same way
 * whichever thread does it. A batch bounds the memory held (32 chunks of 16 lines). */
#define EXR_CHUNKS_PER_BATCH 32

typedef struct {
    exr_chunk_info_t info;
    void *data;           /* the compressed (or packed, if smaller) bytes, malloc'ed */
    uint64_t size;
    exr_result_t result;
    const char *failed;   /* the OpenEXRCore call that failed, NULL if none */
    const char *missing_channel; /* a channel the encoder lists that was never added */
} ChunkSlot;

typedef struct {
    exr_context_t ctxt;
    int part;
    const ChannelSource *sources;
    int channel_count, width;
    int32_t lines_per_chunk;
    ChunkSlot *slots; /* the batch's */
} ChunkBatch;

/* The pipeline's write step: keep the bytes for the ordered write. */
static exr_result_t keep_chunk(exr_encode_pipeline_t *encoder)
{
    ChunkSlot *slot = encoder->encoding_user_data;
    slot->data = malloc(encoder->compressed_bytes ? encoder->compressed_bytes : 1);
    if (!slot->data)
        return EXR_ERR_OUT_OF_MEMORY;
    memcpy(slot->data, encoder->compressed_buffer, encoder->compressed_bytes);
    slot->size = encoder->compressed_bytes;
    return EXR_ERR_SUCCESS;
}

/* Points the encoder's channels at the chunk's planes; false when it lists an unknown channel. */
static bool bind_channels(exr_encode_pipeline_t *encoder, const ChunkBatch *b, const float *planes,
                          size_t plane_size, ChunkSlot *slot)
{
    for (int i = 0; i < encoder->channel_count; i++) {
        exr_coding_channel_info_t *channel = &encoder->channels[i];
        int c = channel_source_index(b->sources, b->channel_count, channel->channel_name);
        if (c < 0) {
            slot->missing_channel = channel->channel_name;
            return false;
        }
        channel->encode_from_ptr = (const uint8_t *)(planes + (size_t)c * plane_size);
        channel->user_pixel_stride = (int32_t)sizeof(float);
        channel->user_line_stride = (int32_t)(sizeof(float) * (size_t)b->width);
        channel->user_bytes_per_element = (int16_t)sizeof(float);
        channel->user_data_type = EXR_PIXEL_FLOAT;
    }
    return true;
}

/* parallel_for body: encodes slots [begin, end) of the batch with one pipeline. */
static void encode_chunk_range(void *ctx, size_t begin, size_t end)
{
    const ChunkBatch *b = ctx;
    size_t plane_size = (size_t)b->width * (size_t)b->lines_per_chunk;
    float *planes = malloc(plane_size * (size_t)b->channel_count * sizeof *planes);
    exr_encode_pipeline_t encoder = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool ready = false;
    for (size_t k = begin; k < end; k++) {
        ChunkSlot *slot = &b->slots[k];
        if (!planes) {
            slot->result = EXR_ERR_OUT_OF_MEMORY, slot->failed = "malloc";
            continue;
        }
        slot->failed = ready ? "exr_encoding_update" : "exr_encoding_initialize";
        slot->result = ready ? exr_encoding_update(b->ctxt, b->part, &slot->info, &encoder)
                             : exr_encoding_initialize(b->ctxt, b->part, &slot->info, &encoder);
        if (slot->result != EXR_ERR_SUCCESS)
            break;
        fill_chunk_planes(planes, plane_size, b->sources, b->channel_count, b->width,
                          slot->info.start_y, slot->info.height);
        if (!bind_channels(&encoder, b, planes, plane_size, slot))
            break;
        /* The pack routine depends only on the channel layout, the same for every chunk. */
        if (!ready) {
            slot->failed = "exr_encoding_choose_default_routines";
            slot->result = exr_encoding_choose_default_routines(b->ctxt, b->part, &encoder);
            if (slot->result != EXR_ERR_SUCCESS)
                break;
            ready = true;
        }
        encoder.yield_until_ready_fn = NULL; /* no file access here: the caller writes */
        encoder.write_fn = keep_chunk;
        encoder.encoding_user_data = slot;
        slot->failed = "exr_encoding_run";
        slot->result = exr_encoding_run(b->ctxt, b->part, &encoder);
        if (slot->result != EXR_ERR_SUCCESS)
            break;
        slot->failed = NULL;
    }
    if (ready || encoder.channels)
        exr_encoding_destroy(b->ctxt, &encoder);
    free(planes);
}

/* Encodes and writes every scanline chunk of the part. */
static bool exr_write_chunks(exr_context_t ctxt, int part, const ChannelSource *sources,
                             int channel_count, int width, int height, const char *path,
                             Error *err)
{
    int32_t lines_per_chunk = 0;
    if (!exr_ok(exr_get_scanlines_per_chunk(ctxt, part, &lines_per_chunk),
                "exr_get_scanlines_per_chunk", path, ERR_OUTPUT, err))
        return false;
    ChunkSlot slots[EXR_CHUNKS_PER_BATCH];
    ChunkBatch batch = {.ctxt = ctxt, .part = part, .sources = sources,
                        .channel_count = channel_count, .width = width,
                        .lines_per_chunk = lines_per_chunk, .slots = slots};
    bool ok = true;
    for (int y0 = 0; ok && y0 < height; y0 += EXR_CHUNKS_PER_BATCH * lines_per_chunk) {
        size_t count = 0;
        for (int y = y0; ok && y < height && count < EXR_CHUNKS_PER_BATCH; y += lines_per_chunk) {
            memset(&slots[count], 0, sizeof slots[count]);
            slots[count].failed = "exr_encoding_run"; /* until its range has run */
            slots[count].result = EXR_ERR_UNKNOWN;
            ok = exr_ok(exr_write_scanline_chunk_info(ctxt, part, y, &slots[count].info),
                        "exr_write_scanline_chunk_info", path, ERR_OUTPUT, err);
            count++;
        }
        if (ok)
            parallel_for(count, 1, encode_chunk_range, &batch);
        for (size_t k = 0; k < count; k++) {
            ChunkSlot *slot = &slots[k];
            if (ok && slot->missing_channel) {
                error_set(err, ERR_OUTPUT, path, 0, "%s: the encoder lists channel '%s', which "
                          "was never added", path, slot->missing_channel);
                ok = false;
            } else if (ok && slot->failed) {
                ok = exr_ok(slot->result, slot->failed, path, ERR_OUTPUT, err);
            }
            ok = ok && exr_ok(exr_write_scanline_chunk(ctxt, part, slot->info.start_y, slot->data,
                                                       slot->size),
                              "exr_write_scanline_chunk", path, ERR_OUTPUT, err);
            free(slot->data);
        }
    }
    return ok;
}

static bool exr_write_file(const char *temp, const char *path, const ExrImage *image,
                           const ChannelSource *sources, int channel_count, Error *err)
{
    exr_context_initializer_t init = exr_quiet_initializer();
    exr_context_t ctxt = NULL;
    /* We manage the temporary name ourselves, so OpenEXR writes the file it is given. */
    bool ok = exr_ok(exr_start_write(&ctxt, temp, EXR_WRITE_FILE_DIRECTLY, &init),
                     "exr_start_write", path, ERR_OUTPUT, err);
    int part = 0;
    ok = ok && exr_define_header(ctxt, &part, image, sources, channel_count, path, err);
    ok = ok && exr_write_chunks(ctxt, part, sources, channel_count, image->width, image->height,
                                path, err);
    /* exr_finish writes the chunk offset table, so its result decides whether the file is whole. */
    if (ctxt && !exr_ok(exr_finish(&ctxt), "exr_finish", path, ERR_OUTPUT, err))
        ok = false;
    return ok;
}

bool image_write_exr_layers(const char *path, const ExrImage *image, Error *err)
{
    if (!image_check_args(path, image->rgb, image->width, image->height, err) ||
        !fs_check_writable(path, err))
        return false;
    ChannelSource *sources = NULL;
    int channel_count = 0;
    if (!collect_channels(image, path, &sources, &channel_count, err))
        return false;
    char temp[PATH_MAX];
    fs_temp_path(path, temp, sizeof temp);
    bool written = exr_write_file(temp, path, image, sources, channel_count, err);
    free(sources);
    return fs_finish_atomic_write(temp, path, written, err);
}

bool image_write_exr(const char *path, const float *rgb, int width, int height, Error *err)
{
    ExrImage image = {.rgb = rgb, .width = width, .height = height};
    return image_write_exr_layers(path, &image, err);
}
