// SPDX-License-Identifier: MIT
/* Closest-hit ties are broken by the original triangle index, whatever the tree: a ray that meets
 * several triangles at exactly the same distance (a shared edge or vertex, coincident copies)
 * reports the lowest index among them, on every layout (make test runs this binary with
 * PT_BVH_WIDTH=2, 4, 8 and PT_BVH_QUANTIZED=1). Without the rule, the answer is the first triangle
 * the walk visits, which depends on the tree's shape and so on the device type. */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/bvh_wide.h"
#include "procedural_mesh.h"
#include "support.h"

#define GRID 16                   /* squares per side of the grid */
#define COPIES 3                  /* coincident copies of every triangle */
#define STEPS_PER_UNIT 4          /* ray positions per unit: vertices, edges, diagonals, insides */
#define PLANE_Z 1.0f

/* The grid of unit squares (0..GRID)^2 at z = PLANE_Z, each split along a diagonal (alternating
 * between the two), every triangle COPIES times with its corners rotated and its winding flipped,
 * all in a shuffled order: the tree's leaf order has nothing to do with the indices. */
static TestMesh tie_mesh(uint64_t seed)
{
    uint32_t n = GRID * GRID * 2 * COPIES;
    TestMesh mesh = mesh_alloc((GRID + 1) * (GRID + 1), n);
    for (int y = 0; y <= GRID; y++)
        for (int x = 0; x <= GRID; x++)
            mesh.positions[y * (GRID + 1) + x] = mesh_point((float)x, (float)y, PLANE_Z);
    mesh.num_positions = (GRID + 1) * (GRID + 1);
    for (int y = 0; y < GRID; y++)
        for (int x = 0; x < GRID; x++) {
            uint32_t a = y * (GRID + 1) + x, b = a + 1, c = a + GRID + 2, d = a + GRID + 1;
            uint32_t tri[2][3] = {{a, b, c}, {a, c, d}};
            if ((x + y) % 2) /* the other diagonal */
                memcpy(tri, (uint32_t[2][3]){{a, b, d}, {b, c, d}}, sizeof tri);
            for (int k = 0; k < 2; k++)
                for (int copy = 0; copy < COPIES; copy++) {
                    uint32_t *v = tri[k];
                    if (copy % 2)
                        mesh_add_triangle(&mesh, v[copy % 3], v[(copy + 2) % 3], v[(copy + 1) % 3]);
                    else
                        mesh_add_triangle(&mesh, v[copy % 3], v[(copy + 1) % 3], v[(copy + 2) % 3]);
                }
        }
    uint64_t rng = seed;
    for (uint32_t i = n - 1; i > 0; i--) {
        uint32_t j = (uint32_t)(mesh_rng_next(&rng) % (i + 1));
        Triangle swap = mesh.triangles[i];
        mesh.triangles[i] = mesh.triangles[j];
        mesh.triangles[j] = swap;
    }
    return mesh;
}

/* Whether triangle t of the mesh (in the plane z = PLANE_Z) contains (x, y), edges and corners
 * included; exact: every coordinate is a small multiple of 1 / STEPS_PER_UNIT. */
static bool triangle_contains(const TestMesh *mesh, uint32_t t, double x, double y)
{
    const float4 *p[3];
    for (int c = 0; c < 3; c++)
        p[c] = &mesh->positions[mesh->triangles[t].v.s[c]];
    bool negative = false, positive = false;
    for (int c = 0; c < 3; c++) {
        const float4 *a = p[c], *b = p[(c + 1) % 3];
        double e = ((double)b->s[0] - a->s[0]) * (y - a->s[1]) - ((double)b->s[1] - a->s[1]) * (x - a->s[0]);
        negative |= e < 0.0, positive |= e > 0.0;
    }
    return !(negative && positive);
}

/* The ray layout of tests/cl/bvh_test.cl: (origin, tmin), (direction, tmax). */
typedef struct {
    float4 origin, dir;
} Ray;

