// SPDX-License-Identifier: MIT
/* Interim: triangles in file order and one empty root, for the brute-force traversal. */
#include "bvh.h"

#include <stdlib.h>
#include <string.h>

#include "error.h"

void bvh_build(Bvh *bvh, const float4 *positions, const Triangle *triangles, uint32_t n)
{
    memset(bvh, 0, sizeof *bvh);
    bvh->tris = malloc((n ? n : 1) * sizeof *bvh->tris);
    bvh->nodes = calloc(1, sizeof *bvh->nodes);
    if (!bvh->tris || !bvh->nodes)
        die("out of memory building the BVH (%u triangles)", n);
    for (uint32_t i = 0; i < n; i++) {
        uint4 v = triangles[i].v;
        bvh->tris[i].v0 = positions[v.s[0]];
        bvh->tris[i].v1 = positions[v.s[1]];
        bvh->tris[i].v2 = positions[v.s[2]];
        memcpy(&bvh->tris[i].v0.s[3], &i, sizeof i);
    }
    bvh->num_tris = n;
    bvh->num_nodes = 1;
}

void bvh_free(Bvh *bvh)
{
    free(bvh->nodes);
    free(bvh->tris);
    memset(bvh, 0, sizeof *bvh);
}
