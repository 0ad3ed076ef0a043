/* SPDX-License-Identifier: MIT */
/* ply_faces.c: the face and tristrips elements of a PLY body, for ply_reader.c: each face's
 * vertex_indices list (every index checked against the vertex count), tristrips with -1 restarts
 * turned into triangles of the strip's winding, and the faces kept triangulated like OBJ n-gons
 * once every element is read. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "io/ply_internal.h"
#include "io/triangulate.h"

static bool grow(void **array, size_t *capacity, size_t needed, size_t element_size)
{
    if (needed <= *capacity)
        return true;
    size_t wanted = *capacity ? 2 * *capacity : 256;
    while (wanted < needed)
        wanted *= 2;
    void *grown = realloc(*array, wanted * element_size);
    if (!grown)
        return false;
    *array = grown;
    *capacity = wanted;
    return true;
}

/* Appends one face of n corners, which the caller fills: face_corners[num_corners - n, ...).
 * (n may be 0: a face PLY allows, skipped later with a warning.) */
static bool add_face(Ply *p, size_t n)
{
    if (!grow((void **)&p->face_sizes, &p->faces_capacity, p->num_faces + 1, sizeof *p->face_sizes) ||
        !grow((void **)&p->face_corners, &p->corners_capacity, p->num_corners + n,
              sizeof *p->face_corners))
        return ply_fail(p, ERR_TOO_LARGE, 0, "out of memory reading faces");
    p->face_sizes[p->num_faces++] = (uint16_t)n;
    p->num_corners += n;
    return true;
}

/* One face's vertex_indices list, every index checked against the vertex count. */
bool ply_read_face_list(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t face,
                           uint64_t num_vertices)
{
    size_t n;
    if (!ply_read_list_count(p, prop, e, face, &n))
        return false;
    if (n > PLY_MAX_FACE_CORNERS)
        return ply_fail(p, ERR_TOO_LARGE, ply_body_line(p), "face %llu has %zu vertices (the limit is %d)",
                    (unsigned long long)face, n, PLY_MAX_FACE_CORNERS);
    size_t first = p->num_corners;
    if (!add_face(p, n))
        return false;
    for (size_t k = 0; k < n; k++) {
        double index;
        if (!ply_read_item_value(p, prop->type, e, face, &index))
            return false;
        if (!(index >= 0.0) || index != floor(index) || index >= (double)num_vertices)
            return ply_fail(p, ERR_OBJ_INDEX, ply_body_line(p),
                        "face %llu: vertex index %g out of range (%llu vertices)",
                        (unsigned long long)face, index, (unsigned long long)num_vertices);
        p->face_corners[first + k] = (int32_t)index;
    }
    return true;
}

/* One tristrips item (Cyberware scans): a list of vertex indices where -1 restarts the strip;
 * each index after the first two makes a triangle with the two before it, every other one with
 * its first two corners swapped so that all keep the strip's winding. Triangles with a repeated
 * corner (used to turn a strip) are not emitted. */
bool ply_read_strip_list(Ply *p, const PlyProperty *prop, const PlyElement *e, uint64_t item,
                            uint64_t num_vertices)
{
    size_t n, have = 0, parity = 0;
    if (!ply_read_list_count(p, prop, e, item, &n))
        return false;
    int32_t a = -1, b = -1;
    for (size_t k = 0; k < n; k++) {
        double index;
        if (!ply_read_item_value(p, prop->type, e, item, &index))
            return false;
        if (index == -1.0) {
            have = parity = 0;
            continue;
        }
        if (!(index >= 0.0) || index != floor(index) || index >= (double)num_vertices)
            return ply_fail(p, ERR_OBJ_INDEX, ply_body_line(p),
                        "tristrips %llu: vertex index %g out of range (%llu vertices; -1 restarts)",
                        (unsigned long long)item, index, (unsigned long long)num_vertices);
        int32_t c = (int32_t)index;
        if (have >= 2) {
            if (a != b && b != c && a != c) {
                if (!add_face(p, 3))
                    return false;
                int32_t *t = p->face_corners + p->num_corners - 3;
                t[0] = parity ? b : a;
                t[1] = parity ? a : b;
                t[2] = c;
            }
            parity ^= 1;
        }
        a = b;
        b = c;
        have++;
    }
    return true;
}

/* Triangulates the faces read, in file order, like OBJ n-gons. */
bool ply_emit_triangles(Ply *p, Mesh *out)
{
    size_t max_triangles = 0, short_faces = 0;
    for (size_t f = 0; f < p->num_faces; f++)
        max_triangles += p->face_sizes[f] >= 3 ? p->face_sizes[f] - 2u : 0u;
    out->corners = malloc((max_triangles ? 9 * max_triangles : 1) * sizeof *out->corners);
    out->material_ids = malloc((max_triangles ? max_triangles : 1) * sizeof *out->material_ids);
    if (!out->corners || !out->material_ids)
        return ply_fail(p, ERR_TOO_LARGE, 0, "out of memory for %zu triangles", max_triangles);
    float points[3 * PLY_MAX_FACE_CORNERS];
    uint32_t triangles[3 * PLY_MAX_FACE_CORNERS];
    size_t first = 0; /* the face's first corner in face_corners (NULL when no face has one) */
    for (size_t f = 0; f < p->num_faces; first += p->face_sizes[f++]) {
        size_t n = p->face_sizes[f];
        if (n < 3) {
            short_faces++;
            continue;
        }
        const int32_t *corner = p->face_corners + first;
        out->num_faces++;
        for (size_t k = 0; k < n; k++)
            memcpy(points + 3 * k, out->positions + 3 * (size_t)corner[k], 3 * sizeof(float));
        size_t count = triangulate_polygon(points, n, triangles);
        for (size_t t = 0; t < count; t++) {
            int32_t *emitted = out->corners + 9 * out->num_triangles;
            for (int c = 0; c < 3; c++) {
                int32_t v = corner[triangles[3 * t + c]];
                emitted[3 * c + 0] = v;
                emitted[3 * c + 1] = out->texcoords ? v : -1;
                emitted[3 * c + 2] = out->normals ? v : -1;
            }
            out->material_ids[out->num_triangles++] = -1;
        }
    }
    if (short_faces > 0)
        warn("%s: %zu face%s with fewer than 3 vertices skipped", p->path, short_faces,
             short_faces == 1 ? "" : "s");
    return true;
}
