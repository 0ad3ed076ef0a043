/* SPDX-License-Identifier: MIT */
/* medium_grid.cl: a grid medium's density and the walk over its majorants (shared/medium.h).
 * Index space: voxel (i, j, k)'s value at (i + 0.5, j + 0.5, k + 0.5), the grid spanning [0, res];
 * a point's density is the trilinear value there (clamped to the edge voxels inside the box, 0
 * outside it), as Mitsuba 3's gridvolume with its default linear filter. The walk visits the
 * brick cells a ray crosses (a 3D DDA, Amanatides and Woo 1987), each with a constant majorant:
 * one global majorant would waste tentative collisions in the empty parts of sparse smoke. */

/* Voxel (x, y, z), clamped to the grid. */
inline float grid_voxel(const SceneView *scene, const global Medium *m, int x, int y, int z)
{
    x = clamp(x, 0, (int)m->res_x - 1), y = clamp(y, 0, (int)m->res_y - 1);
    z = clamp(z, 0, (int)m->res_z - 1);
    uint cell = (uint)(x >> 3) + m->bricks_x * ((uint)(y >> 3) + m->bricks_y * (uint)(z >> 3));
    uint brick = scene->grid_bricks[m->brick_table + cell];
    if (brick == MEDIUM_NO_BRICK)
        return 0.0f;
    uint voxel = (uint)(x & 7) + 8u * ((uint)(y & 7) + 8u * (uint)(z & 7));
    return scene->grid_values[m->values + brick * MEDIUM_BRICK_VOXELS + voxel];
}

/* The density at index point q. */
inline float grid_density(const SceneView *scene, const global Medium *m, float3 q)
{
    if (!(q.x >= 0.0f && q.y >= 0.0f && q.z >= 0.0f && q.x <= (float)m->res_x &&
          q.y <= (float)m->res_y && q.z <= (float)m->res_z))
        return 0.0f;
    float3 s = q - 0.5f, base = floor(s), f = s - base;
    int x = (int)base.x, y = (int)base.y, z = (int)base.z;
    float c00 = mix(grid_voxel(scene, m, x, y, z), grid_voxel(scene, m, x + 1, y, z), f.x);
    float c10 = mix(grid_voxel(scene, m, x, y + 1, z), grid_voxel(scene, m, x + 1, y + 1, z), f.x);
    float c01 = mix(grid_voxel(scene, m, x, y, z + 1), grid_voxel(scene, m, x + 1, y, z + 1), f.x);
    float c11 =
        mix(grid_voxel(scene, m, x, y + 1, z + 1), grid_voxel(scene, m, x + 1, y + 1, z + 1), f.x);
    return mix(mix(c00, c10, f.y), mix(c01, c11, f.y), f.z);
}

inline float3 grid_to_index_point(const global Medium *m, float3 p)
{
    return (float3)(dot(xyz(m->to_index[0]), p) + m->to_index[0].w,
                    dot(xyz(m->to_index[1]), p) + m->to_index[1].w,
                    dot(xyz(m->to_index[2]), p) + m->to_index[2].w);
}

inline float3 grid_to_index_vector(const global Medium *m, float3 v)
{
    return (float3)(dot(xyz(m->to_index[0]), v), dot(xyz(m->to_index[1]), v),
                    dot(xyz(m->to_index[2]), v));
}

/* The walk's state: the ray in index space (o + t d, with the world ray's t), the brick cell it
 * is in and, per axis, the t of its next cell boundary and the t between boundaries. */
typedef struct {
    float3 o, d;
    int3 cell, step;
    float3 t_next, t_delta;
    float t, t_end; /* the current piece starts at t; the walk ends at t_end */
} GridWalk;

/* Starts the walk of ray (o, d) over [0, tmax) in world space; false when it misses the grid. */
inline bool grid_walk_start(const global Medium *m, float3 o, float3 d, float tmax, GridWalk *w)
{
    w->o = grid_to_index_point(m, o);
    w->d = grid_to_index_vector(m, d);
    float3 hi = (float3)((float)m->res_x, (float)m->res_y, (float)m->res_z);
    float3 inv = 1.0f / w->d; /* +-inf on a zero component: its slab is all or nothing */
    float3 ta = (0.0f - w->o) * inv, tb = (hi - w->o) * inv;
    float3 tlo = fmin(ta, tb), thi = fmax(ta, tb);
    float t0 = fmax(fmax(tlo.x, tlo.y), fmax(tlo.z, 0.0f));
    float t1 = fmin(fmin(thi.x, thi.y), fmin(thi.z, tmax));
    if (!(t0 < t1))
        return false;
    w->t = t0, w->t_end = t1;
    float3 q = w->o + t0 * w->d;
    float3 cell = clamp(floor(q / (float)MEDIUM_BRICK), 0.0f,
                        (float3)((float)(m->bricks_x - 1u), (float)(m->bricks_y - 1u),
                                 (float)(m->bricks_z - 1u)));
    w->cell = convert_int3(cell);
    w->step = (int3)(w->d.x > 0.0f ? 1 : -1, w->d.y > 0.0f ? 1 : -1, w->d.z > 0.0f ? 1 : -1);
    float3 next = (cell + (float3)(w->d.x > 0.0f, w->d.y > 0.0f, w->d.z > 0.0f)) * (float)MEDIUM_BRICK;
    w->t_next = (float3)(w->d.x != 0.0f ? (next.x - w->o.x) * inv.x : INFINITY,
                         w->d.y != 0.0f ? (next.y - w->o.y) * inv.y : INFINITY,
                         w->d.z != 0.0f ? (next.z - w->o.z) * inv.z : INFINITY);
    w->t_delta = fabs((float)MEDIUM_BRICK * inv);
    return true;
}

/* The current piece [w->t, *t1) and its density majorant; false once the walk has ended. Call
 * grid_walk_next to move to the following piece. */
inline bool grid_walk_piece(const SceneView *scene, const global Medium *m, const GridWalk *w,
                            float *t1, float *majorant)
{
    if (!(w->t < w->t_end))
        return false;
    *t1 = fmin(w->t_end, fmin(w->t_next.x, fmin(w->t_next.y, w->t_next.z)));
    uint cell = (uint)w->cell.x + m->bricks_x * ((uint)w->cell.y + m->bricks_y * (uint)w->cell.z);
    *majorant = scene->grid_majorants[m->majorants + cell];
    return true;
}

inline void grid_walk_next(const global Medium *m, GridWalk *w, float t1)
{
    w->t = t1;
    if (w->t_next.x <= t1) {
        w->cell.x += w->step.x;
        w->t_next.x += w->t_delta.x;
    }
    if (w->t_next.y <= t1) {
        w->cell.y += w->step.y;
        w->t_next.y += w->t_delta.y;
    }
    if (w->t_next.z <= t1) {
        w->cell.z += w->step.z;
        w->t_next.z += w->t_delta.z;
    }
    if (w->cell.x < 0 || w->cell.y < 0 || w->cell.z < 0 || w->cell.x >= (int)m->bricks_x ||
        w->cell.y >= (int)m->bricks_y || w->cell.z >= (int)m->bricks_z)
        w->t = w->t_end; /* left the grid (rounding at its faces) */
}