/* Traces rays with bvh_test_trace_closest on the layout the test device was built for. */
static float4 *trace_closest_hits(Device *dev, const TestMesh *mesh, const Ray *rays, uint32_t n)
{
    Error err = {0};
    Bvh bvh;
    bvh_build_for_width(&bvh, mesh->positions, mesh->triangles, mesh->num_triangles, dev->bvh_width);
    BvhLayout layout;
    bvh_layout(&layout, &bvh, dev->bvh_width, dev->bvh_quantized);
    cl_mem nodes = device_buffer(dev, "bvh_nodes", CL_MEM_READ_ONLY, layout.num_nodes * layout.node_size,
                                 layout.nodes, &err);
    cl_mem prims = device_buffer(dev, "bvh_triangles", CL_MEM_READ_ONLY,
                                 layout.num_prims * layout.prim_size, layout.prims, &err);
    cl_mem ray_buf = device_buffer(dev, "rays", CL_MEM_READ_ONLY, n * sizeof *rays, rays, &err);
    cl_mem hit_buf = device_buffer(dev, "hits", CL_MEM_WRITE_ONLY, n * sizeof(float4), NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, "bvh_test_trace_closest");
    cl_uint arg = 0, num_prims = layout.num_prims, num_rays = n;
    KERNEL_ARG(kernel, arg++, nodes);
    KERNEL_ARG(kernel, arg++, prims);
    KERNEL_ARG(kernel, arg++, num_prims);
    KERNEL_ARG(kernel, arg++, ray_buf);
    KERNEL_ARG(kernel, arg++, num_rays);
    KERNEL_ARG(kernel, arg++, hit_buf);
    device_run(dev, kernel, n, 0, NULL);
    float4 *hits = malloc(n * sizeof *hits);
    device_read(dev, hit_buf, 0, n * sizeof *hits, hits);
    clReleaseKernel(kernel);
    clReleaseMemObject(nodes);
    clReleaseMemObject(prims);
    clReleaseMemObject(ray_buf);
    clReleaseMemObject(hit_buf);
    bvh_layout_free(&layout);
    bvh_free(&bvh);
    return hits;
}

/* Rays along +z and -z through every point of the grid at 1 / STEPS_PER_UNIT spacing: corners
 * shared by up to 8 triangles (times COPIES), edges and diagonals shared by 2, insides of one
 * triangle and its copies. Each meets the plane at t = 1 exactly (every triangle computes the same
 * t there), so every triangle it meets ties: the lowest index must win. */
static void check_ties(uint64_t seed)
{
    Device *dev = test_device();
    TestMesh mesh = tie_mesh(seed);
    const int side = GRID * STEPS_PER_UNIT + 1;
    uint32_t n = 2u * side * side;
    Ray *rays = malloc(n * sizeof *rays);
    uint32_t *expected = malloc(n * sizeof *expected);
    uint32_t count = 0;
    for (int j = 0; j < side; j++)
        for (int i = 0; i < side; i++)
            for (int from_below = 0; from_below < 2; from_below++) {
                float x = (float)i / STEPS_PER_UNIT, y = (float)j / STEPS_PER_UNIT;
                float z = from_below ? PLANE_Z - 1.0f : PLANE_Z + 1.0f;
                rays[count].origin = (float4){{x, y, z, 0.0f}};
                rays[count].dir = (float4){{0.0f, 0.0f, from_below ? 1.0f : -1.0f, INFINITY}};
                expected[count] = HIT_NONE;
                for (uint32_t t = 0; t < mesh.num_triangles && expected[count] == HIT_NONE; t++)
                    if (triangle_contains(&mesh, t, x, y))
                        expected[count] = t;
                cr_assert_neq(expected[count], HIT_NONE, "(%g, %g) is on the grid", x, y);
                count++;
            }
    float4 *hits = trace_closest_hits(dev, &mesh, rays, n);
    uint32_t wrong = 0;
    for (uint32_t r = 0; r < n; r++) {
        uint32_t prim;
        memcpy(&prim, &hits[r].s[3], sizeof prim);
        if ((prim != expected[r] || hits[r].s[0] != 1.0f) && wrong++ < 5)
            cr_log_error("ray %u at (%g, %g) going %s: triangle %d at t = %.9g, expected %u at 1", r,
                         rays[r].origin.s[0], rays[r].origin.s[1], rays[r].dir.s[2] > 0 ? "up" : "down",
                         (int)prim, hits[r].s[0], expected[r]);
    }
    cr_expect_eq(wrong, 0, "BVH width %d%s: %u of %u rays did not report the lowest tied triangle",
                 dev->bvh_width, dev->bvh_quantized ? " quantized" : "", wrong, n);
    free(hits);
    free(rays);
    free(expected);
    test_mesh_free(&mesh);
    test_device_release(dev);
}

Test(hit_ties, lowest_index_wins_at_shared_edges_and_coincident_triangles) { check_ties(1); }
Test(hit_ties, lowest_index_wins_in_another_shuffle) { check_ties(2); }
