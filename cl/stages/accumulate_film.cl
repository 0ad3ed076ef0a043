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
    uint num_pixels = p->width * p->height;
    if (i >= min(p->batch_size, num_pixels))
        return;
    ulong3 sum = (ulong3)(0);
    ulong count = 0;
    for (uint k = i; k < p->batch_size; k += num_pixels) {
        float3 L = xyz(radiance[k]);
        if (isfinite(L.x) && isfinite(L.y) && isfinite(L.z))
            sum = add_sat(sum, film_fixed_point(L));
        else
            atomic_inc(&counters[COUNTER_NONFINITE]);
        count++;
    }
    uint pixel = (p->batch_start + i) % num_pixels;
    film[pixel] = add_sat(film[pixel], (ulong4)(sum, count));
}
