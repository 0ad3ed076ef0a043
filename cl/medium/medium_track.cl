/* SPDX-License-Identifier: MIT */
/* medium_track.cl: null-scattering tracking in a medium (Miller et al. 2019; pbrt-v4's volpath).
 * Tentative collisions are drawn against a majorant sigma_bar (per brick for grids, medium_grid.cl;
 * the largest channel of sigma_t for homogeneous media) and each is an absorption, a scattering or
 * a null collision. Chromatic media (sigma per channel) use spectral tracking with history-aware
 * probabilities (Kutz et al. 2017, "Spectral and decomposition tracking"): the probabilities are
 * the channel means of sigma times the path's weight, and the weight takes the per-channel ratio,
 * so no channel is biased and a grey medium does plain delta tracking with weight 1. Shadow rays
 * use ratio tracking (Novak et al. 2014) in grids and the closed form in homogeneous media. */

#define MEDIUM_EVENT_NONE 0u    /* the segment reached its end (the surface, or the sky) */
#define MEDIUM_EVENT_SCATTER 1u /* a real scattering at *t_event */
#define MEDIUM_EVENT_ABSORB 2u  /* absorbed: the path ends */
/* Tentative collisions one segment may take before it gives up (absorbed): a bound on the work of
 * a ray through a huge optically thick medium, reached only by paths whose weight is long gone. */
#define MEDIUM_STEP_LIMIT 65536u

/* The uniform numbers of one segment's tracking: the first is the bounce's DIM_MEDIUM number (so
 * that the first free-flight distance is stratified by the sampler), the rest a hashed stream. */
typedef struct {
    uint first, state, drawn;
} MediumRng;

inline MediumRng medium_rng(uint bits, uint salt)
{
    MediumRng r = {bits, hash_pcg(bits ^ salt), 0u};
    return r;
}

inline float medium_rng_next(MediumRng *r)
{
    if (r->drawn++ == 0u)
        return uint_to_unit(r->first);
    r->state = r->state * 747796405u + 2891336453u;
    return uint_to_unit(hash_pcg(r->state));
}

inline float mean3(float3 v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }

/* The medium in slot (1 + its index; MEDIUM_SLOT_WORLD is resolved by the caller). */
inline const global Medium *medium_at_slot(const SceneView *scene, uint slot)
{
    return &scene->media[slot - 1u];
}

/* Whether paths in medium slot need tracking (it scatters or emits, or its density varies);
 * otherwise it only absorbs, homogeneously, in closed form (through_medium). */
inline bool medium_tracks(const SceneView *scene, uint slot)
{
    if (slot == 0u)
        return false;
    const global Medium *m = medium_at_slot(scene, slot);
    if (m->flags & (MEDIUM_FLAG_SCATTERS | MEDIUM_FLAG_EMITS))
        return true;
    return PT_FEATURE(GRID_MEDIA) && m->type == MEDIUM_GRID;
}

/* The pieces of [0, tmax) with a constant density majorant: one piece of majorant 1 in a
 * homogeneous medium; the brick cells along the ray in a grid. */
typedef struct {
    GridWalk walk;
    float start, end, majorant;
    bool grid;
} MajorantPieces;

inline bool majorant_first(const SceneView *scene, const global Medium *m, float3 o, float3 d,
                           float tmax, MajorantPieces *s)
{
    s->grid = PT_FEATURE(GRID_MEDIA) && m->type == MEDIUM_GRID;
    if (!s->grid) {
        s->start = 0.0f, s->end = tmax, s->majorant = 1.0f;
        return tmax > 0.0f;
    }
    if (!grid_walk_start(m, o, d, tmax, &s->walk) ||
        !grid_walk_piece(scene, m, &s->walk, &s->end, &s->majorant))
        return false;
    s->start = s->walk.t;
    return true;
}

inline bool majorant_next(const SceneView *scene, const global Medium *m, MajorantPieces *s)
{
    if (!s->grid)
        return false;
    grid_walk_next(m, &s->walk, s->end);
    if (!grid_walk_piece(scene, m, &s->walk, &s->end, &s->majorant))
        return false;
    s->start = s->walk.t;
    return true;
}

inline float medium_density(const SceneView *scene, const global Medium *m, const MajorantPieces *s,
                            float3 p)
{
    return s->grid ? grid_density(scene, m, grid_to_index_point(m, p)) : 1.0f;
}

