// SPDX-License-Identifier: MIT
/* BVH layouts on the host: the 4- and 8-wide collapsed trees (host/accel/bvh_wide.c) keep every
 * triangle in exactly one leaf, their boxes nested and their stack need as reported; quantised
 * 2-wide nodes (host/accel/bvh_quantized.c) hold their children's exact boxes with the traversal's
 * margin. Checked on the builder's awkward meshes and a torus far from the origin. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/bvh_quantized.h"
#include "accel/bvh_wide.h"
#include "bvh_fixtures.h"
#include "procedural_mesh.h"

typedef struct {
    const BvhLayout *layout;
    const TestMesh *mesh;
    uint32_t *tri_seen;   /* per original triangle: in how many leaves (padding lanes not counted) */
    uint8_t *node_seen;
    uint32_t max_stack;   /* the deepest stack a walk can fill, recomputed */
    uint32_t errors;
} WideCheck;

static void wide_error(WideCheck *c, const char *what, uint32_t index)
{
    if (c->errors++ < 5)
        cr_log_error("%d-wide: %s at %u", c->layout->width, what, index);
}

static const float *wide_rows(const BvhLayout *l, uint32_t node)
{
    return (const float *)((const uint8_t *)l->nodes + (size_t)node * l->node_size);
}

static const float *pack_rows(const BvhLayout *l, uint32_t pack)
{
    return (const float *)((const uint8_t *)l->prims + (size_t)pack * l->prim_size);
}

/* A leaf's packs: original indices valid, corners inside the lane's box, padding lanes repeat the
 * lane before them. */
static void check_wide_leaf(WideCheck *c, uint32_t ref, const float lo[3], const float hi[3])
{
    int w = c->layout->width;
    uint32_t code = ~ref, first = code >> BVH_WIDE_LEAF_PACK_BITS;
    uint32_t count = (code & ((1u << BVH_WIDE_LEAF_PACK_BITS) - 1u)) + 1u;
    for (uint32_t p = first; p < first + count; p++) {
        if (p >= c->layout->num_prims) {
            wide_error(c, "pack index out of range", p);
            return;
        }
        const float *rows = pack_rows(c->layout, p);
        const uint32_t *prim = (const uint32_t *)(rows + 9 * w);
        for (int lane = 0; lane < w; lane++) {
            if (prim[lane] >= c->mesh->num_triangles) {
                wide_error(c, "pack lane holds no triangle", p);
                continue;
            }
            bool padding = lane > 0 && prim[lane] == prim[lane - 1];
            if (!padding)
                c->tri_seen[prim[lane]]++;
            for (int corner = 0; corner < 3; corner++)
                for (int k = 0; k < 3; k++) {
                    float x = rows[(3 * corner + k) * w + lane];
                    if (!(x >= lo[k] && x <= hi[k]))
                        wide_error(c, "triangle outside its leaf's box", p);
                }
        }
    }
}

/* A node's used lanes come first and lie in the parent's box; pushes along the path are counted as
 * the traversal makes them (all hit children but the nearest). */
static void check_wide_node(WideCheck *c, uint32_t node, const float lo[3], const float hi[3],
                            uint32_t stacked)
{
    if (node >= c->layout->num_nodes || c->node_seen[node]++) {
        wide_error(c, "node out of range or shared", node);
        return;
    }
    int w = c->layout->width;
    const float *rows = wide_rows(c->layout, node);
    const uint32_t *child = (const uint32_t *)(rows + 6 * w);
    int used = 0;
    for (int lane = 0; lane < w; lane++) {
        bool empty = rows[lane] > rows[3 * w + lane];
        if (empty && (child[lane] != 0 || rows[lane] != INFINITY))
            wide_error(c, "unused lane not marked empty", node);
        if (!empty && used++ != lane)
            wide_error(c, "used lane after an unused one", node);
    }
    uint32_t pushes = used > 0 ? (uint32_t)used - 1 : 0;
    if (stacked + pushes > c->max_stack)
        c->max_stack = stacked + pushes;
    for (int lane = 0; lane < used; lane++) {
        float child_lo[3], child_hi[3];
        for (int k = 0; k < 3; k++) {
            child_lo[k] = rows[k * w + lane];
            child_hi[k] = rows[(3 + k) * w + lane];
            if (!(child_lo[k] >= lo[k] && child_hi[k] <= hi[k]))
                wide_error(c, "child box outside its parent's", node);
        }
        if ((int32_t)child[lane] < 0)
            check_wide_leaf(c, child[lane], child_lo, child_hi);
        else
            check_wide_node(c, child[lane], child_lo, child_hi, stacked + pushes);
    }
}

/* Every invariant of the wide layout of mesh's tree; returns its stack need. */
static uint32_t check_wide_layout(const TestMesh *mesh, int width, const char *name)
{
    Bvh bvh;
    bvh_build_for_width(&bvh, mesh->positions, mesh->triangles, mesh->num_triangles, width);
    BvhLayout layout;
    bvh_layout(&layout, &bvh, width, false);
    cr_assert_eq(layout.width, width);
    cr_assert_eq(layout.node_size, width == 4 ? sizeof(BvhNode4) : sizeof(BvhNode8));
    WideCheck c = {&layout, mesh, calloc(mesh->num_triangles + 1, 4), calloc(layout.num_nodes, 1), 0, 0};
    float lo[3], hi[3];
    mesh_bounds(mesh, lo, hi);
    check_wide_node(&c, 0, lo, hi, 0);
    for (uint32_t i = 0; i < layout.num_nodes; i++)
        if (c.node_seen[i] != 1)
            wide_error(&c, "node unreachable or shared", i);
    for (uint32_t i = 0; i < mesh->num_triangles; i++)
        if (c.tri_seen[i] != 1)
            wide_error(&c, "triangle not in exactly one leaf", i);
    cr_expect_eq(c.errors, 0, "%s: %u invariant violations in the %d-wide layout", name, c.errors, width);
    cr_expect_eq(c.max_stack, layout.max_stack, "%s: stack need %u, layout reports %u", name,
                 c.max_stack, layout.max_stack);
    cr_expect_leq(c.max_stack, BVH_WIDE_STACK_SIZE, "%s: %d-wide stack need %u", name, width, c.max_stack);
    free(c.tri_seen);
    free(c.node_seen);
    bvh_layout_free(&layout);
    bvh_free(&bvh);
    return c.max_stack;
}

