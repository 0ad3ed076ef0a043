/* SPDX-License-Identifier: MIT */
/* phase_test.cl: kernels for tests/test_medium_phase.c (cl/medium/phase.cl). */

/* phase_hg_sample(g, d, u[2i], u[2i + 1]) into out[4i .. 4i + 3]: wi's xyz and the pdf. */
kernel void phase_test_sample(float g, float4 d, const global float *u, uint count,
                              global float *out)
{
    uint i = get_global_id(0);
    if (i >= count)
        return;
    float pdf;
    float3 wi = phase_hg_sample(g, xyz(d), u[2 * i], u[2 * i + 1], &pdf);
    vstore4((float4)(wi, pdf), i, out);
}

/* phase_hg(g, cos[i]) into out[i]. */
kernel void phase_test_eval(float g, const global float *cos_theta, uint count, global float *out)
{
    uint i = get_global_id(0);
    if (i >= count)
        return;
    out[i] = phase_hg(g, cos_theta[i]);
}
