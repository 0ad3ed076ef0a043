/* SPDX-License-Identifier: MIT */
/* exr_inspect.h: reading pt's EXR files back in tests through OpenEXR's C API itself (not pt's
 * reader): header attributes by name, the channel list with its types, and any channel's values.
 * Every failure fails the test. */
#ifndef PT_TEST_EXR_INSPECT_H
#define PT_TEST_EXR_INSPECT_H

#include <criterion/criterion.h>
#include <openexr.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define EXR_INSPECT_MAX_CHANNELS 32

typedef struct {
    exr_context_t ctxt;
    int width, height;
    int channel_count;
    char names[EXR_INSPECT_MAX_CHANNELS][64]; /* as listed in the header (sorted by OpenEXR) */
    exr_pixel_type_t types[EXR_INSPECT_MAX_CHANNELS];
} ExrInspect;

static inline void exr_inspect_open(ExrInspect *f, const char *path)
{
    memset(f, 0, sizeof *f);
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    cr_assert_eq(exr_start_read(&f->ctxt, path, &init), EXR_ERR_SUCCESS, "%s: not a readable EXR",
                 path);
    int parts = 0;
    cr_assert_eq(exr_get_count(f->ctxt, &parts), EXR_ERR_SUCCESS);
    cr_assert_eq(parts, 1, "%s: %d parts", path, parts);
    exr_storage_t storage;
    cr_assert_eq(exr_get_storage(f->ctxt, 0, &storage), EXR_ERR_SUCCESS);
    cr_assert_eq(storage, EXR_STORAGE_SCANLINE);
    exr_attr_box2i_t window;
    cr_assert_eq(exr_get_data_window(f->ctxt, 0, &window), EXR_ERR_SUCCESS);
    f->width = window.max.x - window.min.x + 1;
    f->height = window.max.y - window.min.y + 1;
    const exr_attr_chlist_t *channels = NULL;
    cr_assert_eq(exr_get_channels(f->ctxt, 0, &channels), EXR_ERR_SUCCESS);
    cr_assert_leq(channels->num_channels, EXR_INSPECT_MAX_CHANNELS);
    f->channel_count = channels->num_channels;
    for (int i = 0; i < channels->num_channels; i++) {
        snprintf(f->names[i], sizeof f->names[i], "%s", channels->entries[i].name.str);
        f->types[i] = channels->entries[i].pixel_type;
    }
}

static inline void exr_inspect_close(ExrInspect *f) { exr_finish(&f->ctxt); }

/* The index of channel `name` in the list, -1 when absent. */
static inline int exr_inspect_find(const ExrInspect *f, const char *name)
{
    for (int i = 0; i < f->channel_count; i++)
        if (!strcmp(f->names[i], name))
            return i;
    return -1;
}

static inline const exr_attribute_t *exr_inspect_attribute(const ExrInspect *f, const char *name,
                                                           exr_attribute_type_t type)
{
    const exr_attribute_t *attr = NULL;
    cr_assert_eq(exr_get_attribute_by_name(f->ctxt, 0, name, &attr), EXR_ERR_SUCCESS,
                 "no header attribute '%s'", name);
    cr_assert_eq(attr->type, type, "attribute '%s' is a %s", name, attr->type_name);
    return attr;
}

static inline int exr_inspect_int(const ExrInspect *f, const char *name)
{
    return exr_inspect_attribute(f, name, EXR_ATTR_INT)->i;
}

static inline float exr_inspect_float(const ExrInspect *f, const char *name)
{
    return exr_inspect_attribute(f, name, EXR_ATTR_FLOAT)->f;
}

static inline const char *exr_inspect_string(const ExrInspect *f, const char *name)
{
    return exr_inspect_attribute(f, name, EXR_ATTR_STRING)->string->str;
}

/* The values of one FLOAT channel, width * height, row 0 at the top (malloc'ed). */
static inline float *exr_inspect_channel(const ExrInspect *f, const char *name)
{
    cr_assert_geq(exr_inspect_find(f, name), 0, "no channel '%s'", name);
    float *values = calloc((size_t)f->width * (size_t)f->height, sizeof *values);
    cr_assert(values);
    int32_t lines = 0;
    cr_assert_eq(exr_get_scanlines_per_chunk(f->ctxt, 0, &lines), EXR_ERR_SUCCESS);
    exr_decode_pipeline_t decoder = EXR_DECODE_PIPELINE_INITIALIZER;
    for (int y = 0; y < f->height; y += lines) {
        exr_chunk_info_t chunk;
        cr_assert_eq(exr_read_scanline_chunk_info(f->ctxt, 0, y, &chunk), EXR_ERR_SUCCESS);
        cr_assert_eq(y == 0 ? exr_decoding_initialize(f->ctxt, 0, &chunk, &decoder)
                            : exr_decoding_update(f->ctxt, 0, &chunk, &decoder),
                     EXR_ERR_SUCCESS);
        for (int i = 0; i < decoder.channel_count; i++) {
            exr_coding_channel_info_t *channel = &decoder.channels[i];
            bool wanted = !strcmp(channel->channel_name, name);
            channel->decode_to_ptr =
                wanted ? (uint8_t *)(values + (size_t)chunk.start_y * (size_t)f->width) : NULL;
            channel->user_pixel_stride = (int32_t)sizeof(float);
            channel->user_line_stride = (int32_t)(sizeof(float) * (size_t)f->width);
            channel->user_bytes_per_element = (int16_t)sizeof(float);
            channel->user_data_type = EXR_PIXEL_FLOAT;
        }
        cr_assert_eq(exr_decoding_choose_default_routines(f->ctxt, 0, &decoder), EXR_ERR_SUCCESS);
        cr_assert_eq(exr_decoding_run(f->ctxt, 0, &decoder), EXR_ERR_SUCCESS);
    }
    exr_decoding_destroy(f->ctxt, &decoder);
    return values;
}

#endif
