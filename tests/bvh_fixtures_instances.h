/* SPDX-License-Identifier: MIT */
/* bvh_fixtures_instances.h: scenes of instanced procedural meshes for the two-level BVH tests
 * (tests/test_accel_instances_bvh.c): the meshes in one triangle array, instances with composed,
 * mirrored or moving transforms (host/base/transform.h), and their world boxes. Header-only. */
#ifndef PT_BVH_FIXTURES_INSTANCES_H
#define PT_BVH_FIXTURES_INSTANCES_H

#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/scene_bvh.h"
#include "base/transform.h"
#include "procedural_mesh.h"

#define MAX_INSTANCES 64

typedef struct {
    uint32_t mesh;
    Affine to_world;  /* static, or the motion's start */
    bool moving;
    Trs motion[2];
    float pad;        /* the TLAS box is this much larger on every side (still conservative) */
} TestInstance;

typedef struct {
    TestMesh all;         /* every mesh's triangles, in object space, one after another */
    BvhMesh meshes[4];
    uint32_t num_meshes;
    TestInstance inst[MAX_INSTANCES];
    uint32_t num_instances;
    float lo[3], hi[3]; /* the world box of every instance */
} InstancedScene;

static inline void add_mesh(InstancedScene *s, TestMesh m)
{
    uint32_t base = s->all.num_positions, first = s->all.num_triangles;
    s->all.positions = realloc(s->all.positions, (base + m.num_positions) * sizeof(float4));
    s->all.triangles = realloc(s->all.triangles, (first + m.num_triangles) * sizeof(Triangle));
    cr_assert(s->all.positions && s->all.triangles);
    memcpy(s->all.positions + base, m.positions, m.num_positions * sizeof(float4));
    for (uint32_t i = 0; i < m.num_triangles; i++) {
        Triangle t = m.triangles[i];
        for (int c = 0; c < 3; c++)
            t.v.s[c] += base;
        s->all.triangles[first + i] = t;
    }
    s->all.num_positions += m.num_positions;
    s->all.num_triangles += m.num_triangles;
    s->meshes[s->num_meshes++] = (BvhMesh){first, m.num_triangles};
    test_mesh_free(&m);
}

static inline InstancedScene scene_with_meshes(void)
{
    InstancedScene s;
    memset(&s, 0, sizeof s);
    add_mesh(&s, mesh_icosphere(2));
    add_mesh(&s, mesh_torus(600));
    add_mesh(&s, mesh_soup(300, 7));
    return s;
}

static inline Affine random_rotation(uint64_t *rng)
{
    double axis[3] = {mesh_rng_float(rng) - 0.5, mesh_rng_float(rng) - 0.5, mesh_rng_float(rng) - 0.5};
    Affine r;
    if (!affine_rotate(axis, 360.0 * mesh_rng_float(rng), &r))
        r = affine_identity();
    return r;
}

/* A composed transform: translate, rotate, scale (non-uniform, mirrored when asked), rotate again. */
static inline Affine random_transform(uint64_t *rng, bool mirrored, double spread)
{
    double sx = 0.4 + 1.2 * mesh_rng_float(rng), sy = 0.4 + 1.2 * mesh_rng_float(rng);
    double sz = 0.4 + 1.2 * mesh_rng_float(rng);
    if (mirrored)
        sx = -sx;
    Affine t = affine_translate(spread * (mesh_rng_float(rng) - 0.5), spread * (mesh_rng_float(rng) - 0.5),
                                spread * (mesh_rng_float(rng) - 0.5));
    Affine r1 = random_rotation(rng), r2 = random_rotation(rng), sc = affine_scale(sx, sy, sz);
    Affine inner = affine_mul(&sc, &r2);
    Affine outer = affine_mul(&r1, &inner);
    return affine_mul(&t, &outer);
}

static inline void add_instance(InstancedScene *s, uint32_t mesh, Affine to_world, const Affine *to_world_end)
{
    cr_assert(s->num_instances < MAX_INSTANCES);
    TestInstance *in = &s->inst[s->num_instances++];
    memset(in, 0, sizeof *in);
    in->mesh = mesh;
    in->to_world = to_world;
    if (to_world_end) {
        in->moving = true;
        cr_assert(trs_decompose(&to_world, &in->motion[0]) && trs_decompose(to_world_end, &in->motion[1]));
        trs_align(&in->motion[0], &in->motion[1]);
    }
}

/* The instance's transform at shutter fraction f. */
static inline Affine instance_at_time(const TestInstance *in, double f)
{
    if (!in->moving)
        return in->to_world;
    Trs trs = trs_interpolate(&in->motion[0], &in->motion[1], f);
    return trs_compose(&trs);
}

static inline void world_box(const InstancedScene *s, const TestInstance *in, float lo[3], float hi[3])
{
    TestMesh m = s->all;
    m.triangles += s->meshes[in->mesh].first_triangle;
    m.num_triangles = s->meshes[in->mesh].num_triangles;
    float olo[3], ohi[3];
    mesh_bounds(&m, olo, ohi);
    if (in->moving) {
        trs_swept_box(&in->motion[0], &in->motion[1], olo, ohi, lo, hi);
    } else { /* the transformed corners, as pt's TLAS takes them (render/scene_upload.c) */
        float4 *corners = malloc(3 * (size_t)m.num_triangles * sizeof *corners);
        cr_assert(corners);
        for (uint32_t t = 0; t < m.num_triangles; t++)
            for (int c = 0; c < 3; c++)
                corners[3 * t + c] = m.positions[m.triangles[t].v.s[c]];
        affine_points_box(&in->to_world, corners, 3 * (size_t)m.num_triangles, lo, hi);
        free(corners);
    }
    for (int k = 0; k < 3; k++)
        lo[k] -= in->pad, hi[k] += in->pad;
}

#endif
