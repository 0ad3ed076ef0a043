// SPDX-License-Identifier: MIT
#include "render/film.h"

#include <math.h>
#include <stdlib.h>

bool film_init(Film *film, Device *dev, uint32_t num_pixels, Error *err)
{
    film->dev = dev;
    film->num_pixels = num_pixels;
    film->sums = device_buffer(dev, "film", CL_MEM_READ_WRITE, (size_t)num_pixels * FILM_BYTES_PER_PIXEL,
                               NULL, err);
    if (!film->sums)
        return false;
    film_clear(film);
    return true;
}

bool film_add_moments(Film *film, Error *err)
{
    film->moments = device_buffer(film->dev, "film_moments", CL_MEM_READ_WRITE,
                                  (size_t)film->num_pixels * MOMENT_BYTES_PER_PIXEL, NULL, err);
    if (!film->moments)
        return false;
    film_clear(film);
    return true;
}

void film_release(Film *film)
{
    if (film->sums)
        device_release_buffer(film->sums);
    if (film->moments)
        device_release_buffer(film->moments);
    film->sums = film->moments = NULL;
}

void film_clear(Film *film)
{
    cl_ulong zero = 0;
    device_fill(film->dev, film->sums, &zero, sizeof zero, 0,
                (size_t)film->num_pixels * FILM_BYTES_PER_PIXEL, NULL);
    if (film->moments)
        device_fill(film->dev, film->moments, &zero, sizeof zero, 0,
                    (size_t)film->num_pixels * MOMENT_BYTES_PER_PIXEL, NULL);
}

void film_read_sums(const Film *film, uint64_t *sums)
{
    device_read(film->dev, film->sums, 0, (size_t)film->num_pixels * FILM_BYTES_PER_PIXEL, sums);
}

void film_write_sums(Film *film, const uint64_t *sums)
{
    device_write(film->dev, film->sums, 0, (size_t)film->num_pixels * FILM_BYTES_PER_PIXEL, sums);
}

void film_read(const Film *film, float *rgb)
{
    uint64_t *sums = malloc((size_t)film->num_pixels * FILM_BYTES_PER_PIXEL);
    if (!sums)
        die("out of memory reading the film");
    film_read_sums(film, sums);
    film_sums_to_rgb(sums, film->num_pixels, rgb);
    free(sums);
}

/* In double: 53 bits hold a sum exactly up to 2^53 steps (2^29 samples of radiance 1) and to 2^-53
 * beyond, so the one rounding that matters is the last, to float. */
void film_sums_to_rgb(const uint64_t *sums, size_t num_pixels, float *rgb)
{
    const double step = ldexp(1.0, -FILM_FRACTION_BITS);
    for (size_t i = 0; i < num_pixels; i++) {
        const uint64_t *px = &sums[FILM_WORDS * i];
        uint64_t count = px[3];
        for (int c = 0; c < 3; c++)
            rgb[3 * i + c] = count ? (float)((double)px[c] * step / (double)count) : 0.0f;
    }
}

void film_sums_add(uint64_t *into, const uint64_t *from, size_t num_pixels)
{
    for (size_t i = 0; i < FILM_WORDS * num_pixels; i++)
        into[i] = into[i] + from[i] < into[i] ? UINT64_MAX : into[i] + from[i];
}