/* Moves s to the next tentative collision along the pieces (a free flight against each piece's
 * majorant sigma_bar, the piece's density majorant times st_max; a flight past the piece's end
 * starts afresh at the next, as exponential flights may): true with the collision's t in s->start
 * and its sigma_bar, false once the pieces are passed. */
inline bool majorant_collision(const SceneView *scene, const global Medium *m, MajorantPieces *s,
                               float st_max, MediumRng *rng, float *sigma_bar)
{
    for (;;) {
        *sigma_bar = s->majorant * st_max;
        float t = *sigma_bar > 0.0f ? s->start - log(1.0f - medium_rng_next(rng)) / *sigma_bar
                                    : INFINITY;
        if (t < s->end) {
            s->start = t;
            return true;
        }
        if (!majorant_next(scene, m, s))
            return false;
    }
}

/* Tracks the segment o + t d, t in [0, tmax), through medium m for the path of weight *beta:
 * returns MEDIUM_EVENT_* (a scattering's distance in *t_event), updates *beta by the tracking's
 * weights and adds to *emitted what the medium emits toward the path's start (the collision
 * estimator sigma_a Le / sigma_bar at each tentative collision, times the weight there). */
PT_INLINE uint medium_track(const SceneView *scene, const global Medium *m, float3 o, float3 d,
                            float tmax, MediumRng *rng, float3 *beta, float3 *emitted,
                            float *t_event)
{
    float3 sa = xyz(m->sigma_a), ss = xyz(m->sigma_s), le = xyz(m->emission);
    float st_max = max3(sa + ss);
    bool emits = (m->flags & MEDIUM_FLAG_EMITS) != 0u;
    MajorantPieces s;
    if (!majorant_first(scene, m, o, d, tmax, &s))
        return MEDIUM_EVENT_NONE;
    for (uint step = 0u; step < MEDIUM_STEP_LIMIT; step++) {
        float sigma_bar;
        if (!majorant_collision(scene, m, &s, st_max, rng, &sigma_bar))
            return MEDIUM_EVENT_NONE;
        float t = s.start;
        float density = medium_density(scene, m, &s, o + t * d);
        float3 ca = sa * density, cs = ss * density;
        float3 cn = fmax(sigma_bar - (ca + cs), 0.0f);
        if (emits)
            *emitted += *beta * ca * le / sigma_bar;
        float pa = mean3(ca * *beta), ps = mean3(cs * *beta), pn = mean3(cn * *beta);
        float c = pa + ps + pn;
        if (!(c > 0.0f))
            return MEDIUM_EVENT_ABSORB;
        float u = medium_rng_next(rng) * c;
        if (u < pa)
            return MEDIUM_EVENT_ABSORB;
        if (u < pa + ps) {
            *beta *= cs * (c / (sigma_bar * ps));
            *t_event = t;
            return MEDIUM_EVENT_SCATTER;
        }
        *beta *= cn * (c / (sigma_bar * pn));
    }
    return MEDIUM_EVENT_ABSORB;
}

/* Transmittance of medium m along o + t d, t in [0, tmax): exact in a homogeneous medium, ratio
 * tracking (with Russian roulette once it falls below 0.1) in a grid. */
PT_INLINE float3 medium_transmittance(const SceneView *scene, const global Medium *m, float3 o,
                                      float3 d, float tmax, MediumRng *rng)
{
    float3 st = xyz(m->sigma_a) + xyz(m->sigma_s);
    if (!(PT_FEATURE(GRID_MEDIA) && m->type == MEDIUM_GRID))
        return dielectric_transmittance(st, tmax); /* Beer-Lambert, exp(-st tmax) per channel */
    float st_max = max3(st);
    float3 tr = (float3)(1.0f);
    MajorantPieces s;
    if (!majorant_first(scene, m, o, d, tmax, &s))
        return tr;
    for (uint step = 0u; step < MEDIUM_STEP_LIMIT; step++) {
        float sigma_bar;
        if (!majorant_collision(scene, m, &s, st_max, rng, &sigma_bar))
            return tr;
        float density = medium_density(scene, m, &s, o + s.start * d);
        tr *= fmax(1.0f - density * st / sigma_bar, 0.0f);
        float q = max3(tr);
        if (q < 0.1f) {
            if (medium_rng_next(rng) >= q)
                return (float3)(0.0f);
            tr /= q;
        }
    }
    return (float3)(0.0f);
}
