// SPDX-License-Identifier: MIT
/* scene_bvh.c: see scene_bvh.h. */
#include "accel/scene_bvh.h"

#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/bvh_wide.h"
#include "accel/tlas.h"
#include "base/clock.h"
#include "base/error.h"

static void *copy_of(const void *data, size_t bytes)
{
    void *copy = malloc(bytes ? bytes : 1);
    if (!copy)
        die("out of memory for the BVH (%zu bytes)", bytes);
    memcpy(copy, data, bytes);
    return copy;
}

/* One level: n triangles in world space, as v1 built them. */
static void build_one_level(SceneBvh *out, const float4 *positions, const Triangle *triangles,
                            uint32_t n)
{
    double t0 = seconds_now();
    Bvh bvh;
    bvh_build_for_width(&bvh, positions, triangles, n, out->width);
    BvhLayout layout;
    bvh_layout(&layout, &bvh, out->width, out->quantized);
    /* The 2-wide closest-hit walk packs a leaf's first triangle as the quantised node does
     * (cl/geometry/bvh_node_2wide.cl walk_leaf). */
    if (out->width == 2 && layout.num_prims >= BVH_QUANTIZED_MAX_TRIANGLES)
        die("BVH: %u triangles; the 2-wide layout addresses fewer than %u (PT_BVH_WIDTH=8 lifts "
            "the limit)", layout.num_prims, BVH_QUANTIZED_MAX_TRIANGLES);
    out->nodes = copy_of(layout.nodes, (size_t)layout.num_nodes * layout.node_size);
    out->node_size = layout.node_size;
    out->num_nodes = layout.num_nodes;
    out->prims = copy_of(layout.prims, (size_t)layout.num_prims * layout.prim_size);
    out->prim_size = layout.prim_size;
    out->num_prims = layout.num_prims;
    out->sah_cost = bvh.sah_cost;
    bvh_layout_free(&layout);
    bvh_free(&bvh);
    out->blas_seconds = seconds_now() - t0;
}

static float4 transformed_point(const Affine *m, float4 p)
{
    double x[3] = {p.s[0], p.s[1], p.s[2]}, y[3];
    affine_point(m, x, y);
    return (float4){{(float)y[0], (float)y[1], (float)y[2], 0.0f}};
}

/* Flat: each instance's triangles in world space, three corners of their own each (the mesh's
 * vertex sharing would save memory only where the budget that chose this layout already keeps it
 * small), instance by instance, so that a flat index orders hits as (instance, triangle) does. */
static void build_flat(SceneBvh *out, const float4 *positions, const Triangle *triangles,
                       const BvhMesh *meshes, const BvhInstance *instances, uint32_t num_instances)
{
    uint64_t total = 0;
    for (uint32_t i = 0; i < num_instances; i++)
        total += meshes[instances[i].mesh].num_triangles;
    if (total >= BVH_QUANTIZED_MAX_TRIANGLES)
        die("BVH: %llu baked triangles; a flat BVH holds fewer than %u", (unsigned long long)total,
            BVH_QUANTIZED_MAX_TRIANGLES);
    uint32_t n = (uint32_t)total;
    float4 *world = malloc((n ? n : 1) * 3 * sizeof *world);
    Triangle *flat = malloc((n ? n : 1) * sizeof *flat);
    out->flat_prims = malloc((n ? n : 1) * 2 * sizeof *out->flat_prims);
    if (!world || !flat || !out->flat_prims)
        die("out of memory for a flat BVH of %u triangles", n);
    uint32_t f = 0;
    for (uint32_t i = 0; i < num_instances; i++) {
        const BvhMesh *mesh = &meshes[instances[i].mesh];
        for (uint32_t t = mesh->first_triangle; t < mesh->first_triangle + mesh->num_triangles;
             t++, f++) {
            for (int k = 0; k < 3; k++)
                world[3 * f + k] = transformed_point(&instances[i].to_world,
                                                     positions[triangles[t].v.s[k]]);
            flat[f].v = (uint4){{3 * f, 3 * f + 1, 3 * f + 2, triangles[t].v.s[3]}};
            out->flat_prims[2 * f] = i;
            out->flat_prims[2 * f + 1] = t;
        }
    }
    out->num_flat_prims = n;
    build_one_level(out, world, flat, n);
    free(world);
    free(flat);
}

void scene_bvh_build(SceneBvh *out, const float4 *positions, const Triangle *triangles,
                     const BvhMesh *meshes, uint32_t num_meshes, const BvhInstance *instances,
                     uint32_t num_instances, int width, bool quantized, BvhLevels levels)
{
    memset(out, 0, sizeof *out);
    out->width = width;
    out->quantized = quantized;
    out->levels = levels;
    out->num_meshes = num_meshes;
    out->blas_root = calloc(num_meshes ? num_meshes : 1, sizeof *out->blas_root);
    out->first_prim = calloc(num_meshes ? num_meshes : 1, sizeof *out->first_prim);
    out->num_mesh_prims = calloc(num_meshes ? num_meshes : 1, sizeof *out->num_mesh_prims);
    if (!out->blas_root || !out->first_prim || !out->num_mesh_prims)
        die("out of memory for the BVH (%u meshes)", num_meshes);
    switch (levels) {
    case BVH_TWO_LEVEL:
        /* The 2-wide walk packs a TLAS leaf's instance as the quantised node does
         * (cl/geometry/bvh_node_2wide.cl walk_leaf). */
        if (width == 2 && num_instances >= BVH_QUANTIZED_MAX_TRIANGLES)
            die("BVH: %u instances; the 2-wide TLAS addresses fewer than %u", num_instances,
                BVH_QUANTIZED_MAX_TRIANGLES);
        scene_bvh_build_two_level(out, positions, triangles, meshes, num_meshes, instances,
                                  num_instances);
        return;
    case BVH_FLAT:
        /* blas_root, first_prim and num_mesh_prims stay 0: only the two-level walk and its
         * brute-force ablation read them, and a flat BVH's ablation walks its own triangles. */
        build_flat(out, positions, triangles, meshes, instances, num_instances);
        return;
    case BVH_ONE_LEVEL:
        break;
    }
    if (num_meshes != 1 || meshes[0].first_triangle != 0)
        die("scene_bvh_build: one level takes exactly one mesh (got %u)", num_meshes);
    build_one_level(out, positions, triangles + meshes[0].first_triangle, meshes[0].num_triangles);
    out->num_mesh_prims[0] = out->num_prims;
}

void scene_bvh_drop_arrays(SceneBvh *bvh)
{
    free(bvh->nodes);
    free(bvh->prims);
    free(bvh->flat_prims);
    bvh->nodes = bvh->prims = NULL;
    bvh->flat_prims = NULL;
}

void scene_bvh_free(SceneBvh *bvh)
{
    free(bvh->nodes);
    free(bvh->prims);
    free(bvh->flat_prims);
    free(bvh->blas_root);
    free(bvh->first_prim);
    free(bvh->num_mesh_prims);
    memset(bvh, 0, sizeof *bvh);
}
