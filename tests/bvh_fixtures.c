// SPDX-License-Identifier: MIT
/* bvh_fixtures.c: the host-side invariants of a built BVH and the builder's awkward meshes, for
 * the BVH tests (bvh_fixtures.h). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bvh_fixtures.h"

typedef struct {
    const Bvh *bvh;
    const TestMesh *mesh;
    uint32_t *leaf_hits;  /* per leaf-order triangle: how many leaves hold it */
    uint8_t *node_seen;
    int max_depth;        /* deepest inner node, root = 0 */
    double cost_sum;
    uint32_t errors;
    BvhCosts costs;       /* the SAH costs the tree was built with */
} TreeCheck;

static bool box_contains(const float lo[3], const float hi[3], const float4 *p)
{
    for (int k = 0; k < 3; k++)
        if (!(p->s[k] >= lo[k] && p->s[k] <= hi[k]))
            return false;
    return true;
}

static double half_area(const float lo[3], const float hi[3])
{
    double d[3] = {(double)hi[0] - lo[0], (double)hi[1] - lo[1], (double)hi[2] - lo[2]};
    return d[0] >= 0.0 ? d[0] * d[1] + d[1] * d[2] + d[2] * d[0] : 0.0;
}

static void check_error(TreeCheck *check, const char *what, uint32_t node)
{
    if (check->errors++ < 5)
        cr_log_error("BVH invariant broken at node %u: %s", node, what);
}

static void check_node(TreeCheck *check, uint32_t index, const float lo[3], const float hi[3],
                       int depth);

/* A child box lies inside its parent's box, or is empty (an unused child slot). */
static bool child_box_inside(const float lo[3], const float hi[3], const float4 *child_lo,
                             const float4 *child_hi)
{
    if (child_lo->s[0] > child_hi->s[0])
        return true;
    return box_contains(lo, hi, child_lo) && box_contains(lo, hi, child_hi);
}

/* Checks one child slot of node `parent`: a leaf's triangles lie in its box, an inner reference is
 * valid and its subtree is checked. */
static void check_child(TreeCheck *check, uint32_t parent, const float4 *lo4, const float4 *hi4,
                        int depth)
{
    float lo[3] = {lo4->s[0], lo4->s[1], lo4->s[2]}, hi[3] = {hi4->s[0], hi4->s[1], hi4->s[2]};
    int32_t ref;
    uint32_t count;
    memcpy(&ref, &lo4->s[3], sizeof ref);
    memcpy(&count, &hi4->s[3], sizeof count);
    const Bvh *bvh = check->bvh;
    if (ref < 0) {
        uint32_t first = ~(uint32_t)ref;
        if (count > BVH_MAX_LEAF_SIZE || (uint64_t)first + count > bvh->num_tris) {
            check_error(check, "leaf range", parent);
            return;
        }
        check->cost_sum += check->costs.intersect * (double)count * half_area(lo, hi);
        for (uint32_t i = first; i < first + count; i++) {
            check->leaf_hits[i]++;
            const BvhTriangle *t = &bvh->tris[i];
            if (!box_contains(lo, hi, &t->v0) || !box_contains(lo, hi, &t->v1) ||
                !box_contains(lo, hi, &t->v2))
                check_error(check, "leaf box misses a triangle corner", parent);
        }
        return;
    }
    uint32_t index = (uint32_t)ref;
    if (count != 0 || index == 0 || index >= bvh->num_nodes || check->node_seen[index]++) {
        check_error(check, "inner reference", parent);
        return;
    }
    check_node(check, index, lo, hi, depth);
}

/* Checks inner node `index`, whose box (stored in its parent) is lo/hi. */
static void check_node(TreeCheck *check, uint32_t index, const float lo[3], const float hi[3],
                       int depth)
{
    check->cost_sum += check->costs.traversal * half_area(lo, hi);
    check->max_depth = depth > check->max_depth ? depth : check->max_depth;
    const BvhNode *node = &check->bvh->nodes[index];
    if (!child_box_inside(lo, hi, &node->lmin, &node->lmax) ||
        !child_box_inside(lo, hi, &node->rmin, &node->rmax))
        check_error(check, "child box outside its parent's", index);
    /* Pre-order: an inner left child comes right after its parent. */
    int32_t left;
    memcpy(&left, &node->lmin.s[3], sizeof left);
    if (left >= 0 && (uint32_t)left != index + 1)
        check_error(check, "left child not adjacent", index);
    check_child(check, index, &node->lmin, &node->lmax, depth + 1);
    check_child(check, index, &node->rmin, &node->rmax, depth + 1);
}

