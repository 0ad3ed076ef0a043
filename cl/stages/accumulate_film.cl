/* SPDX-License-Identifier: MIT */
/* accumulate_film: adds the window's finished samples to the film, one work item per pixel of the
 * window. Each sample becomes fixed point (FILM_* in shared.h) and the sums are integers, so the
 * film's bits do not depend on the window split, the pool or the order of the samples.
 * Reads: radiance (per window sample). Writes: film[pixel] += (sums, samples in w);
 * counters[COUNTER_NONFINITE] counts samples whose radiance was NaN or Inf: they count as black
 * samples, never reach the film. */

/* A sample's radiance in film steps: clamped to [0, FILM_SAMPLE_MAX], rounded to the nearest. */
inline ulong3 film_fixed_point(float3 L)
{
    return convert_ulong3_rte(clamp(L, 0.0f, FILM_SAMPLE_MAX) * (float)(1u << FILM_FRACTION_BITS));
}

kernel void accumulate_film(constant RenderParams *p, PATH_STATE_PARAMS global ulong4 *film,
                            global uint *counters)
{
    uint i = get_global_id(0);
    uint n = p->window_pixels;
    if (i >= min(p->window_size, n))
        return;
    ulong3 sum = (ulong3)(0);
    ulong count = 0;
    for (uint k = i; k < p->window_size; k += n) {
        float3 L = xyz(radiance[k]);
        if (isfinite(L.x) && isfinite(L.y) && isfinite(L.z))
            sum = add_sat(sum, film_fixed_point(L));
        else
            atomic_inc(&counters[COUNTER_NONFINITE]);
        count++;
    }
    uint pixel = p->pixel_offset + (p->window_start + i) % n;
    film[pixel] = add_sat(film[pixel], (ulong4)(sum, count));
}

/* ---- With the second moments (RenderSettings.moments) ---------------------------------------- */

/* 128-bit unsigned integers as ulong2 (x: low word, y: high word): the moments' sums. */
inline ulong2 u128_mul(ulong a, ulong b) { return (ulong2)(a * b, mul_hi(a, b)); }

inline ulong2 u128_add(ulong2 a, ulong2 b)
{
    ulong lo = a.x + b.x;
    return (ulong2)(lo, a.y + b.y + (lo < a.x ? 1ul : 0ul));
}

/* a + b, saturating at 2^128 - 1 like the film's words (never reached below 2^40 samples). */
inline ulong2 u128_add_sat(ulong2 a, ulong2 b)
{
    ulong2 s = u128_add(a, b);
    bool wrapped = s.y < a.y || (s.y == a.y && s.x < a.x); /* unsigned: wrapped iff s < a */
    return wrapped ? (ulong2)(ULONG_MAX) : s;
}

/* accumulate_film, and per channel the sum of the squares of the same fixed-point samples into
 * moments (MOMENT_WORDS per pixel, shared.h). It also serves adaptive sampling, whose windows
 * cycle over the active pixels (window_pixel): one work item per pixel of the window still. */
kernel void accumulate_film_moments(constant RenderParams *p, PATH_STATE_PARAMS global ulong4 *film,
                                    global uint *counters, global ulong2 *moments)
{
    uint i = get_global_id(0);
    uint n = p->window_pixels;
    if (i >= min(p->window_size, n))
        return;
    ulong3 sum = (ulong3)(0);
    ulong2 squares[3] = {(ulong2)(0), (ulong2)(0), (ulong2)(0)};
    ulong count = 0;
    for (uint k = i; k < p->window_size; k += n) {
        float3 L = xyz(radiance[k]);
        if (isfinite(L.x) && isfinite(L.y) && isfinite(L.z)) {
            ulong3 x = film_fixed_point(L);
            sum = add_sat(sum, x);
            squares[0] = u128_add(squares[0], u128_mul(x.x, x.x));
            squares[1] = u128_add(squares[1], u128_mul(x.y, x.y));
            squares[2] = u128_add(squares[2], u128_mul(x.z, x.z));
        } else {
            atomic_inc(&counters[COUNTER_NONFINITE]);
        }
        count++;
    }
    uint pixel = window_pixel(p, active_pixels, i);
    film[pixel] = add_sat(film[pixel], (ulong4)(sum, count));
    for (uint c = 0; c < 3; c++)
        moments[3 * pixel + c] = u128_add_sat(moments[3 * pixel + c], squares[c]);
}
