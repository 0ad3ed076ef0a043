// SPDX-License-Identifier: MIT
/* tlas.c: see tlas.h. Every tree is built on its own (the TLAS by bvh_build_over_boxes, each BLAS
 * as a one-level scene's tree over its mesh, in object space) and laid out for the device; the
 * layouts are then concatenated, TLAS first, with each BLAS's node and prim references moved by
 * where its nodes and prims landed. TLAS leaves name instances (~i) and are not moved. */
#include "accel/tlas.h"

#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/bvh_quantized.h"
#include "accel/bvh_wide.h"
#include "base/clock.h"
#include "base/error.h"

static void *alloc_or_die(size_t count, size_t size)
{
    void *p = calloc(count ? count : 1, size);
    if (!p)
        die("out of memory for the two-level BVH (%zu x %zu bytes)", count, size);
    return p;
}

static void build_tlas(Bvh *tlas, const BvhInstance *instances, uint32_t n)
{
    float (*lo)[3] = alloc_or_die(n, sizeof *lo), (*hi)[3] = alloc_or_die(n, sizeof *hi);
    for (uint32_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            lo[i][k] = instances[i].lo[k], hi[i][k] = instances[i].hi[k];
    bvh_build_over_boxes(tlas, (const float(*)[3])lo, (const float(*)[3])hi, n);
    free(lo);
    free(hi);
}

/* One mesh's tree; its triangles name the scene's (global) triangle indices. */
static void build_blas(Bvh *blas, const float4 *positions, const Triangle *triangles,
                       const BvhMesh *mesh, int width)
{
    bvh_build_for_width(blas, positions, triangles + mesh->first_triangle, mesh->num_triangles,
                        width);
    for (uint32_t i = 0; i < blas->num_tris; i++) {
        uint32_t index;
        memcpy(&index, &blas->tris[i].v0.s[3], sizeof index);
        index += mesh->first_triangle;
        memcpy(&blas->tris[i].v0.s[3], &index, sizeof index);
    }
}

/* A 2-wide float node's child reference moved: inner nodes by node_base, leaves by tri_base. */
static void move_child(float4 *lo, float4 *hi, uint32_t node_base, uint32_t tri_base)
{
    uint32_t ref, count;
    memcpy(&ref, &lo->s[3], sizeof ref);
    memcpy(&count, &hi->s[3], sizeof count);
    ref = (int32_t)ref >= 0 ? ref + node_base : ~(~ref + tri_base);
    memcpy(&lo->s[3], &ref, sizeof ref);
}

/* 2-wide (float, or quantised from the joined float nodes): one Bvh of every tree. */
static void join_two_wide(SceneBvh *out, const Bvh *tlas, const Bvh *blas, uint32_t num_meshes)
{
    uint32_t num_nodes = tlas->num_nodes, num_tris = 0;
    for (uint32_t m = 0; m < num_meshes; m++) {
        out->blas_root[m] = num_nodes;
        out->first_prim[m] = num_tris;
        out->num_mesh_prims[m] = blas[m].num_tris;
        num_nodes += blas[m].num_nodes;
        num_tris += blas[m].num_tris;
    }
    Bvh joined = {alloc_or_die(num_nodes, sizeof(BvhNode)), num_nodes,
                  alloc_or_die(num_tris, sizeof(BvhTriangle)), num_tris, tlas->sah_cost};
    memcpy(joined.nodes, tlas->nodes, tlas->num_nodes * sizeof(BvhNode));
    for (uint32_t m = 0; m < num_meshes; m++) {
        BvhNode *nodes = joined.nodes + out->blas_root[m];
        memcpy(nodes, blas[m].nodes, blas[m].num_nodes * sizeof(BvhNode));
        memcpy(joined.tris + out->first_prim[m], blas[m].tris, blas[m].num_tris * sizeof(BvhTriangle));
        for (uint32_t i = 0; i < blas[m].num_nodes; i++) {
            move_child(&nodes[i].lmin, &nodes[i].lmax, out->blas_root[m], out->first_prim[m]);
            move_child(&nodes[i].rmin, &nodes[i].rmax, out->blas_root[m], out->first_prim[m]);
        }
    }
    out->prims = joined.tris;
    out->prim_size = sizeof(BvhTriangle);
    out->num_prims = num_tris;
    out->num_nodes = num_nodes;
    if (out->quantized) {
        out->nodes = bvh_quantize(&joined);
        out->node_size = sizeof(BvhNodeQuantized);
        free(joined.nodes);
    } else {
        out->nodes = joined.nodes;
        out->node_size = sizeof(BvhNode);
    }
}

/* Wide: the collapsed layouts' arrays, a BLAS's child lanes moved (an unused lane holds child 0,
 * which no tree's root-relative reference is: the root is never a child). */
static void join_wide(SceneBvh *out, const Bvh *tlas, const Bvh *blas, uint32_t num_meshes)
{
    int width = out->width;
    BvhLayout top, *bottom = alloc_or_die(num_meshes, sizeof *bottom);
    bvh_layout_tlas(&top, tlas, width);
    uint32_t num_nodes = top.num_nodes, num_packs = 0;
    for (uint32_t m = 0; m < num_meshes; m++) {
        bvh_layout(&bottom[m], &blas[m], width, false);
        out->blas_root[m] = num_nodes;
        out->first_prim[m] = num_packs;
        out->num_mesh_prims[m] = bottom[m].num_prims;
        num_nodes += bottom[m].num_nodes;
        num_packs += bottom[m].num_prims;
    }
    if ((uint64_t)num_packs << BVH_WIDE_LEAF_PACK_BITS >= 0x80000000u)
        die("BVH: %u triangle packs are more than a %d-wide leaf reference can index", num_packs,
            width);
    size_t node_size = top.node_size, pack_size = width == 4 ? sizeof(TrianglePack4)
                                                            : sizeof(TrianglePack8);
    uint8_t *nodes = aligned_alloc(64, ((size_t)num_nodes * node_size + 63) / 64 * 64);
    uint8_t *packs = aligned_alloc(64, ((size_t)(num_packs ? num_packs : 1) * pack_size + 63) / 64 * 64);
    if (!nodes || !packs)
        die("out of memory for the %d-wide two-level BVH (%u nodes)", width, num_nodes);
    memcpy(nodes, top.nodes, top.num_nodes * node_size);
    for (uint32_t m = 0; m < num_meshes; m++) {
        uint8_t *base = nodes + (size_t)out->blas_root[m] * node_size;
        memcpy(base, bottom[m].nodes, bottom[m].num_nodes * node_size);
        memcpy(packs + (size_t)out->first_prim[m] * pack_size, bottom[m].prims,
               bottom[m].num_prims * pack_size);
        for (uint32_t i = 0; i < bottom[m].num_nodes; i++) {
            uint32_t *child = (uint32_t *)(base + i * node_size + 6 * width * sizeof(float));
            for (int lane = 0; lane < width; lane++) {
                uint32_t ref = child[lane];
                if (ref == 0)
                    continue;
                if ((int32_t)ref >= 0) {
                    child[lane] = ref + out->blas_root[m];
                } else {
                    uint32_t code = ~ref, mask = (1u << BVH_WIDE_LEAF_PACK_BITS) - 1u;
                    uint32_t first = (code >> BVH_WIDE_LEAF_PACK_BITS) + out->first_prim[m];
                    child[lane] = ~(first << BVH_WIDE_LEAF_PACK_BITS | (code & mask));
                }
            }
        }
        bvh_layout_free(&bottom[m]);
    }
    bvh_layout_free(&top);
    free(bottom);
    out->nodes = nodes;
    out->node_size = node_size;
    out->num_nodes = num_nodes;
    out->prims = packs;
    out->prim_size = pack_size;
    out->num_prims = num_packs;
}

void scene_bvh_build_two_level(SceneBvh *out, const float4 *positions, const Triangle *triangles,
                               const BvhMesh *meshes, uint32_t num_meshes,
                               const BvhInstance *instances, uint32_t num_instances)
{
    double t0 = seconds_now();
    Bvh *blas = alloc_or_die(num_meshes, sizeof *blas);
    for (uint32_t m = 0; m < num_meshes; m++)
        build_blas(&blas[m], positions, triangles, &meshes[m], out->width);
    double t1 = seconds_now();
    Bvh tlas;
    build_tlas(&tlas, instances, num_instances);
    out->tlas_seconds = seconds_now() - t1;
    out->tlas_nodes = tlas.num_nodes;
    out->sah_cost = tlas.sah_cost;
    if (out->width == 2)
        join_two_wide(out, &tlas, blas, num_meshes);
    else
        join_wide(out, &tlas, blas, num_meshes);
    if (out->width != 2) {
        /* The collapse may have merged TLAS nodes: the BLAS roots above already count that. */
        out->tlas_nodes = out->blas_root[0];
        if (num_meshes == 0)
            out->tlas_nodes = out->num_nodes;
    }
    bvh_free(&tlas);
    for (uint32_t m = 0; m < num_meshes; m++)
        bvh_free(&blas[m]);
    free(blas);
    out->blas_seconds = seconds_now() - t0 - out->tlas_seconds;
}
