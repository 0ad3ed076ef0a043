/* SPDX-License-Identifier: MIT */
/* adaptive_select: adaptive sampling's decision at a sample-count boundary (host/render/adaptive.c),
 * after film_variance. An active pixel stays active unless all its neighbours (the 8 around it
 * inside the film; the pixel itself only on a 1 x 1 film) have a relative error below threshold.
 * Why not its own error: a pixel's sample count then never depends on its own samples, only on
 * its neighbours' (independent RNG streams), so the mean of its samples stays unbiased; a pixel
 * judged by itself would stop early exactly when its first samples happened to agree (a caustic
 * not yet found), darkening it. Noise is spatially coherent, so the neighbours speak for it.
 * Reads: variance (w: relative error), pixel_flags. Writes: pixel_flags (1 active, 0 done). */

kernel void adaptive_select(uint width, uint height, float threshold,
                            const global float4 *variance, global uint *pixel_flags)
{
    uint pixel = get_global_id(0);
    if (pixel >= width * height || pixel_flags[pixel] == 0u)
        return;
    int x = (int)(pixel % width), y = (int)(pixel / width);
    bool any = false, converged = true; /* a NaN error is never below: it keeps the pixel */
    for (int dy = -1; dy <= 1; dy++)
        for (int dx = -1; dx <= 1; dx++) {
            int nx = x + dx, ny = y + dy;
            if ((dx != 0 || dy != 0) && nx >= 0 && ny >= 0 && nx < (int)width && ny < (int)height) {
                any = true;
                converged = converged && variance[(uint)ny * width + (uint)nx].w < threshold;
            }
        }
    if (!any)
        converged = variance[pixel].w < threshold;
    pixel_flags[pixel] = converged ? 0u : 1u;
}
