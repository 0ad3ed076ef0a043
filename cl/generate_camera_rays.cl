/* SPDX-License-Identifier: MIT */
/* generate_camera_rays: starts one path per slot of the batch.
 * Reads: params. Writes: ray_origin, ray_direction (w = 0: the camera ray counts as specular for
 * MIS), throughput = 1, radiance = 0, alive = 1, active[slot] = slot. Next: intersect_closest. */

kernel void generate_camera_rays(constant RenderParams *p, PATH_STATE_PARAMS global uint *active)
{
    uint slot = get_global_id(0);
    if (slot >= p->batch_size)
        return;
    uint pixel = slot_pixel(p, slot), sample = slot_sample(p, slot);
    float2 jitter = (float2)(rng_uniform(pixel, sample, DIM_CAMERA_JITTER_X, p->seed),
                             rng_uniform(pixel, sample, DIM_CAMERA_JITTER_Y, p->seed));
    float2 lens = (float2)(rng_uniform(pixel, sample, DIM_LENS_U, p->seed),
                           rng_uniform(pixel, sample, DIM_LENS_V, p->seed));
    float3 origin, dir;
    camera_ray(p, pixel % p->width, pixel / p->width, jitter, lens, &origin, &dir);
    ray_origin[slot] = (float4)(origin, 0.0f);
    ray_direction[slot] = (float4)(dir, 0.0f);
    throughput[slot] = (float4)(1.0f, 1.0f, 1.0f, 0.0f);
    radiance[slot] = (float4)(0.0f);
    shadow_contribution[slot] = (float4)(0.0f);
    alive[slot] = 1u;
    active[slot] = slot;
}
