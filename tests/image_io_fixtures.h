/* SPDX-License-Identifier: MIT */
/* image_io_fixtures.h: what the image I/O tests (test_image_io.c, test_image_io_output.c) share:
 * random finite images whose every bit matters, paths in a temporary folder and a count of what a
 * folder holds (to see leftover temporary files). Header-only, like xorshift.h; each test runs in
 * its own process, so the generator starts from the same state in every test. */
#ifndef PT_TEST_IMAGE_IO_FIXTURES_H
#define PT_TEST_IMAGE_IO_FIXTURES_H

#include <criterion/criterion.h>
#include <dirent.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/tonemap.h"

static uint32_t rng_state = 0x9e3779b9u;

static inline uint32_t next_random(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return rng_state;
}

/* Finite floats over the whole range: ordinary values, huge ones, tiny normals, denormals and
 * signed zeros, so any lossy step (half conversion, rounding) shows up as a bit difference. */
static inline float random_finite_float(void)
{
    switch (next_random() % 6) {
    case 0:
        return (float)(next_random() % 100000) / 1000.0f;
    case 1:
        return ldexpf((float)(next_random() % 1000 + 1), 100 + (int)(next_random() % 17));
    case 2:
        return ldexpf((float)(next_random() % 1000 + 1), -130 + (int)(next_random() % 20));
    case 3:
        return next_random() % 2 ? 0.0f : -0.0f;
    default: {
        uint32_t bits = next_random();
        float value;
        memcpy(&value, &bits, sizeof value);
        return isfinite(value) ? value : 1.0f;
    }
    }
}

static inline float *random_image(int width, int height)
{
    size_t count = (size_t)width * (size_t)height * 3;
    float *rgb = malloc(count * sizeof *rgb);
    cr_assert_not_null(rgb);
    for (size_t i = 0; i < count; i++)
        rgb[i] = random_finite_float();
    return rgb;
}

/* Exposure with the hard clip (--tonemap clamp): the PNG values these tests compute by hand. */
static inline DisplaySettings clamp_at(float exposure)
{
    return (DisplaySettings){.exposure = exposure, .tonemap = TONEMAP_CLAMP};
}

/* "folder/name" in one of 8 rotating buffers, so a result can be joined again. */
static inline const char *join(const char *folder, const char *name)
{
    static char paths[8][512];
    static int slot;
    char joined[512];
    snprintf(joined, sizeof joined, "%s/%s", folder, name);
    slot = (slot + 1) % 8;
    memcpy(paths[slot], joined, sizeof joined);
    return paths[slot];
}

static inline int folder_entry_count(const char *folder)
{
    DIR *dir = opendir(folder);
    cr_assert_not_null(dir, "cannot open %s", folder);
    int count = 0;
    struct dirent *entry;
    while ((entry = readdir(dir)))
        if (strcmp(entry->d_name, ".") != 0 && strcmp(entry->d_name, "..") != 0)
            count++;
    closedir(dir);
    return count;
}

#endif
