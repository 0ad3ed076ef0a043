/* SPDX-License-Identifier: MIT */
/* instance_shading_test.cl: kernels for tests/test_instance_shading.c, which builds them with
 * every feature (instances and motion among them; they compile without too, in the tests' shared
 * program). */

/* surface_at of hits queries[i] = (u, v, as_float(triangle), as_float(instance)) at `time`:
 * out[4 i ..] = position, object_position, geometric_normal, shading_normal. */
kernel void instance_shading_test_surface(SCENE_PARAMS const global float4 *queries, uint n,
                                          float time, global float4 *out)
{
    SceneView scene = SCENE_VIEW;
    uint i = get_global_id(0);
    if (i >= n)
        return;
    float4 q = queries[i];
    Hit hit = {1.0f, q.x, q.y, as_uint(q.z), as_uint(q.w)};
    SurfaceHit s = surface_at(&scene, hit, time);
    out[4 * i] = (float4)(s.position, 0.0f);
    out[4 * i + 1] = (float4)(s.object_position, 0.0f);
    out[4 * i + 2] = (float4)(s.geometric_normal, 0.0f);
    out[4 * i + 3] = (float4)(s.shading_normal, 0.0f);
}

/* Light sample i from `from` at `time` (numbers as shade_surface draws them at bounce 0 of pixel
 * i), and the same emitter point as a BSDF ray would meet it: surface_at of the picked (instance,
 * triangle) at the sample's barycentrics, and the pdf emission_seen weighs that hit with.
 * out[4 i ..] = (ls.position, ls.pdf_w), (ls.normal, as_float(instance)),
 * (hit position, hit light pdf), (hit geometric normal, ls.radiance.x). */
kernel void instance_shading_test_light(constant RenderParams *p, SCENE_PARAMS float4 from,
                                        float time, uint n, global float4 *out)
{
    SceneView scene = SCENE_VIEW;
    uint i = get_global_id(0);
    if (i >= n)
        return;
    EnvMap env = env_map(p, &scene);
    RngKey key = rng_path_key(i, 0u, p->seed);
    uint pick = rng_bounce_bits(key, 0u, DIM_LIGHT_PICK);
    float coin = rng_bounce(key, 0u, DIM_LIGHT_COIN);
    float u1 = rng_bounce(key, 0u, DIM_LIGHT_U), u2 = rng_bounce(key, 0u, DIM_LIGHT_V);
    LightSample ls = light_sample(&scene, &env, p->scene.num_emissive, xyz(from), time, key, 0u);
    LightEntry entry = light_pick(scene.lights, p->scene.num_emissive, pick, coin);
    float2 b = sample_triangle_uniform(u1, u2);
    float t = length(ls.position - xyz(from));
    Hit hit = {t, b.x, b.y, entry.triangle, entry.instance};
    SurfaceHit s = surface_at(&scene, hit, time);
    Material m = scene.materials[s.material];
    float cos_light = dot(-ls.direction, s.geometric_normal);
    float hit_pdf = emitter_light_pdf(p, &scene, m, hit, &s, t, cos_light);
    out[4 * i] = (float4)(ls.position, ls.pdf_w);
    out[4 * i + 1] = (float4)(ls.normal, as_float(entry.instance));
    out[4 * i + 2] = (float4)(s.position, hit_pdf);
    out[4 * i + 3] = (float4)(s.geometric_normal, ls.radiance.x);
}
