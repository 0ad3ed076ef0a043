// SPDX-License-Identifier: MIT
/* media_fixtures.h: what the media render tests (tests/test_media_*.c) share: a closed box mesh
 * with outward fronts. Header-only (static functions) so that each test binary builds from its own
 * .c alone. */
#ifndef PT_TESTS_MEDIA_FIXTURES_H
#define PT_TESTS_MEDIA_FIXTURES_H

#include <stdio.h>

#include "support.h"

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