int check_tree_with_costs(const Bvh *bvh, const TestMesh *mesh, const char *name, BvhCosts costs)
{
    TreeCheck check = {bvh, mesh, calloc(bvh->num_tris + 1, 4), calloc(bvh->num_nodes, 1), 0, 0, 0, costs};
    cr_assert_eq(bvh->num_tris, mesh->num_triangles, "%s: triangle count", name);
    cr_assert_geq(bvh->num_nodes, 1u);
    /* The root is checked as the child of a virtual parent whose box is the mesh bounds. */
    float lo[3], hi[3];
    mesh_bounds(mesh, lo, hi);
    check.node_seen[0] = 1;
    check_node(&check, 0, lo, hi, 0);
    for (uint32_t i = 0; i < bvh->num_nodes; i++)
        if (check.node_seen[i] != 1)
            check_error(&check, "node unreachable or shared", i);
    /* Every triangle in exactly one leaf, and the leaf order is a permutation of the mesh. */
    uint8_t *original_seen = calloc(mesh->num_triangles + 1, 1);
    for (uint32_t i = 0; i < bvh->num_tris; i++) {
        uint32_t original;
        memcpy(&original, &bvh->tris[i].v0.s[3], sizeof original);
        if (check.leaf_hits[i] != 1 || original >= mesh->num_triangles || original_seen[original]++)
            check_error(&check, "triangle not in exactly one leaf", i);
        else {
            const uint4 v = mesh->triangles[original].v;
            if (memcmp(bvh->tris[i].v1.s, mesh->positions[v.s[1]].s, 12) != 0 ||
                memcmp(bvh->tris[i].v2.s, mesh->positions[v.s[2]].s, 12) != 0)
                check_error(&check, "triangle corners differ from the mesh", i);
        }
    }
    cr_expect_eq(check.errors, 0, "%s: %u invariant violations", name, check.errors);
    cr_expect_lt(check.max_depth + 1, BVH_STACK_SIZE + 1, "%s: depth %d overflows the stack", name,
                 check.max_depth);
    double root_area = half_area(lo, hi);
    if (root_area > 0.0) {
        double sah = check.cost_sum / root_area;
        cr_expect(fabs(sah - bvh->sah_cost) <= 1e-4 * sah, "%s: sah_cost %g, recomputed %g", name,
                  bvh->sah_cost, sah);
    }
    free(check.leaf_hits);
    free(check.node_seen);
    free(original_seen);
    return check.max_depth;
}

TestMesh mesh_axis_chains(uint32_t per_axis)
{
    TestMesh mesh = mesh_alloc(9 * per_axis, 3 * per_axis);
    for (uint32_t i = 0; i < per_axis; i++)
        for (int axis = 0; axis < 3; axis++) {
            float p[3] = {0, 0, 0};
            p[axis] = (float)pow(16.0 / 15.0, (double)i);
            uint32_t base = mesh.num_positions;
            for (int c = 0; c < 3; c++) {
                float q[3] = {p[0], p[1], p[2]};
                if (c > 0)
                    q[(axis + c) % 3] += 1.0f;
                mesh.positions[mesh.num_positions++] = mesh_point(q[0], q[1], q[2]);
            }
            mesh_add_triangle(&mesh, base, base + 1, base + 2);
        }
    return mesh;
}

TestMesh mesh_copies(uint32_t n)
{
    TestMesh mesh = mesh_alloc(3, n);
    mesh.positions[mesh.num_positions++] = mesh_point(0, 0, 0);
    mesh.positions[mesh.num_positions++] = mesh_point(1, 0, 0);
    mesh.positions[mesh.num_positions++] = mesh_point(0, 1, 0);
    for (uint32_t i = 0; i < n; i++)
        mesh_add_triangle(&mesh, 0, 1, 2);
    return mesh;
}
