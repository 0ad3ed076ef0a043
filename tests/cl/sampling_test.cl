/* SPDX-License-Identifier: MIT */
/* sampling_test.cl: kernels for tests/test_sampling_trig.c. */

/* cos_sin_turns(turns[i]) into out[2i], out[2i + 1]. */
kernel void sampling_test_cos_sin_turns(const global float *turns, uint count, global float *out)
{
    uint i = get_global_id(0);
    if (i >= count)
        return;
    float2 cs = cos_sin_turns(turns[i]);
    out[2 * i] = cs.x;
    out[2 * i + 1] = cs.y;
}

/* sample_disk_concentric(u[2i], u[2i + 1]) into out[2i], out[2i + 1]. */
kernel void sampling_test_disk(const global float *u, uint count, global float *out)
{
    uint i = get_global_id(0);
    if (i >= count)
        return;
    float2 d = sample_disk_concentric(u[2 * i], u[2 * i + 1]);
    out[2 * i] = d.x;
    out[2 * i + 1] = d.y;
}
