// SPDX-License-Identifier: MIT
/* media_fixtures.h: what the media render tests (tests/test_media_*.c) share: a closed box mesh
 * with outward fronts and a Mitsuba .vol writer. Header-only (static functions) so that each test binary builds from its own
 * .c alone. */
#ifndef PT_TESTS_MEDIA_FIXTURES_H
#define PT_TESTS_MEDIA_FIXTURES_H

#include <criterion/criterion.h>
#include <stdint.h>
#include <stdio.h>

#include "support.h"

/* Writes a one-channel float32 Mitsuba 3 .vol (little-endian, x fastest) spanning lo .. hi. */
static inline void write_vol_file(const char *path, int nx, int ny, int nz, const float *values,
                                  const float lo[3], const float hi[3])
{
    FILE *f = fopen(path, "wb");
    cr_assert(f, "cannot write %s", path);
    int32_t header[5] = {1, nx, ny, nz, 1}; /* encoding float32, resolution, channels */
    float bbox[6] = {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
    fwrite("VOL\3", 1, 4, f);
    fwrite(header, sizeof header, 1, f);
    fwrite(bbox, sizeof bbox, 1, f);
    fwrite(values, sizeof(float), (size_t)nx * ny * nz, f);
    fclose(f);
}

/* A closed box (x0, y0, z0) .. (x1, y1, z1) with outward fronts, written as OBJ dir/name. */
static inline const char *box_obj(const char *dir, const char *name, double x0, double y0,
                                  double z0, double x1, double y1, double z1)
{
    char text[1024];
    snprintf(text, sizeof text,
             "v %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\n"
             "v %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\n"
             "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n",
             x0, y0, z0, x1, y0, z0, x1, y1, z0, x0, y1, z0, x0, y0, z1, x1, y0, z1, x1, y1, z1,
             x0, y1, z1);
    return test_write_file(dir, name, text);
}

#endif
