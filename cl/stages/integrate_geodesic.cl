/* SPDX-License-Identifier: MIT */
/* integrate_geodesic: bends every live path's next segment around the scene's black holes (README
 * "Black holes"), before intersect_closest. A ray whose line meets a hole's influence sphere goes
 * straight to it (a surface on the way ends the stage for the path), then follows
 *     d^2x/dl^2 = -3 M h^2 x / |x|^5,   h = |x x dx/dl|,
 * (the spatial shape of Schwarzschild null geodesics: u'' + u = 3 M u^2) with classic RK4, as a
 * chain of chords, each traced against the scene (closest hit with tmax = its length). Then:
 *   - a chord that hits a surface: the chord becomes the path's ray (ray_origin, ray_direction), and
 *     intersect_closest, tracing that same ray, writes the same hit;
 *   - a chord that crosses a disk inside its annulus: the disk's emission x throughput is added to
 *     the sample and the path goes on with probability 1 - opacity x noise, else it ends;
 *   - r <= 2M (1 + GEODESIC_HORIZON_EPSILON): captured, the path ends with nothing more;
 *   - leaving every influence sphere with no sphere ahead: the ray from there, in the bent
 *     direction, becomes the path's ray (the environment sees that direction).
 * Several holes: their accelerations add (each with its own h), an approximation of the
 * two-centre metric that holds while the holes are far apart (the scene check keeps them apart).
 * Shadow rays (intersect_shadow) stay straight: next-event estimation does not see lensing.
 * Reads: active, path_depth, ray_*, throughput, sample_id, holes. Writes: ray_origin (xyz;
 * travelled: the length of the curve from the segment's start to this origin, which
 * intersect_closest adds to the hit's t: shading's distances, the emitter MIS pdf and absorption,
 * are the whole segment's),
 * ray_direction (xyz; pdf_w, kept), radiance, path_depth (0 when captured or absorbed),
 * hit (HIT_NONE for an ended path). Next: intersect_closest. The kernel exists only with
 * PT_FEATURE(BLACK_HOLES) (render/session.c: scenes with holes). */

/* Step length: a fraction of the distance r to the nearest hole (the field varies on that scale,
 * so each step's RK4 error is a fixed small fraction of the bending it traces), scaled by
 * sqrt(r / 10M) within [1/2, 4]: finer near the photon sphere (3M: steps of 0.13M, ~140 per
 * orbit), where a grazing ray's error grows fastest, coarser far out, where the force (~1/r^4)
 * bends little. tests/test_black_holes_optics.c holds it to 1e-4 rad of a double-precision
 * reference from b = 5.25M to 1000M. */
#define GEODESIC_STEP_FRACTION 0.06f
#define GEODESIC_HORIZON_EPSILON 0.01f
/* A ray still orbiting after this many steps (one grazing the photon sphere within ~1e-40) ends. */
#define GEODESIC_MAX_STEPS 8192u
/* The rng stream of the disk's pass-through coins: spare dimension 14 of the bounce (rng.cl). */
#define DIM_DISK_COIN 14u

/* The acceleration at x (relative to the anchor hole) with velocity v. */
inline float3 geodesic_acceleration(const global BlackHole *holes, uint n, float3 anchor,
                                    float3 x, float3 v)
{
    float3 a = (float3)(0.0f);
    for (uint i = 0u; i < n; i++) {
        float3 r = x - (xyz(holes[i].centre) - anchor);
        float r2 = dot(r, r);
        float3 l = cross(r, v);
        a -= (3.0f * holes[i].centre.w * dot(l, l) / (r2 * r2 * sqrt(r2))) * r;
    }
    return a;
}

/* The distance from x to the nearest hole, in units of that hole's horizon radius 2M (the step
 * and capture tests), and that distance itself. */
inline float geodesic_nearest(const global BlackHole *holes, uint n, float3 anchor, float3 x,
                              float *horizons)
{
    float nearest = INFINITY;
    *horizons = INFINITY;
    for (uint i = 0u; i < n; i++) {
        float r = length(x - (xyz(holes[i].centre) - anchor));
        nearest = fmin(nearest, r);
        *horizons = fmin(*horizons, r / (2.0f * holes[i].centre.w));
    }
    return nearest;
}

/* One classic RK4 step of length dl in the affine parameter. */
inline void geodesic_rk4(const global BlackHole *holes, uint n, float3 anchor, float3 *x, float3 *v,
                         float dl)
{
    float3 x0 = *x, v0 = *v;
    float3 a1 = geodesic_acceleration(holes, n, anchor, x0, v0);
    float3 v2 = v0 + (0.5f * dl) * a1;
    float3 a2 = geodesic_acceleration(holes, n, anchor, x0 + (0.5f * dl) * v0, v2);
    float3 v3 = v0 + (0.5f * dl) * a2;
    float3 a3 = geodesic_acceleration(holes, n, anchor, x0 + (0.5f * dl) * v2, v3);
    float3 v4 = v0 + dl * a3;
    float3 a4 = geodesic_acceleration(holes, n, anchor, x0 + dl * v3, v4);
    *x = x0 + (dl / 6.0f) * (v0 + 2.0f * (v2 + v3) + v4);
    *v = v0 + (dl / 6.0f) * (a1 + 2.0f * (a2 + a3) + a4);
}

