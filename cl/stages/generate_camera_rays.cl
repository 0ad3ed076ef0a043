/* SPDX-License-Identifier: MIT */
/* generate_camera_rays: starts the window's samples first_sample .. first_sample + n_new - 1 in
 * free slots and appends those slots to the active list after its n_live live entries. The free
 * slots are free_slots[0 .. n_new) (from compactor_enqueue_free), or slots 0 .. n_new - 1 when
 * fresh != 0 (an empty pool: every slot is free).
 * Reads: params, free_slots. Writes: sample_id, ray_direction (pdf_w = 0: the camera ray counts as
 * specular for MIS), ray_origin and throughput = 1 (in the camera's medium) unless
 * camera_state_implied (path_state.cl), radiance[k] = 0 (shadow_contribution not: a free slot
 * waits for no shadow ray, render.h),
 * path_depth = 1 (the camera ray), path_time (PT_FEATURE(MOTION): the path's shutter fraction,
 * camera_time), active[n_live + j].
 * Next: intersect_closest. */

/* Starts window sample k's camera path in slot (shared with megakernel.cl, whose packets read
 * ray_origin directly: store_implied stores the lanes that camera_state_implied spares). */
PT_INLINE void start_path(constant RenderParams *p, PATH_STATE_PARAMS uint slot, uint k,
                          bool store_implied)
{
    uint pixel = window_pixel(p, active_pixels, k), sample = window_sample(p, k);
    float3 origin, dir;
    camera_sample(p, pixel, sample, &origin, &dir);
    ray_direction[slot] = ray_direction_pack(dir, 0.0f);
    if (store_implied || !camera_state_implied(p)) {
        ray_origin[slot] = ray_origin_pack_eta(p, origin, 1.0f);
        throughput[slot] = camera_throughput(p);
    }
    sample_id[slot] = k;
    path_depth[slot] = 1u;
    /* Unread without moving instances (intersect_*, shade_surface take 0): no store. */
    if (PT_FEATURE(MOTION))
        path_time[slot] = camera_time(p, pixel, sample);
    radiance[k] = (float4)(0.0f);
}

kernel void generate_camera_rays(constant RenderParams *p, PATH_STATE_PARAMS global uint *active,
                                 const global uint *free_slots, uint n_live, uint first_sample,
                                 uint n_new, uint fresh)
{
    uint j = get_global_id(0);
    if (j >= n_new)
        return;
    uint slot = fresh ? j : free_slots[j];
    start_path(p, PATH_STATE_ARGS slot, first_sample + j, false);
    active[n_live + j] = slot;
}
