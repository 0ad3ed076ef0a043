/* SPDX-License-Identifier: MIT */
/* shared/medium.h: participating media (shared/DESIGN.md "Media"). Part of cl/shared.h (read its
 * rules); the host includes it through shared.h, the kernels' program has it right after
 * material.h (Makefile CL_SOURCES).
 *
 * A path carries the medium its segment runs in (throughput_pack: a medium slot, 0 = none, k =
 * media[k - 1]). Surfaces change it only when their material is a medium interface
 * (MATERIAL_FLAG_MEDIUM_INTERFACE, Material.interior / .exterior): a ray leaving such a surface on
 * its front side runs in the exterior, on its back side in the interior, as Mitsuba's shapes with
 * media and pbrt's MediumInterface do; every other surface keeps the path's medium. */
#ifndef PT_SHARED_MEDIUM_H
#define PT_SHARED_MEDIUM_H

/* Medium types: X(NAME, "json name"). */
#define MEDIUM_TYPES(X)                                                                            \
    X(HOMOGENEOUS, "homogeneous") /* constant coefficients */                                      \
    X(GRID, "grid")               /* coefficients times a density grid (NanoVDB or Mitsuba .vol) */
#define MEDIUM_TYPE_ENUM(name, json) MEDIUM_##name,
enum { MEDIUM_TYPES(MEDIUM_TYPE_ENUM) MEDIUM_TYPE_COUNT };
#undef MEDIUM_TYPE_ENUM

#define MEDIUM_FLAG_SCATTERS 1u /* sigma_s > 0 somewhere: paths scatter inside (tracking) */
#define MEDIUM_FLAG_EMITS 2u    /* emission > 0 */

/* Material.exterior's "the world medium" (SceneParams.world_medium, the top-level "medium"),
 * resolved by the kernels so that objects need not know it. */
#define MEDIUM_SLOT_WORLD 0xffffffffu
/* The most media a scene may have: a slot is 16 bits of the path's and shadow ray's lanes. */
#define MEDIUM_COUNT_LIMIT 65535u

/* Grids are stored in bricks of MEDIUM_BRICK^3 voxels (x fastest), found through a brick table
 * over the grid (x fastest); a table entry MEDIUM_NO_BRICK is a brick of zeros. */
#define MEDIUM_BRICK 8u
#define MEDIUM_BRICK_VOXELS 512u
#define MEDIUM_NO_BRICK 0xffffffffu

/* One medium as the kernels see it. Coefficients are per scene unit; for a grid they are per unit
 * of density (the density_scale already multiplied in), and the density at a point is the grid's
 * trilinear value there: voxel (i, j, k)'s value sits at index point (i + 0.5, j + 0.5, k + 0.5),
 * clamped to the edge inside [0, res], 0 outside. */
typedef struct {
    float4 sigma_a;     /* rgb: absorption; w: Henyey-Greenstein g in (-1, 1) */
    float4 sigma_s;     /* rgb: scattering; w: the largest density (1 for homogeneous) */
    float4 emission;    /* rgb: emitted radiance Le (a unit length adds sigma_a Le); w unused */
    float4 to_index[3]; /* grid: rows of the world-to-index affine (x, y, z; w the translation) */
    uint type;          /* MEDIUM_* */
    uint flags;         /* MEDIUM_FLAG_* */
    uint res_x, res_y, res_z;          /* grid: voxels per axis */
    uint bricks_x, bricks_y, bricks_z; /* grid: brick table size, ceil(res / MEDIUM_BRICK) */
    uint brick_table;   /* grid: first entry of its table in grid_bricks */
    uint values;        /* grid: first float of its bricks in grid_values (brick b at values + 512 b) */
    uint majorants;     /* grid: first float of its majorants in grid_majorants, one per table
                           entry: the largest density any point of that brick's box can have */
    uint pad0;
} Medium;

#endif
