/* SPDX-License-Identifier: MIT */
/* procedural_mesh.h: meshes generated in memory for tests/test_accel_bvh_*.c and tools/bench_bvh.c (header
 * only: both include it, neither links the other). Closed meshes with shared vertices (icosphere,
 * subdivided cube, bumpy torus) for watertightness, and a random triangle soup with exact
 * duplicates and coplanar overlaps for tie handling. */
#ifndef PT_PROCEDURAL_MESH_H
#define PT_PROCEDURAL_MESH_H

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "io/obj_loader.h"
#include "base/shared_types.h"

typedef struct {
    float4 *positions;
    uint32_t num_positions;
    Triangle *triangles;
    uint32_t num_triangles;
} TestMesh;

/* splitmix64: small, seedable, and the same on every platform. */
static inline uint64_t mesh_rng_next(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static inline float mesh_rng_float(uint64_t *state)
{
    return (float)(mesh_rng_next(state) >> 40) * (1.0f / 16777216.0f);
}

static inline float4 mesh_point(float x, float y, float z)
{
    float4 p = {{x, y, z, 0.0f}};
    return p;
}

static inline TestMesh mesh_alloc(uint32_t num_positions, uint32_t num_triangles)
{
    TestMesh mesh = {0};
    mesh.positions = malloc((num_positions ? num_positions : 1) * sizeof *mesh.positions);
    mesh.triangles = malloc((num_triangles ? num_triangles : 1) * sizeof *mesh.triangles);
    if (!mesh.positions || !mesh.triangles)
        die("out of memory for a %u-triangle mesh", num_triangles);
    return mesh;
}

static inline void mesh_add_triangle(TestMesh *mesh, uint32_t a, uint32_t b, uint32_t c)
{
    Triangle *t = &mesh->triangles[mesh->num_triangles++];
    t->v.s[0] = a;
    t->v.s[1] = b;
    t->v.s[2] = c;
    t->v.s[3] = 0;
}

static inline void test_mesh_free(TestMesh *mesh)
{
    free(mesh->positions);
    free(mesh->triangles);
    memset(mesh, 0, sizeof *mesh);
}

/* Midpoint of edge (a, b) on the unit sphere, created once per edge so neighbours share it:
 * edge_key[] maps a sorted pair to a vertex through open addressing. */
static inline uint32_t icosphere_midpoint(TestMesh *mesh, uint64_t *keys, uint32_t *values,
                                          uint32_t capacity, uint32_t a, uint32_t b)
{
    uint64_t key = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
    uint32_t slot = (uint32_t)((key * 0x9e3779b97f4a7c15ull) >> 40) % capacity;
    while (keys[slot] != UINT64_MAX && keys[slot] != key)
        slot = (slot + 1) % capacity;
    if (keys[slot] == key)
        return values[slot];
    float4 pa = mesh->positions[a], pb = mesh->positions[b];
    float x = pa.s[0] + pb.s[0], y = pa.s[1] + pb.s[1], z = pa.s[2] + pb.s[2];
    float len = sqrtf(x * x + y * y + z * z);
    uint32_t v = mesh->num_positions++;
    mesh->positions[v] = mesh_point(x / len, y / len, z / len);
    keys[slot] = key;
    values[slot] = v;
    return v;
}

/* Unit icosphere: 20 * 4^subdivisions triangles, closed, convex, counter-clockwise outside. */
static inline TestMesh mesh_icosphere(int subdivisions)
{
    uint32_t num_triangles = 20u << (2 * subdivisions);
    TestMesh mesh = mesh_alloc(num_triangles / 2 + 2, num_triangles);
    const float t = (1.0f + sqrtf(5.0f)) / 2.0f, s = 1.0f / sqrtf(1.0f + t * t);
    const float corners[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                  {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                  {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    const uint32_t faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int i = 0; i < 12; i++)
        mesh.positions[mesh.num_positions++] =
            mesh_point(corners[i][0] * s, corners[i][1] * s, corners[i][2] * s);
    for (int i = 0; i < 20; i++)
        mesh_add_triangle(&mesh, faces[i][0], faces[i][1], faces[i][2]);
    for (int level = 0; level < subdivisions; level++) {
        uint32_t old_count = mesh.num_triangles, capacity = old_count * 4 + 1;
        Triangle *old = malloc(old_count * sizeof *old);
        uint64_t *keys = malloc(capacity * sizeof *keys);
        uint32_t *values = malloc(capacity * sizeof *values);
        if (!old || !keys || !values)
            die("out of memory subdividing an icosphere");
        memcpy(old, mesh.triangles, old_count * sizeof *old);
        memset(keys, 0xff, capacity * sizeof *keys);
        mesh.num_triangles = 0;
        for (uint32_t i = 0; i < old_count; i++) {
            uint32_t a = old[i].v.s[0], b = old[i].v.s[1], c = old[i].v.s[2];
            uint32_t ab = icosphere_midpoint(&mesh, keys, values, capacity, a, b);
            uint32_t bc = icosphere_midpoint(&mesh, keys, values, capacity, b, c);
            uint32_t ca = icosphere_midpoint(&mesh, keys, values, capacity, c, a);
            mesh_add_triangle(&mesh, a, ab, ca);
            mesh_add_triangle(&mesh, b, bc, ab);
            mesh_add_triangle(&mesh, c, ca, bc);
            mesh_add_triangle(&mesh, ab, bc, ca);
        }
        free(old);
        free(keys);
        free(values);
    }
    return mesh;
}

/* The cube [-1, 1]^3 with each face cut into k x k squares (12 k^2 triangles), closed and with
 * shared vertices: grid coordinates are exact in float, so rays along the axes can be aimed
 * exactly at edges and vertices. */
static inline TestMesh mesh_cube_grid(int k)
{
    uint32_t side = (uint32_t)k + 1;
    TestMesh mesh = mesh_alloc(side * side * side, 12u * (uint32_t)(k * k));
    for (uint32_t z = 0; z < side; z++)
        for (uint32_t y = 0; y < side; y++)
            for (uint32_t x = 0; x < side; x++)
                mesh.positions[mesh.num_positions++] =
                    mesh_point(2.0f * (float)x / (float)k - 1.0f, 2.0f * (float)y / (float)k - 1.0f,
                               2.0f * (float)z / (float)k - 1.0f);
    /* Faces: for each axis and side, walk the grid in the other two axes. */
    for (int axis = 0; axis < 3; axis++)
        for (int high = 0; high < 2; high++)
            for (uint32_t i = 0; i < (uint32_t)k; i++)
                for (uint32_t j = 0; j < (uint32_t)k; j++) {
                    uint32_t corner[4];
                    for (int c = 0; c < 4; c++) {
                        uint32_t g[3];
                        g[axis] = high ? (uint32_t)k : 0;
                        g[(axis + 1) % 3] = i + (c == 1 || c == 2);
                        g[(axis + 2) % 3] = j + (c >= 2);
                        corner[c] = (g[2] * side + g[1]) * side + g[0];
                    }
                    if (high) {
                        mesh_add_triangle(&mesh, corner[0], corner[1], corner[2]);
                        mesh_add_triangle(&mesh, corner[0], corner[2], corner[3]);
                    } else {
                        mesh_add_triangle(&mesh, corner[0], corner[2], corner[1]);
                        mesh_add_triangle(&mesh, corner[0], corner[3], corner[2]);
                    }
                }
    return mesh;
}

/* Bumpy torus of about `target` triangles (a grid of nu x nv quads, nu = 2 nv): closed, no
 * degenerate triangles, with detail at every scale; the benchmark's size-scaling mesh. */
static inline TestMesh mesh_torus(uint32_t target)
{
    uint32_t nv = (uint32_t)sqrt((double)target / 4.0);
    nv = nv < 3 ? 3 : nv;
    uint32_t nu = 2 * nv;
    TestMesh mesh = mesh_alloc(nu * nv, 2 * nu * nv);
    for (uint32_t i = 0; i < nu; i++)
        for (uint32_t j = 0; j < nv; j++) {
            double u = 6.283185307179586 * i / nu, v = 6.283185307179586 * j / nv;
            double bump = 0.04 * sin(7.0 * u) * sin(5.0 * v) + 0.01 * sin(41.0 * u + 3.0 * v) +
                          0.004 * sin(173.0 * u) * cos(97.0 * v);
            double r = 0.35 + bump;
            mesh.positions[mesh.num_positions++] = mesh_point(
                (float)((1.0 + r * cos(v)) * cos(u)), (float)(r * sin(v)),
                (float)((1.0 + r * cos(v)) * sin(u)));
        }
    for (uint32_t i = 0; i < nu; i++)
        for (uint32_t j = 0; j < nv; j++) {
            uint32_t a = i * nv + j, b = ((i + 1) % nu) * nv + j;
            uint32_t c = ((i + 1) % nu) * nv + (j + 1) % nv, d = i * nv + (j + 1) % nv;
            mesh_add_triangle(&mesh, a, b, c);
            mesh_add_triangle(&mesh, a, c, d);
        }
    return mesh;
}

/* n random triangles in [-1, 1]^3 of mixed sizes. About a tenth are exact duplicates of an earlier
 * triangle (same corners, other order) and a tenth lie in an earlier triangle's plane, overlapping
 * it, so closest-hit queries meet exact ties. */
static inline TestMesh mesh_soup(uint32_t n, uint64_t seed)
{
    TestMesh mesh = mesh_alloc(3 * n, n);
    uint64_t rng = seed;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t base = mesh.num_positions;
        float kind = mesh_rng_float(&rng);
        if (i > 0 && kind < 0.1f) {
            const Triangle *other = &mesh.triangles[mesh_rng_next(&rng) % i];
            mesh_add_triangle(&mesh, other->v.s[1], other->v.s[2], other->v.s[0]);
            continue;
        }
        if (i > 0 && kind < 0.2f) {
            /* Affine combinations of an earlier triangle's corners stay in its plane. */
            const Triangle *other = &mesh.triangles[mesh_rng_next(&rng) % i];
            for (int c = 0; c < 3; c++) {
                float a = mesh_rng_float(&rng) * 1.2f - 0.1f, b = mesh_rng_float(&rng) * (1.0f - a);
                float4 p0 = mesh.positions[other->v.s[0]], p1 = mesh.positions[other->v.s[1]];
                float4 p2 = mesh.positions[other->v.s[2]];
                float p[3];
                for (int k = 0; k < 3; k++)
                    p[k] = p0.s[k] + a * (p1.s[k] - p0.s[k]) + b * (p2.s[k] - p0.s[k]);
                mesh.positions[mesh.num_positions++] = mesh_point(p[0], p[1], p[2]);
            }
        } else {
            float size = 0.02f + 0.5f * mesh_rng_float(&rng) * mesh_rng_float(&rng);
            float center[3];
            for (int k = 0; k < 3; k++)
                center[k] = 2.0f * mesh_rng_float(&rng) - 1.0f;
            for (int c = 0; c < 3; c++) {
                float p[3];
                for (int k = 0; k < 3; k++)
                    p[k] = center[k] + size * (2.0f * mesh_rng_float(&rng) - 1.0f);
                mesh.positions[mesh.num_positions++] = mesh_point(p[0], p[1], p[2]);
            }
        }
        mesh_add_triangle(&mesh, base, base + 1, base + 2);
    }
    return mesh;
}

/* Copies an OBJ's positions and triangles. */
static inline TestMesh mesh_from_obj(const Mesh *obj)
{
    TestMesh mesh = mesh_alloc((uint32_t)obj->num_positions, (uint32_t)obj->num_triangles);
    for (size_t i = 0; i < obj->num_positions; i++)
        mesh.positions[mesh.num_positions++] = mesh_point(
            obj->positions[3 * i], obj->positions[3 * i + 1], obj->positions[3 * i + 2]);
    for (size_t i = 0; i < obj->num_triangles; i++)
        mesh_add_triangle(&mesh, (uint32_t)obj->corners[9 * i], (uint32_t)obj->corners[9 * i + 3],
                          (uint32_t)obj->corners[9 * i + 6]);
    return mesh;
}

/* Bounding box of the positions that triangles use. */
static inline void mesh_bounds(const TestMesh *mesh, float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (uint32_t i = 0; i < mesh->num_triangles; i++)
        for (int c = 0; c < 3; c++) {
            const float4 p = mesh->positions[mesh->triangles[i].v.s[c]];
            for (int k = 0; k < 3; k++) {
                lo[k] = fminf(lo[k], p.s[k]);
                hi[k] = fmaxf(hi[k], p.s[k]);
            }
        }
}

#endif
