// SPDX-License-Identifier: MIT
/* mesh_shapes.c: analytic shapes as triangle meshes (io/mesh_shapes.h). */
#include "io/mesh_shapes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_F 3.14159265358979323846f

/* Room for v vertices (positions, normals when `normals`, uvs, one index each) and t triangles. */
static bool allocate(Mesh *m, size_t v, size_t t, bool normals)
{
    memset(m, 0, sizeof *m);
    m->positions = malloc(v * 3 * sizeof(float));
    m->normals = normals ? malloc(v * 3 * sizeof(float)) : NULL;
    m->texcoords = malloc(v * 2 * sizeof(float));
    m->corners = malloc(t * 9 * sizeof(int32_t));
    m->material_ids = malloc(t * sizeof(int32_t));
    if (!m->positions || (normals && !m->normals) || !m->texcoords || !m->corners ||
        !m->material_ids) {
        mesh_free(m);
        return false;
    }
    m->num_positions = m->num_texcoords = v;
    m->num_normals = normals ? v : 0;
    return true;
}

static void vertex(Mesh *m, size_t i, float x, float y, float z, float u, float v)
{
    m->positions[3 * i] = x, m->positions[3 * i + 1] = y, m->positions[3 * i + 2] = z;
    m->texcoords[2 * i] = u, m->texcoords[2 * i + 1] = v;
}

/* Triangle (a, b, c), counter-clockwise seen from its front; every attribute indexed alike. */
static void triangle(Mesh *m, int32_t a, int32_t b, int32_t c)
{
    int32_t *k = m->corners + 9 * m->num_triangles;
    bool n = m->normals != NULL;
    int32_t v[3] = {a, b, c};
    for (int i = 0; i < 3; i++)
        k[3 * i] = v[i], k[3 * i + 1] = v[i], k[3 * i + 2] = n ? v[i] : -1;
    m->material_ids[m->num_triangles++] = -1;
    m->num_faces++;
}

bool mesh_sphere(Mesh *m, const float center[3], float radius, int segments)
{
    int around = segments < 3 ? 3 : segments, rings = around / 2 < 2 ? 2 : around / 2;
    size_t columns = (size_t)around + 1; /* the seam's column twice, for its two u values */
    if (!allocate(m, columns * ((size_t)rings + 1), (size_t)around * (size_t)rings * 2, true))
        return false;
    for (int r = 0; r <= rings; r++) {
        float theta = PI_F * (float)r / (float)rings;
        for (int s = 0; s <= around; s++) {
            float phi = 2.0f * PI_F * (float)(s % around) / (float)around;
            /* sinf(PI_F) is -8.7e-8, not 0: the -z pole's vertices would be a tiny ring, and the
             * sphere open there (a medium needs it closed, scene/object_media.h). */
            float st = r == rings ? 0.0f : sinf(theta);
            float n[3] = {st * cosf(phi), st * sinf(phi), cosf(theta)};
            size_t i = (size_t)r * columns + (size_t)s;
            vertex(m, i, center[0] + radius * n[0], center[1] + radius * n[1],
                   center[2] + radius * n[2], (float)s / (float)around, (float)r / (float)rings);
            memcpy(m->normals + 3 * i, n, sizeof n);
        }
    }
    for (int r = 0; r < rings; r++)
        for (int s = 0; s < around; s++) {
            int32_t a = (int32_t)((size_t)r * columns + (size_t)s), b = a + 1;
            int32_t c = a + (int32_t)columns, d = c + 1;
            /* Going down from the +z pole (a above c) and around toward +phi (a before b), the
             * outside is seen counter-clockwise as a, c, d, b. Pole rows drop their degenerate
             * triangle. */
            if (r > 0)
                triangle(m, a, c, b);
            if (r < rings - 1)
                triangle(m, b, c, d);
        }
    return true;
}

bool mesh_disk(Mesh *m, int segments)
{
    int around = segments < 3 ? 3 : segments;
    if (!allocate(m, (size_t)around + 1, (size_t)around, true))
        return false;
    vertex(m, 0, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f);
    for (int s = 0; s < around; s++) {
        float phi = 2.0f * PI_F * (float)s / (float)around;
        vertex(m, (size_t)s + 1, cosf(phi), sinf(phi), 0.0f, 1.0f, (float)s / (float)around);
    }
    for (size_t i = 0; i <= (size_t)around; i++)
        m->normals[3 * i] = 0.0f, m->normals[3 * i + 1] = 0.0f, m->normals[3 * i + 2] = 1.0f;
    for (int s = 0; s < around; s++)
        triangle(m, 0, s + 1, (s + 1) % around + 1);
    return true;
}

bool mesh_rectangle(Mesh *m)
{
    if (!allocate(m, 4, 2, true))
        return false;
    vertex(m, 0, -1.0f, -1.0f, 0.0f, 0.0f, 0.0f);
    vertex(m, 1, 1.0f, -1.0f, 0.0f, 1.0f, 0.0f);
    vertex(m, 2, 1.0f, 1.0f, 0.0f, 1.0f, 1.0f);
    vertex(m, 3, -1.0f, 1.0f, 0.0f, 0.0f, 1.0f);
    for (int i = 0; i < 4; i++)
        m->normals[3 * i] = 0.0f, m->normals[3 * i + 1] = 0.0f, m->normals[3 * i + 2] = 1.0f;
    triangle(m, 0, 1, 2);
    triangle(m, 0, 2, 3);
    return true;
}

bool mesh_cube(Mesh *m)
{
    if (!allocate(m, 24, 12, false))
        return false;
    /* Per face: the outward axis and sign, and two in-plane axes (u, v) with u x v = outward. */
    static const int faces[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}};
    size_t v = 0;
    for (int f = 0; f < 6; f++) {
        int axis = faces[f % 3][0], ua = faces[f % 3][1], va = faces[f % 3][2];
        float sign = f < 3 ? 1.0f : -1.0f;
        for (int c = 0; c < 4; c++) {
            float cu = (c == 1 || c == 2) ? 1.0f : -1.0f, cv = c >= 2 ? 1.0f : -1.0f;
            float p[3];
            p[axis] = sign;
            p[ua] = cu * sign; /* mirrored on the negative face so it still winds outward */
            p[va] = cv;
            vertex(m, v + (size_t)c, p[0], p[1], p[2], 0.5f * (cu + 1.0f), 0.5f * (cv + 1.0f));
        }
        triangle(m, (int32_t)v, (int32_t)v + 1, (int32_t)v + 2);
        triangle(m, (int32_t)v, (int32_t)v + 2, (int32_t)v + 3);
        v += 4;
    }
    return true;
}
