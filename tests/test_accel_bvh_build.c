// SPDX-License-Identifier: MIT
/* BVH build on the host: the tree's invariants (boxes contain what is below them, every triangle
 * in exactly one leaf, pre-order layout, bounded depth, stored SAH cost) on procedural meshes and
 * the builder's awkward cases; the depth limit acts where SAH alone would overflow the traversal
 * stack; binned SAH stays within 3% of a full-sweep build. */
#include <criterion/criterion.h>
#include <stdlib.h>

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

