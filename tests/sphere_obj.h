/* SPDX-License-Identifier: MIT */
/* sphere_obj.h: a UV sphere written as OBJ text, for tests that render spheres from scene files
 * (header only). */
#ifndef PT_TEST_SPHERE_OBJ_H
#define PT_TEST_SPHERE_OBJ_H

#include <math.h>
#include <stdbool.h>
#include <stdio.h>

/* Writes a UV sphere (radius r, centre c) as OBJ; inward = true flips the winding so the
 * counter-clockwise normals point inside. */
static inline void write_sphere_obj(FILE *out, const float c[3], float r, int stacks, int slices, bool inward)
{
    const double pi = 3.14159265358979323846;
    fprintf(out, "v %f %f %f\n", c[0], c[1] + r, c[2]);
    for (int i = 1; i < stacks; i++)
        for (int j = 0; j < slices; j++) {
            double theta = pi * i / stacks, phi = 2 * pi * j / slices;
            fprintf(out, "v %.7f %.7f %.7f\n", c[0] + r * sin(theta) * cos(phi), c[1] + r * cos(theta),
                    c[2] - r * sin(theta) * sin(phi));
        }
    fprintf(out, "v %f %f %f\n", c[0], c[1] - r, c[2]);
    int bottom = 2 + (stacks - 1) * slices;
#define RING(i, j) (2 + ((i) - 1) * slices + ((j) % slices))
#define FACE(a, b, c) (inward ? fprintf(out, "f %d %d %d\n", a, c, b) : fprintf(out, "f %d %d %d\n", a, b, c))
    for (int j = 0; j < slices; j++)
        FACE(1, RING(1, j), RING(1, j + 1));
    for (int i = 1; i < stacks - 1; i++)
        for (int j = 0; j < slices; j++) {
            FACE(RING(i, j), RING(i + 1, j), RING(i + 1, j + 1));
            FACE(RING(i, j), RING(i + 1, j + 1), RING(i, j + 1));
        }
    for (int j = 0; j < slices; j++)
        FACE(RING(stacks - 1, j), bottom, RING(stacks - 1, j + 1));
#undef RING
#undef FACE
}

#endif
