/* SPDX-License-Identifier: MIT */
/* bench_bvh_rays.h: the primary rays tools/bench_bvh traces: a fixed camera on each mesh, rays in
 * tiles or scanlines. Header-only (static functions), like bench_common.h, so that
 * tools/bench_bvh.c stays one translation unit. */
#ifndef PT_BENCH_BVH_RAYS_H
#define PT_BENCH_BVH_RAYS_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "base/error.h"
#include "bench_bvh_options.h"
#include "procedural_mesh.h"

#define IMAGE_WIDTH 480
#define IMAGE_HEIGHT 320

/* Ray as the batch kernels read it: origin with tmin in w, direction with tmax in w. */
typedef struct {
    float4 origin, dir;
} Ray;

/* Pinhole camera 1.4 bounding radii (half the bounds' diagonal) from the centre, looking at it
 * from a fixed oblique direction, 50 degrees vertical field of view: the meshes fill most of the
 * frame (a view that fits the whole bounding sphere, 91 degrees, leaves 90% of the rays to
 * miss). Rays are stored as tinybvh's speed test stores them: pixels in 4x4 tiles, each pixel's
 * samples together, stratified on a k x k grid when spp = k^2 (jittered within each cell, from
 * splitmix64). A warp so holds two neighbouring pixels and a GPU core's resident rays a compact
 * patch of the image; rows (--order rows) spread that patch along a scanline; --order random
 * shuffles the tiled rays (Fisher-Yates, fixed seed). */
#define RAY_TILE 4
_Static_assert(IMAGE_WIDTH % RAY_TILE == 0 && IMAGE_HEIGHT % RAY_TILE == 0, "whole tiles");
static Ray *primary_rays(const TestMesh *mesh, int spp, RayOrder order, uint32_t *count)
{
    float lo[3], hi[3], center[3], radius = 0.0f;
    mesh_bounds(mesh, lo, hi);
    for (int k = 0; k < 3; k++) {
        center[k] = 0.5f * (lo[k] + hi[k]);
        radius += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    radius = sqrtf(radius);
    const float view[3] = {0.57f, 0.42f, 0.71f}; /* from the centre toward the eye, unit length */
    float eye[3], forward[3], right[3], up[3];
    for (int k = 0; k < 3; k++) {
        eye[k] = center[k] + 1.4f * radius * view[k];
        forward[k] = -view[k];
    }
    /* right = forward x (0, 1, 0), up = right x forward */
    float rlen = sqrtf(forward[2] * forward[2] + forward[0] * forward[0]);
    right[0] = -forward[2] / rlen;
    right[1] = 0.0f;
    right[2] = forward[0] / rlen;
    up[0] = right[1] * forward[2] - right[2] * forward[1];
    up[1] = right[2] * forward[0] - right[0] * forward[2];
    up[2] = right[0] * forward[1] - right[1] * forward[0];
    float tan_half = tanf(0.5f * 50.0f * 3.14159265f / 180.0f), aspect = (float)IMAGE_WIDTH / IMAGE_HEIGHT;
    uint32_t n = (uint32_t)IMAGE_WIDTH * IMAGE_HEIGHT * (uint32_t)spp;
    Ray *rays = malloc(n * sizeof *rays);
    if (!rays)
        die("out of memory for %u rays", n);
    int strata = (int)sqrt((double)spp);
    if (strata * strata != spp)
        strata = 1;
    uint64_t rng = 1;
    uint32_t i = 0;
    for (uint32_t pixel = 0; pixel < (uint32_t)IMAGE_WIDTH * IMAGE_HEIGHT; pixel++) {
        int x = (int)(pixel % IMAGE_WIDTH), y = (int)(pixel / IMAGE_WIDTH);
        if (order != ORDER_ROWS) { /* IMAGE_WIDTH and IMAGE_HEIGHT are multiples of RAY_TILE */
            uint32_t tile = pixel / (RAY_TILE * RAY_TILE), within = pixel % (RAY_TILE * RAY_TILE);
            x = (int)(tile % (IMAGE_WIDTH / RAY_TILE) * RAY_TILE + within % RAY_TILE);
            y = (int)(tile / (IMAGE_WIDTH / RAY_TILE) * RAY_TILE + within / RAY_TILE);
        }
        for (int s = 0; s < spp; s++, i++) {
            float jx = ((float)(s % strata) + mesh_rng_float(&rng)) / (float)strata;
            float jy = ((float)(s / strata % strata) + mesh_rng_float(&rng)) / (float)strata;
            float sx = (2.0f * (x + jx) / IMAGE_WIDTH - 1.0f) * tan_half * aspect;
            float sy = (1.0f - 2.0f * (y + jy) / IMAGE_HEIGHT) * tan_half;
            float d[3];
            for (int k = 0; k < 3; k++)
                d[k] = forward[k] + sx * right[k] + sy * up[k];
            float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            float4 origin = {{eye[0], eye[1], eye[2], 0.0f}};
            float4 dir = {{d[0] / len, d[1] / len, d[2] / len, INFINITY}};
            rays[i].origin = origin;
            rays[i].dir = dir;
        }
    }
    if (order == ORDER_RANDOM)
        for (uint32_t k = n - 1; k > 0; k--) {
            uint32_t j = (uint32_t)(mesh_rng_next(&rng) % (k + 1u));
            Ray swap = rays[k];
            rays[k] = rays[j];
            rays[j] = swap;
        }
    *count = n;
    return rays;
}

#endif