/* One step from (x, v): its length follows the nearest hole's distance. */
inline void geodesic_step(const global BlackHole *holes, uint n, float3 anchor, float3 *x, float3 *v)
{
    float horizons;
    float r = geodesic_nearest(holes, n, anchor, *x, &horizons);
    float f = GEODESIC_STEP_FRACTION * clamp(sqrt(horizons * 0.04f), 0.6f, 2.5f);
    geodesic_rk4(holes, n, anchor, x, v, f * r / length(*v));
}

/* Whether x (relative to the anchor) lies inside some hole's influence sphere. */
inline bool geodesic_inside(const global BlackHole *holes, uint n, float3 anchor, float3 x)
{
    for (uint i = 0u; i < n; i++) {
        float3 r = x - (xyz(holes[i].centre) - anchor);
        if (dot(r, r) < holes[i].normal.w * holes[i].normal.w)
            return true;
    }
    return false;
}

/* Where the straight ray x + t d (d unit) first enters an influence sphere, t >= 0; INFINITY when
 * it enters none. The hole entered is *entered. */
inline float geodesic_next_entry(const global BlackHole *holes, uint n, float3 x, float3 d,
                                 uint *entered)
{
    float best = INFINITY;
    for (uint i = 0u; i < n; i++) {
        float3 oc = x - xyz(holes[i].centre);
        float R = holes[i].normal.w;
        float b = dot(oc, d), c = dot(oc, oc) - R * R;
        float disc = b * b - c;
        if (disc < 0.0f || (b > 0.0f && c > 0.0f))
            continue; /* missed, or outside and moving away */
        float t = fmax(-b - sqrt(disc), 0.0f);
        if (t < best)
            best = t, *entered = i;
    }
    return best;
}

/* Where the chord from x0 to x1 (relative to the anchor, length len) crosses hole i's disk inside
 * its annulus: the distance along the chord, INFINITY if it does not; *q the crossing relative to
 * the hole, *r its radius. */
inline float disk_crossing(const global BlackHole *h, float3 centre, float3 x0, float3 x1, float len,
                           float3 *q, float *r)
{
    if (h->tangent.w == 0.0f)
        return INFINITY;
    float3 n = xyz(h->normal);
    float y0 = dot(x0 - centre, n), y1 = dot(x1 - centre, n);
    if ((y0 > 0.0f) == (y1 > 0.0f))
        return INFINITY;
    float s = y0 / (y0 - y1);
    *q = x0 + s * (x1 - x0) - centre;
    *q -= dot(*q, n) * n; /* onto the plane exactly */
    *r = length(*q);
    return *r >= h->radii.x && *r <= h->radii.y ? s * len : INFINITY;
}

/* The scene's world box (with a margin), which most chords miss: they skip the BVH. */
typedef struct {
    float3 lo, hi;
} SceneBox;

inline bool chord_meets_box(float3 o, float3 d, float len, SceneBox box)
{
    float3 inv = 1.0f / d;
    float3 t0 = (box.lo - o) * inv, t1 = (box.hi - o) * inv;
    float3 tn = fmin(t0, t1), tf = fmax(t0, t1);
    return fmax(fmax(tn.x, tn.y), fmax(tn.z, 0.0f)) <= fmin(fmin(tf.x, tf.y), fmin(tf.z, len));
}

/* The distance to the closest surface on the chord (o, d) closer than tmax, INFINITY if none: the
 * hit intersect_closest finds on the ray (o, d) (cut-outs passed with the same coins). */
inline float geodesic_chord_hit(const SceneView *scene, SceneBox box, float3 o, float3 d, float tmax,
                                float time, RngKey key, uint bounce)
{
    if (!chord_meets_box(o, d, tmax, box))
        return INFINITY;
    Hit h = PT_FEATURE(CUTOUT) ? trace_closest_through(scene, 0u, o, d, 0.0f, tmax, time, false,
                                                       rng_bounce_bits(key, bounce, DIM_OPACITY))
                               : scene_closest(scene, 0u, o, d, 0.0f, tmax, time);
    return h.prim != HIT_NONE ? h.t : INFINITY;
}

#if PT_FEATURE(BLACK_HOLES)

/* Counts a finished curved ray into the step statistics: totals per work-group (group[3], added
 * to stats once per group by the kernel), the histogram spread over its bins. */
inline void geodesic_count(local uint *group, global uint *stats, uint steps, bool captured)
{
    atomic_inc(&group[GEODESIC_STAT_RAYS]);
    atomic_add(&group[GEODESIC_STAT_STEPS], steps);
    if (captured)
        atomic_inc(&group[GEODESIC_STAT_CAPTURED]);
    atomic_inc(&stats[GEODESIC_STAT_HISTOGRAM + min(steps / GEODESIC_BIN_STEPS, GEODESIC_BINS - 1u)]);
}

