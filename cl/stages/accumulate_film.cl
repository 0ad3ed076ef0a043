/* SPDX-License-Identifier: MIT */
/* accumulate_film: adds the window's finished samples to the film, one work item per pixel of the
 * window, summing that pixel's samples in a fixed order (deterministic, no atomics on floats).
 * Reads: radiance (per window sample). Writes: film[pixel] += (sum, samples in w); counters[COUNTER_NONFINITE] counts
 * samples whose radiance was NaN or Inf: they count as black samples, never reach the film. */

kernel void accumulate_film(constant RenderParams *p, PATH_STATE_PARAMS global float4 *film,
                            global uint *counters)
{
    uint i = get_global_id(0);
    uint num_pixels = p->width * p->height;
    if (i >= min(p->batch_size, num_pixels))
        return;
    float3 sum = (float3)(0.0f);
    float count = 0.0f;
    for (uint k = i; k < p->batch_size; k += num_pixels) {
        float3 L = xyz(radiance[k]);
        if (isfinite(L.x) && isfinite(L.y) && isfinite(L.z))
            sum += L;
        else
            atomic_inc(&counters[COUNTER_NONFINITE]);
        count += 1.0f;
    }
    uint pixel = (p->batch_start + i) % num_pixels;
    film[pixel] += (float4)(sum, count);
}
