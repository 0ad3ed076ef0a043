/* SPDX-License-Identifier: MIT */
/* instance_scene.h: a small instanced scene built by hand (SceneData's meshes and instances, as
 * scene_data_finish_instances documents them) for tests/test_instance_*.c, and the double
 * precision maths the tests check the kernels and the light table against. Header-only. */
#ifndef PT_TEST_INSTANCE_SCENE_H
#define PT_TEST_INSTANCE_SCENE_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/transform.h"
#include "scene/scene_data.h"

/* Mesh 0, the "ground" (instance 0, the identity, as a merged static mesh): one grey triangle.
 * Mesh 1, the "lamp", in object space: triangle 1 grey with vertex normals, triangle 2 emissive
 * (luminance 2) in the z = 0 plane and triangle 3 emissive (luminance 0.5) in the y = 0 plane, so
 * that a non-uniform scale changes their areas differently. */
#define LAMP_FIRST_TRIANGLE 1u
#define LAMP_GREY 1u
#define LAMP_BRIGHT 2u
#define LAMP_DIM 3u
static const float instance_scene_positions[][3] = {
    {-10, 0, -10}, {10, 0, -10}, {0, 0, 10},               /* ground */
    {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {2, 0, 0.5f}, /* lamp */
};
static const float instance_scene_normals[][3] = {
    {0, 1, 0}, {0, 1, 0}, {0, 1, 0},
    {0, 0, 1}, {0.3f, 0, 1}, {0, 0.4f, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1},
};
static const uint32_t instance_scene_triangles[][4] = {
    {2, 1, 0, 0},                    /* ground, facing +y */
    {3, 4, 5, TRIANGLE_HAS_NORMALS}, /* lamp: grey, interpolated normals */
    {4, 6, 5, 0},                    /* lamp: bright, z = 0, facing +z */
    {3, 8, 7, 0},                    /* lamp: dim, facing -y */
};
static const uint32_t instance_scene_materials[] = {0, 0, 1, 2};

/* One instance of the lamp: static at `transform`, or moving from `transform` (open) to `end`. */
typedef struct {
    Affine transform;
    bool moving;
    Affine end;
} LampInstance;

/* The scene: the ground (identity, instance 0), then one lamp instance per lamps[i]
 * (instance i + 1). Free with scene_data_free. */
static inline void instance_scene_build(SceneData *d, const LampInstance *lamps, int num_lamps)
{
    scene_data_init(d);
    uint32_t nv = sizeof instance_scene_positions / sizeof instance_scene_positions[0];
    uint32_t nt = sizeof instance_scene_triangles / sizeof instance_scene_triangles[0];
    d->positions = calloc(nv, sizeof *d->positions);
    d->normals = calloc(nv, sizeof *d->normals);
    d->uvs = calloc(nv, sizeof *d->uvs);
    d->triangles = calloc(nt, sizeof *d->triangles);
    d->material_ids = calloc(nt, sizeof *d->material_ids);
    d->materials = calloc(3, sizeof *d->materials);
    d->emissive_triangles = calloc(2, sizeof *d->emissive_triangles);
    cr_assert(d->positions && d->normals && d->uvs && d->triangles && d->material_ids &&
              d->materials && d->emissive_triangles);
    for (uint32_t v = 0; v < nv; v++) {
        for (int k = 0; k < 3; k++) {
            d->positions[v].s[k] = instance_scene_positions[v][k];
            d->normals[v].s[k] = instance_scene_normals[v][k];
        }
    }
    for (uint32_t t = 0; t < nt; t++) {
        for (int k = 0; k < 4; k++)
            d->triangles[t].v.s[k] = instance_scene_triangles[t][k];
        d->material_ids[t] = instance_scene_materials[t];
    }
    d->num_vertices = nv;
    d->num_triangles = nt;
    d->materials[0] = material_default();
    d->materials[1] = material_default();
    d->materials[1].emission = (float4){{2.0f, 2.0f, 2.0f, 2.0f}};
    d->materials[2] = material_default();
    d->materials[2].emission = (float4){{0.5f, 0.5f, 0.5f, 0.5f}};
    d->num_materials = 3;
    d->emissive_triangles[0] = LAMP_BRIGHT;
    d->emissive_triangles[1] = LAMP_DIM;
    d->num_emissive = 2;

    /* scene_data_add_mesh takes everything appended since its first triangle and vertex: add the
     * lamp's range by pretending the arrays end where the ground does, then restoring them. */
    Error err = {0};
    d->num_triangles = 1, d->num_vertices = 3;
    cr_assert(scene_data_add_mesh(d, 0, 0, &err), "%s", err.message);
    d->num_triangles = nt, d->num_vertices = nv;
    cr_assert(scene_data_add_mesh(d, LAMP_FIRST_TRIANGLE, 3, &err), "%s", err.message);
    SceneInstance ground = {.mesh = 0, .object = -1, .to_world = affine_identity()};
    cr_assert(scene_data_add_instance(d, &ground, &err), "%s", err.message);
    for (int i = 0; i < num_lamps; i++) {
        SceneInstance lamp = {.mesh = 1, .object = i, .to_world = lamps[i].transform};
        if (lamps[i].moving) {
            lamp.moving = true;
            cr_assert(trs_decompose(&lamps[i].transform, &lamp.motion[0]));
            cr_assert(trs_decompose(&lamps[i].end, &lamp.motion[1]));
        }
        cr_assert(scene_data_add_instance(d, &lamp, &err), "%s", err.message);
    }
    scene_data_finish_instances(d);
}

/* ---- Double-precision reference maths ------------------------------------------------------- */

static inline void vec_sub(const double a[3], const double b[3], double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = a[k] - b[k];
}

static inline void vec_cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double vec_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void vec_normalize(double v[3])
{
    double len = sqrt(vec_dot(v, v));
    for (int k = 0; k < 3; k++)
        v[k] /= len;
}

/* M p, written out here rather than through transform.h, so that the reference is independent. */
static inline void ref_point(const Affine *m, const double p[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m->m[r][0] * p[0] + m->m[r][1] * p[1] + m->m[r][2] * p[2] + m->m[r][3];
}

/* The corners of triangle t in object space, and through m. */
static inline void ref_corners(uint32_t t, const Affine *m, double world[3][3])
{
    for (int i = 0; i < 3; i++) {
        const float *p = instance_scene_positions[instance_scene_triangles[t][i]];
        double q[3] = {p[0], p[1], p[2]};
        ref_point(m, q, world[i]);
    }
}

/* Triangle t's area through m. */
static inline double ref_area(uint32_t t, const Affine *m)
{
    double c[3][3], e1[3], e2[3], n[3];
    ref_corners(t, m, c);
    vec_sub(c[1], c[0], e1);
    vec_sub(c[2], c[0], e2);
    vec_cross(e1, e2, n);
    return 0.5 * sqrt(vec_dot(n, n));
}

/* The cofactor matrix of m's linear part, det(M) (M^-1)^T, applied to n: the inverse transpose
 * up to the factor det, which `sign_det` divides back out in sign only (the length is
 * normalised away). */
static inline void ref_normal(const Affine *m, const double n[3], double out[3])
{
    const double(*a)[4] = m->m;
    double cof[3][3];
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++) {
            int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            cof[r][c] = a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1];
        }
    }
    double det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
    for (int r = 0; r < 3; r++)
        out[r] = (cof[r][0] * n[0] + cof[r][1] * n[1] + cof[r][2] * n[2]) * (det < 0 ? -1.0 : 1.0);
    vec_normalize(out);
}

#endif
