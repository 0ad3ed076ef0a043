// SPDX-License-Identifier: MIT
/* The TLAS of a two-level SceneBvh (host/accel/tlas.c), in every layout (2-wide float and
 * quantised, 4- and 8-wide): every box holds the boxes of the instances below it, every instance
 * is named by exactly one leaf, inner references stay inside the TLAS, and the BLAS roots follow
 * it. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh_quantized.h"
#include "accel/scene_bvh.h"
#include "procedural_mesh.h"

#define NUM_INSTANCES 3000

typedef struct {
    const SceneBvh *bvh;
    const BvhInstance *instances;
    uint32_t *seen;
    uint32_t errors;
} TlasCheck;

static void tlas_error(TlasCheck *c, const char *what, uint32_t index)
{
    if (c->errors++ < 5)
        cr_log_error("width %d%s: %s at %u", c->bvh->width, c->bvh->quantized ? " quantised" : "",
                     what, index);
}

static void grow(double lo[3], double hi[3], const float blo[3], const float bhi[3])
{
    for (int k = 0; k < 3; k++)
        lo[k] = fmin(lo[k], blo[k]), hi[k] = fmax(hi[k], bhi[k]);
}

static bool holds(const double lo[3], const double hi[3], const double ilo[3], const double ihi[3])
{
    for (int k = 0; k < 3; k++)
        if (!(lo[k] <= ilo[k] && hi[k] >= ihi[k]))
            return false;
    return true;
}

static void check_node(TlasCheck *c, uint32_t node, double ulo[3], double uhi[3]);

/* A child: a leaf names an instance (~i or the quantised leaf code); its box must hold what is
 * below it. Grows [ulo, uhi] by that. */
static void check_child(TlasCheck *c, uint32_t ref, bool leaf, const double lo[3], const double hi[3],
                        double ulo[3], double uhi[3])
{
    double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    if (leaf) {
        if (ref >= NUM_INSTANCES) {
            tlas_error(c, "leaf names no instance", ref);
            return;
        }
        c->seen[ref]++;
        grow(blo, bhi, c->instances[ref].lo, c->instances[ref].hi);
    } else {
        if (ref == 0 || ref >= c->bvh->tlas_nodes) {
            tlas_error(c, "inner reference outside the TLAS", ref);
            return;
        }
        check_node(c, ref, blo, bhi);
    }
    if (!holds(lo, hi, blo, bhi))
        tlas_error(c, "box does not hold the instances below it", ref);
    for (int k = 0; k < 3; k++)
        ulo[k] = fmin(ulo[k], blo[k]), uhi[k] = fmax(uhi[k], bhi[k]);
}

static void check_node(TlasCheck *c, uint32_t node, double ulo[3], double uhi[3])
{
    const SceneBvh *b = c->bvh;
    const uint8_t *base = (const uint8_t *)b->nodes + (size_t)node * b->node_size;
    if (b->width == 2 && b->quantized) {
        const BvhNodeQuantized *q = (const BvhNodeQuantized *)base;
        for (int side = 0; side < 2; side++) {
            uint32_t ref = side ? q->refs.s[3] : q->refs.s[2];
            bool leaf = (ref & BVH_QUANTIZED_LEAF) != 0;
            if (leaf && (ref & ((1u << BVH_QUANTIZED_COUNT_BITS) - 1u)) == 0)
                continue; /* the empty child of a one-instance TLAS */
            double lo[3], hi[3];
            bvh_quantized_child_box(q, side, lo, hi);
            check_child(c, leaf ? (ref & ~BVH_QUANTIZED_LEAF) >> BVH_QUANTIZED_COUNT_BITS : ref, leaf,
                        lo, hi, ulo, uhi);
        }
    } else if (b->width == 2) {
        const BvhNode *n = (const BvhNode *)base;
        const float4 *los[2] = {&n->lmin, &n->rmin}, *his[2] = {&n->lmax, &n->rmax};
        for (int side = 0; side < 2; side++) {
            uint32_t ref, count;
            memcpy(&ref, &los[side]->s[3], sizeof ref);
            memcpy(&count, &his[side]->s[3], sizeof count);
            bool leaf = (int32_t)ref < 0;
            if (leaf && count == 0)
                continue;
            if (leaf && count != 1)
                tlas_error(c, "TLAS leaf of more than one instance", node);
            double lo[3] = {los[side]->s[0], los[side]->s[1], los[side]->s[2]};
            double hi[3] = {his[side]->s[0], his[side]->s[1], his[side]->s[2]};
            check_child(c, leaf ? ~ref : ref, leaf, lo, hi, ulo, uhi);
        }
    } else {
        int w = b->width;
        const float *rows = (const float *)base;
        const uint32_t *child = (const uint32_t *)(rows + 6 * w);
        for (int lane = 0; lane < w; lane++) {
            if (child[lane] == 0)
                continue; /* unused */
            double lo[3], hi[3];
            for (int k = 0; k < 3; k++)
                lo[k] = rows[k * w + lane], hi[k] = rows[(3 + k) * w + lane];
            bool leaf = (int32_t)child[lane] < 0;
            check_child(c, leaf ? ~child[lane] : child[lane], leaf, lo, hi, ulo, uhi);
        }
    }
}

static void check_layout(int width, bool quantized)
{
    TestMesh mesh = mesh_icosphere(1);
    BvhMesh meshes[1] = {{0, mesh.num_triangles}};
    BvhInstance *instances = malloc(NUM_INSTANCES * sizeof *instances);
    uint64_t rng = 5;
    for (uint32_t i = 0; i < NUM_INSTANCES; i++) {
        instances[i].mesh = 0;
        for (int k = 0; k < 3; k++) {
            float centre = 100.0f * mesh_rng_float(&rng) - 50.0f, half = 3.0f * mesh_rng_float(&rng);
            instances[i].lo[k] = centre - half;
            instances[i].hi[k] = centre + half;
        }
    }
    SceneBvh bvh;
    scene_bvh_build(&bvh, mesh.positions, mesh.triangles, meshes, 1, instances, NUM_INSTANCES, width,
                    quantized, BVH_TWO_LEVEL);
    TlasCheck c = {&bvh, instances, calloc(NUM_INSTANCES, sizeof(uint32_t)), 0};
    double ulo[3] = {INFINITY, INFINITY, INFINITY}, uhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    check_node(&c, 0, ulo, uhi);
    for (uint32_t i = 0; i < NUM_INSTANCES; i++)
        if (c.seen[i] != 1)
            tlas_error(&c, "instance not named by exactly one leaf", i);
    cr_expect(bvh.tlas_nodes > 0 && bvh.blas_root[0] >= bvh.tlas_nodes && bvh.blas_root[0] < bvh.num_nodes,
              "width %d: BLAS root %u, TLAS nodes %u of %u", width, bvh.blas_root[0], bvh.tlas_nodes,
              bvh.num_nodes);
    cr_expect_eq(c.errors, 0, "width %d%s: %u TLAS errors", width, quantized ? " quantised" : "",
                 c.errors);
    free(c.seen);
    scene_bvh_free(&bvh);
    free(instances);
    test_mesh_free(&mesh);
}

Test(instances_bvh, tlas_boxes_hold_every_instance_box_2_wide) { check_layout(2, false); }
Test(instances_bvh, tlas_boxes_hold_every_instance_box_quantized) { check_layout(2, true); }
Test(instances_bvh, tlas_boxes_hold_every_instance_box_4_wide) { check_layout(4, false); }
Test(instances_bvh, tlas_boxes_hold_every_instance_box_8_wide) { check_layout(8, false); }
