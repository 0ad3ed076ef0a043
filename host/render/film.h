/* SPDX-License-Identifier: MIT */
/* film.h: the film on the device and its one reading. Per pixel, exact fixed-point sums of r, g, b
 * and a sample count (layout in cl/shared.h, FILM_*); accumulate_film adds to it. Because the sums
 * are integers, films of disjoint sample blocks can be added (film_sums_add) in any order and give
 * the bits of one render of all the blocks. */
#ifndef PT_FILM_H
#define PT_FILM_H

#include <stdbool.h>
#include <stdint.h>

#include "base/shared_types.h"
#include "device/device.h"

typedef struct {
    Device *dev;
    cl_mem sums;          /* FILM_WORDS cl_ulong per pixel */
    cl_mem moments;       /* MOMENT_WORDS cl_ulong per pixel (shared/render.h); NULL unless
                           * film_add_moments: the variance AOV and adaptive sampling */
    uint32_t num_pixels;
} Film;

#define FILM_BYTES_PER_PIXEL (FILM_WORDS * sizeof(cl_ulong))
#define MOMENT_BYTES_PER_PIXEL (MOMENT_WORDS * sizeof(cl_ulong))

bool film_init(Film *film, Device *dev, uint32_t num_pixels, Error *err);
/* Gives the film its second moments (empty; cleared with the film from then on). */
bool film_add_moments(Film *film, Error *err);
void film_release(Film *film);
void film_clear(Film *film); /* enqueued: no samples */

/* Blocking copies of the raw words (FILM_WORDS * num_pixels), to merge or resume films. */
void film_read_sums(const Film *film, uint64_t *sums);
void film_write_sums(Film *film, const uint64_t *sums);

/* The mean per pixel into rgb (num_pixels * 3 floats), 0 where there is no sample yet. */
void film_read(const Film *film, float *rgb);

/* Host side: the one conversion from sums to means, and the merge (saturating, as on the device). */
void film_sums_to_rgb(const uint64_t *sums, size_t num_pixels, float *rgb);
void film_sums_add(uint64_t *into, const uint64_t *from, size_t num_pixels);

#endif