PT_INLINE void integrate_path(constant RenderParams *p, const SceneView *scene,
                              PATH_STATE_PARAMS uint slot, const global BlackHole *holes, uint n,
                              SceneBox box, local uint *group, global uint *stats)
{
    uint depth = path_depth[slot];
    if (depth == 0u)
        return;
    float4 dir4 = ray_direction[slot];
    float3 world = xyz(ray_origin[slot]), d = xyz(dir4);
    uint anchor_hole = 0u;
    float t_entry = geodesic_next_entry(holes, n, world, d, &anchor_hole);
    if (t_entry == INFINITY)
        return; /* a straight ray: intersect_closest as always */
    uint k = sample_id[slot];
    RngKey key = path_rng_key(p, active_pixels, k);
    uint bounce = depth - 1u;
    float time = PT_FEATURE(MOTION) ? path_time[slot] : 0.0f;
    if (t_entry > 0.0f && geodesic_chord_hit(scene, box, world, d, t_entry, time, key, bounce) < INFINITY)
        return; /* a surface before the sphere */
    /* Integrate relative to the first hole entered (float keeps its precision near it). */
    float3 anchor = xyz(holes[anchor_hole].centre);
    float3 x = world + t_entry * d - anchor, v = d;
    float travelled = t_entry; /* along the curve, from the segment's start to x */
    float3 beta = xyz(throughput[slot]);
    uint steps = 0u, crossings = 0u;
    bool ended = false, captured = false;
    for (;;) {
        if (!geodesic_inside(holes, n, anchor, x)) {
            /* Straight on to the next sphere, if any (two holes). */
            float3 u = normalize(v);
            uint next;
            float t = geodesic_next_entry(holes, n, x + anchor, u, &next);
            if (t == INFINITY ||
                geodesic_chord_hit(scene, box, x + anchor, u, t, time, key, bounce) < INFINITY) {
                v = u;
                break;
            }
            x += (t + 1e-4f * holes[next].normal.w) * u;
            travelled += t + 1e-4f * holes[next].normal.w;
            v = u;
            continue;
        }
        if (steps == GEODESIC_MAX_STEPS) {
            ended = captured = true;
            break;
        }
        float3 x1 = x, v1 = v;
        geodesic_step(holes, n, anchor, &x1, &v1);
        steps++;
        float3 chord = x1 - x;
        float len = length(chord);
        float3 u = chord / len;
        float t_hit = geodesic_chord_hit(scene, box, x + anchor, u, len, time, key, bounce);
        for (uint i = 0u; i < n && !ended; i++) {
            float3 q;
            float r;
            float t_disk = disk_crossing(&holes[i], xyz(holes[i].centre) - anchor, x, x1, len, &q, &r);
            if (!(t_disk < t_hit))
                continue;
            float noise = disk_noise(&holes[i], q, r);
            float3 L = beta * disk_emission(&holes[i], r, noise);
            add_radiance(radiance, k, L);
            uint coin = hash_pcg(rng_bounce_bits(key, bounce, DIM_DISK_COIN) + crossings++ * 0x9e3779b9u);
            if (uint_to_unit(coin) < holes[i].radii.z * noise)
                ended = true;
        }
        if (ended)
            break;
        if (t_hit < INFINITY) {
            v = u;
            break; /* the chord is the ray intersect_closest traces */
        }
        x = x1, v = v1;
        travelled += len;
        float horizons;
        geodesic_nearest(holes, n, anchor, x, &horizons);
        if (horizons <= 1.0f + GEODESIC_HORIZON_EPSILON) {
            ended = captured = true;
            break;
        }
    }
    geodesic_count(group, stats, steps, captured);
    if (ended) {
        path_depth[slot] = 0u;
        hit[slot] = hit_pack(INFINITY, 0.0f, 0.0f, HIT_NONE);
        return;
    }
    ray_origin[slot] = ray_origin_pack(x + anchor, travelled);
    ray_direction[slot] = ray_direction_pack(normalize(v), ray_direction_pdf_w(dir4));
}

kernel void integrate_geodesic(constant RenderParams *p, SCENE_PARAMS PATH_STATE_PARAMS
                                   const global uint *active, uint n_active,
                               const global BlackHole *holes, uint num_holes, float4 box_lo,
                               float4 box_hi, global uint *stats)
{
    local uint group[3];
    for (uint j = get_local_id(0); j < 3u; j += get_local_size(0))
        group[j] = 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    uint i = get_global_id(0);
    SceneView scene = SCENE_VIEW;
    SceneBox box = {xyz(box_lo), xyz(box_hi)};
    if (i < n_active)
        integrate_path(p, &scene, PATH_STATE_ARGS active[i], holes, num_holes, box, group, stats);
    /* Every work item reaches this barrier: no early return above. */
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint j = get_local_id(0); j < 3u; j += get_local_size(0))
        if (group[j] > 0u)
            atomic_add(&stats[j], group[j]);
}

#endif
