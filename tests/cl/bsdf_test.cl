/* SPDX-License-Identifier: MIT */
/* bsdf_test.cl: kernels for tests/test_bsdf_*.c. The material (no textures) becomes a Bsdf through
 * bsdf_at, as shade_surface does; directions are in the local shading frame. */

inline float bsdf_test_uniform(uint *state)
{
    /* PCG-style hash chain: independent of the renderer's RNG, 24 bits per number. */
    uint s = *state = *state * 747796405u + 2891336453u;
    uint w = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    w = (w >> 22u) ^ w;
    return (float)(w >> 8) * 0x1p-24f;
}

inline Bsdf bsdf_test_bsdf(const global Material *material)
{
    SceneView scene = {0};
    scene.materials = material;
    return bsdf_at(&scene, material[0], (float2)(0.0f), (float3)(0.0f));
}

/* Sample i of wo (xyz; w != 0: front): wi and pdf, weight and flags. */
kernel void bsdf_test_sample(const global Material *material, float4 wo_front, uint seed, uint n,
                             global float4 *wi_pdf, global float4 *weight_flags)
{
    uint i = get_global_id(0);
    if (i >= n)
        return;
    Bsdf b = bsdf_test_bsdf(material);
    uint state = i * 2654435761u ^ (seed * 0x9e3779b9u + 0x7f4a7c15u);
    float u1 = bsdf_test_uniform(&state), u2 = bsdf_test_uniform(&state);
    float u3 = bsdf_test_uniform(&state);
    BsdfSample s = bsdf_sample(&b, xyz(wo_front), wo_front.w != 0.0f, u1, u2, u3);
    wi_pdf[i] = (float4)(s.wi, s.pdf_w);
    weight_flags[i] = (float4)(s.weight, (float)s.flags);
}

/* eval at pair i: wo[i] (w != 0: front), wi[i]; out: f |cos wi| and the pdf. */
kernel void bsdf_test_eval(const global Material *material, const global float4 *wo,
                           const global float4 *wi, uint n, global float4 *out)
{
    uint i = get_global_id(0);
    if (i >= n)
        return;
    Bsdf b = bsdf_test_bsdf(material);
    float pdf;
    float3 f_cos = bsdf_eval(&b, xyz(wo[i]), xyz(wi[i]), wo[i].w != 0.0f, &pdf);
    out[i] = (float4)(f_cos, pdf);
}
