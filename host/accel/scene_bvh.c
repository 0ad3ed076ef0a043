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

/* One level: the mesh's tree in the device layout, as v1 built it. */
static void build_one_level(SceneBvh *out, const float4 *positions, const Triangle *triangles,
                            const BvhMesh *mesh)
{
    double t0 = seconds_now();
    Bvh bvh;
    bvh_build_for_width(&bvh, positions, triangles + mesh->first_triangle, mesh->num_triangles,
                        out->width);
    BvhLayout layout;
    bvh_layout(&layout, &bvh, out->width, out->quantized);
    out->nodes = copy_of(layout.nodes, (size_t)layout.num_nodes * layout.node_size);
    out->node_size = layout.node_size;
    out->num_nodes = layout.num_nodes;
    out->prims = copy_of(layout.prims, (size_t)layout.num_prims * layout.prim_size);
    out->prim_size = layout.prim_size;
    out->num_prims = layout.num_prims;
    out->sah_cost = bvh.sah_cost;
    bvh_layout_free(&layout);
    bvh_free(&bvh);
    out->blas_root[0] = 0;
    out->first_prim[0] = 0;
    out->num_mesh_prims[0] = out->num_prims;
    out->blas_seconds = seconds_now() - t0;
}

void scene_bvh_build(SceneBvh *out, const float4 *positions, const Triangle *triangles,
                     const BvhMesh *meshes, uint32_t num_meshes, const BvhInstance *instances,
                     uint32_t num_instances, int width, bool quantized, bool two_level)
{
    memset(out, 0, sizeof *out);
    out->width = width;
    out->quantized = quantized;
    out->two_level = two_level;
    out->num_meshes = num_meshes;
    out->blas_root = calloc(num_meshes ? num_meshes : 1, sizeof *out->blas_root);
    out->first_prim = calloc(num_meshes ? num_meshes : 1, sizeof *out->first_prim);
    out->num_mesh_prims = calloc(num_meshes ? num_meshes : 1, sizeof *out->num_mesh_prims);
    if (!out->blas_root || !out->first_prim || !out->num_mesh_prims)
        die("out of memory for the BVH (%u meshes)", num_meshes);
    if (two_level) {
        if (quantized && num_instances >= BVH_QUANTIZED_MAX_TRIANGLES)
            die("BVH: %u instances; the quantised nodes address fewer than %u", num_instances,
                BVH_QUANTIZED_MAX_TRIANGLES);
        scene_bvh_build_two_level(out, positions, triangles, meshes, num_meshes, instances,
                                  num_instances);
        return;
    }
    if (num_meshes != 1 || meshes[0].first_triangle != 0)
        die("scene_bvh_build: one level takes exactly one mesh (got %u)", num_meshes);
    build_one_level(out, positions, triangles, &meshes[0]);
}

void scene_bvh_free(SceneBvh *bvh)
{
    free(bvh->nodes);
    free(bvh->prims);
    free(bvh->blas_root);
    free(bvh->first_prim);
    free(bvh->num_mesh_prims);
    memset(bvh, 0, sizeof *bvh);
}
