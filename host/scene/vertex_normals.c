// SPDX-License-Identifier: MIT
/* vertex_normals.c: area- and angle-weighted vertex normals. Each triangle adds its normal scaled
 * by its area (the cross product's length is twice the area) times its interior angle at the
 * vertex: the angle makes the result independent of how a polygon is split into triangles
 * (Thuermer & Wuethrich 1998), the area lets small slivers count little. */
#include "scene/vertex_normals.h"

#include <math.h>
#include <stdlib.h>

static void sub(const float *a, const float *b, double out[3])
{
    for (int i = 0; i < 3; i++)
        out[i] = (double)a[i] - (double)b[i];
}

static double angle_between(const double a[3], const double b[3])
{
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    if (!(la > 0.0) || !(lb > 0.0))
        return 0.0;
    double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
    return acos(c < -1.0 ? -1.0 : c > 1.0 ? 1.0 : c);
}

/* The OBJ position index of unified vertex v. */
static int32_t position_of(const Mesh *mesh, uint32_t v, uint32_t first_vertex,
                           const uint32_t *first_corner)
{
    return mesh->corners[3 * (size_t)first_corner[v - first_vertex]];
}

bool vertex_normals_smooth(const Mesh *mesh, const float4 *positions, float4 *normals,
                           Triangle *triangles, uint32_t first_triangle, uint32_t num_triangles,
                           uint32_t first_vertex, const uint32_t *first_corner, Error *err)
{
    double *sum = calloc(mesh->num_positions ? 3 * mesh->num_positions : 1, sizeof *sum);
    if (!sum) {
        error_set(err, ERR_TOO_LARGE, NULL, 0, "out of memory for vertex normals");
        return false;
    }
    for (uint32_t t = first_triangle; t < num_triangles; t++) {
        const uint32_t *v = triangles[t].v.s;
        if (v[3] & TRIANGLE_HAS_NORMALS)
            continue;
        const float *p[3] = {positions[v[0]].s, positions[v[1]].s, positions[v[2]].s};
        double e1[3], e2[3];
        sub(p[1], p[0], e1);
        sub(p[2], p[0], e2);
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; k++) {
            double to_next[3], to_prev[3];
            sub(p[(k + 1) % 3], p[k], to_next);
            sub(p[(k + 2) % 3], p[k], to_prev);
            double w = angle_between(to_next, to_prev);
            double *s = &sum[3 * (size_t)position_of(mesh, v[k], first_vertex, first_corner)];
            for (int i = 0; i < 3; i++)
                s[i] += w * n[i];
        }
    }
    for (uint32_t t = first_triangle; t < num_triangles; t++) {
        uint32_t *v = triangles[t].v.s;
        if (v[3] & TRIANGLE_HAS_NORMALS)
            continue;
        bool all = true;
        for (int k = 0; k < 3; k++) {
            const double *s = &sum[3 * (size_t)position_of(mesh, v[k], first_vertex, first_corner)];
            double len = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
            const float *have = normals[v[k]].s;
            if (have[0] != 0.0f || have[1] != 0.0f || have[2] != 0.0f)
                continue; /* a corner with its own vn in a triangle with another corner without */
            if (len > 0.0 && isfinite(len))
                normals[v[k]] = (float4){{(float)(s[0] / len), (float)(s[1] / len), (float)(s[2] / len), 0.0f}};
            else
                all = false;
        }
        if (all)
            v[3] |= TRIANGLE_HAS_NORMALS;
    }
    free(sum);
    return true;
}
