// SPDX-License-Identifier: MIT
/* BVH build on the host: the tree's invariants (boxes contain what is below them, every triangle
 * covered by the boxes of the leaves that hold it, pre-order layout, bounded depth, stored SAH
 * cost) on procedural meshes and the builder's awkward cases; spatial splits cut long triangles
 * and lower the SAH cost; the depth limit acts where SAH alone would overflow the traversal
 * stack; binned SAH stays within 3% of a full-sweep build. */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "bvh_fixtures.h"
#include "procedural_mesh.h"

static int check_tree(const Bvh *bvh, const TestMesh *mesh, const char *name)
{
    return check_tree_with_costs(bvh, mesh, name, BVH_COSTS_DEFAULT);
}

static int build_and_check(const TestMesh *mesh, const char *name)
{
    Bvh bvh;
    bvh_build(&bvh, mesh->positions, mesh->triangles, mesh->num_triangles);
    int depth = check_tree(&bvh, mesh, name);
    bvh_free(&bvh);
    return depth;
}

Test(bvh, build_invariants_hold_on_procedural_meshes)
{
    struct {
        const char *name;
        TestMesh mesh;
    } cases[] = {{"icosphere", mesh_icosphere(4)}, {"cube", mesh_cube_grid(9)},
                 {"torus", mesh_torus(30000)},   {"soup", mesh_soup(5000, 7)},
                 {"one", mesh_soup(1, 1)},       {"two", mesh_soup(2, 2)},
                 {"nine", mesh_soup(9, 3)},      {"copies", mesh_copies(5000)}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        build_and_check(&cases[i].mesh, cases[i].name);
        test_mesh_free(&cases[i].mesh);
    }
}

/* Long thin triangles across a box's diagonal, side by side: every triangle's box is nearly the
 * whole box, so no object split separates them, while a plane across the diagonal cuts each into
 * parts with boxes an eighth the size (the case of spatial splits: walls, roads, wires). */
static TestMesh diagonal_slivers(uint32_t n)
{
    TestMesh mesh = mesh_alloc(3 * n, n);
    for (uint32_t i = 0; i < n; i++) {
        float s = 0.5f * (float)i / (float)n, base = (float)mesh.num_positions;
        mesh.positions[mesh.num_positions++] = mesh_point(s, 0.0f, 0.0f);
        mesh.positions[mesh.num_positions++] = mesh_point(s + 1.0f, 1.0f, 1.0f);
        mesh.positions[mesh.num_positions++] = mesh_point(s + 1.0f, 1.01f, 1.0f);
        mesh_add_triangle(&mesh, (uint32_t)base, (uint32_t)base + 1, (uint32_t)base + 2);
    }
    return mesh;
}

Test(bvh, spatial_splits_cut_long_triangles)
{
    TestMesh mesh = diagonal_slivers(256);
    Bvh spatial, objects;
    bvh_build(&spatial, mesh.positions, mesh.triangles, mesh.num_triangles);
    check_tree(&spatial, &mesh, "diagonal slivers, spatial splits");
    setenv("PT_BVH_SPATIAL", "0", 1); /* criterion runs each test in a process of its own */
    bvh_build(&objects, mesh.positions, mesh.triangles, mesh.num_triangles);
    check_tree(&objects, &mesh, "diagonal slivers, object splits");
    cr_log_info("SAH %.3f with spatial splits (%u references), %.3f without", spatial.sah_cost,
                spatial.num_tris, objects.sah_cost);
    cr_expect_eq(objects.num_tris, mesh.num_triangles, "object splits add no references");
    cr_expect_gt(spatial.num_tris, mesh.num_triangles, "no spatial split was made");
    cr_expect_lt(spatial.sah_cost, 0.9 * objects.sah_cost, "SAH %g with spatial splits, %g without",
                 spatial.sah_cost, objects.sah_cost);
    bvh_free(&spatial);
    bvh_free(&objects);
    test_mesh_free(&mesh);
}

Test(bvh, depth_stays_within_the_traversal_stack)
{
    TestMesh mesh = mesh_axis_chains(1280);
    int depth = build_and_check(&mesh, "axis chains");
    /* Deep enough that the depth limit had to act (a balanced tree would be 9 levels deep). */
    cr_expect_geq(depth, 48, "chains depth %d: too shallow to exercise the limit", depth);
    test_mesh_free(&mesh);
}

Test(bvh, binned_sah_is_within_3_percent_of_full_sweep)
{
    TestMesh meshes[] = {mesh_torus(20000), mesh_icosphere(5), mesh_soup(10000, 11)};
    const char *names[] = {"torus", "icosphere", "soup"};
    for (int i = 0; i < 3; i++) {
        Bvh binned, swept;
        bvh_build(&binned, meshes[i].positions, meshes[i].triangles, meshes[i].num_triangles);
        bvh_build_full_sweep(&swept, meshes[i].positions, meshes[i].triangles,
                             meshes[i].num_triangles);
        check_tree(&swept, &meshes[i], names[i]);
        cr_log_info("%s: SAH binned %.3f, full sweep %.3f", names[i], binned.sah_cost, swept.sah_cost);
        cr_expect_leq(binned.sah_cost, 1.03 * swept.sah_cost, "%s: binned %g vs full sweep %g",
                      names[i], binned.sah_cost, swept.sah_cost);
        bvh_free(&binned);
        bvh_free(&swept);
        test_mesh_free(&meshes[i]);
    }
}