/* The meshes every layout is checked on: the awkward cases of the builder (one triangle, nine,
 * identical copies, none, chains along the axes) and a torus far from the origin and small against
 * its coordinates, where quantised frames lose the most bits. */
typedef struct {
    const char *name;
    TestMesh mesh;
} NamedMesh;
#define LAYOUT_MESHES 9
static void layout_meshes(NamedMesh out[LAYOUT_MESHES])
{
    NamedMesh cases[LAYOUT_MESHES] = {
        {"icosphere", mesh_icosphere(4)}, {"torus", mesh_torus(30000)},
        {"soup", mesh_soup(5000, 7)},     {"one", mesh_soup(1, 1)},
        {"nine", mesh_soup(9, 3)},        {"copies", mesh_copies(5000)},
        {"empty", mesh_soup(0, 1)},       {"axis chains", mesh_axis_chains(1280)},
        {"far torus", mesh_torus(30000)}};
    TestMesh *far = &cases[8].mesh;
    for (uint32_t v = 0; v < far->num_positions; v++)
        for (int k = 0; k < 3; k++)
            far->positions[v].s[k] = far->positions[v].s[k] * 1e-3f - 3.0e4f * (k + 1) * (k == 1 ? -1 : 1);
    memcpy(out, cases, sizeof cases);
}

Test(bvh, wide_layout_invariants_hold)
{
    NamedMesh cases[LAYOUT_MESHES];
    layout_meshes(cases);
    for (size_t i = 0; i < LAYOUT_MESHES; i++) {
        for (int width = 4; width <= 8; width += 4) {
            uint32_t stack = check_wide_layout(&cases[i].mesh, width, cases[i].name);
            cr_log_info("%s, %d-wide: stack need %u", cases[i].name, width, stack);
        }
        test_mesh_free(&cases[i].mesh);
    }
}

/* Every quantised child box holds its exact box with the margin the traversal relies on
 * (host/accel/bvh_quantized.c), is at most two steps looser per side, and keeps its reference; an empty
 * child is inverted on every axis with no triangles. */
static void check_quantized(const TestMesh *mesh, const char *name)
{
    Bvh bvh;
    bvh_build(&bvh, mesh->positions, mesh->triangles, mesh->num_triangles);
    BvhNodeQuantized *q = bvh_quantize(&bvh);
    unsigned errors = 0;
    for (uint32_t i = 0; i < bvh.num_nodes; i++) {
        const BvhNode *n = &bvh.nodes[i];
        const float4 *lo[2] = {&n->lmin, &n->rmin}, *hi[2] = {&n->lmax, &n->rmax};
        const uint32_t refs[2] = {q[i].refs.s[2], q[i].refs.s[3]};
        for (int c = 0; c < 2; c++) {
            double qlo[3], qhi[3];
            bvh_quantized_child_box(&q[i], c, qlo, qhi);
            uint32_t ref, count;
            memcpy(&ref, &lo[c]->s[3], sizeof ref);
            memcpy(&count, &hi[c]->s[3], sizeof count);
            bool empty = !(lo[c]->s[0] <= hi[c]->s[0]);
            for (int k = 0; k < 3; k++) {
                double step = ldexp(1.0, (int)(q[i].frame.s[k] & 0xffu) - 127), margin = step / 1024;
                bool ok = empty ? qlo[k] > qhi[k]
                                : qlo[k] <= lo[c]->s[k] - margin && qhi[k] >= hi[c]->s[k] + margin &&
                                      qlo[k] >= lo[c]->s[k] - 2 * step && qhi[k] <= hi[c]->s[k] + 2 * step;
                if (!ok && errors++ < 5)
                    cr_log_error("%s: node %u child %d axis %d: [%.9g, %.9g] against [%.9g, %.9g]", name,
                                 i, c, k, qlo[k], qhi[k], lo[c]->s[k], hi[c]->s[k]);
            }
            uint32_t want = (int32_t)ref >= 0 ? ref
                                              : BVH_QUANTIZED_LEAF | ~ref << BVH_QUANTIZED_COUNT_BITS | count;
            if (refs[c] != want && errors++ < 5)
                cr_log_error("%s: node %u child %d: reference %08x, want %08x", name, i, c, refs[c], want);
        }
    }
    cr_expect_eq(errors, 0, "%s: %u quantisation errors", name, errors);
    free(q);
    bvh_free(&bvh);
}

Test(bvh, quantized_nodes_hold_their_children)
{
    NamedMesh cases[LAYOUT_MESHES];
    layout_meshes(cases);
    for (size_t i = 0; i < LAYOUT_MESHES; i++) {
        check_quantized(&cases[i].mesh, cases[i].name);
        test_mesh_free(&cases[i].mesh);
    }
}

