/* SPDX-License-Identifier: MIT */
/* light_sample.cl: next-event estimation on emissive triangles (one-sided: they emit on the side of
 * their counter-clockwise normal), analytic lights (light_analytic.cl) and the environment map,
 * chosen through the power-proportional
 * alias table. */

/* The alias table's choice from two independent random numbers: the entry, uniform over
 * [0, num_lights) from 32 bits by a multiply-high (each index gets floor or ceil of 2^32 / n of the
 * values: exact for powers of two, within n / 2^32 relative otherwise), then the entry or its alias
 * by the coin. (One uniform for both leaves the coin the bits the index did not use: 4 of 24 at
 * 2^20 emitters, a keep probability off by up to 1/16.) */
inline LightEntry light_pick(const global LightEntry *lights, uint num_lights, uint pick_bits,
                             float u_coin)
{
    LightEntry entry = lights[mul_hi(pick_bits, num_lights)];
    return u_coin < entry.prob ? entry : lights[entry.alias];
}

/* pick_bits, u_coin choose the light; env_pick_bits, env_coin the environment map's texel when it
 * is chosen (independent numbers: the light's are spent on the light); u1, u2 the point on it. */
PT_INLINE LightSample light_sample(const SceneView *scene, const EnvMap *env, uint num_lights,
                                   float3 from, uint pick_bits, float u_coin, uint env_pick_bits,
                                   float env_coin, float u1, float u2)
{
    const global LightEntry *lights = scene->lights;
    const global float4 *positions = scene->positions;
    const global Triangle *triangles = scene->triangles;
    const global uint *material_ids = scene->material_ids;
    const global Material *materials = scene->materials;
    LightSample ls;
    LightEntry entry = light_pick(lights, num_lights, pick_bits, u_coin);
    if (PT_FEATURE_ENV && entry.triangle == LIGHT_ENVIRONMENT) {
        EnvSample es = env_sample(env, env_pick_bits, env_coin, u1, u2);
        ls.position = from;
        ls.normal = -es.direction;
        ls.direction = es.direction;
        ls.at_infinity = 1u;
        ls.delta = 0u;
        ls.radiance = es.radiance;
        ls.pdf_w = entry.pdf * es.pdf_w;
        return ls;
    }
    if (PT_FEATURE_ANALYTIC && entry.triangle >= LIGHT_ANALYTIC_BASE)
        return analytic_light_sample(scene->analytic_lights[entry.triangle - LIGHT_ANALYTIC_BASE],
                                     entry.pdf, from, u1, u2);
    ls.at_infinity = 0u;
    ls.delta = 0u;
    uint4 tri = triangles[entry.triangle].v;
    float3 p0 = xyz(positions[tri.x]), p1 = xyz(positions[tri.y]), p2 = xyz(positions[tri.z]);
    float2 b = sample_triangle_uniform(u1, u2);
    ls.position = (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
    float3 cross_n = cross(p1 - p0, p2 - p0);
    float double_area = length(cross_n);
    float3 n_light = cross_n / double_area;
    ls.normal = n_light;
    float3 to_light = ls.position - from;
    float dist2 = dot(to_light, to_light);
    ls.direction = to_light * rsqrt(dist2);
    float cos_light = -dot(to_light, n_light) * rsqrt(dist2);
    if (!(cos_light > 0.0f) || !(double_area > 0.0f)) {
        ls.radiance = (float3)(0.0f);
        ls.pdf_w = 0.0f;
        return ls;
    }
    Material m = materials[material_ids[entry.triangle]];
    ls.radiance = xyz(m.emission);
    bool textured = PT_HAS_MATERIAL_FEATURE(EMISSION_TEXTURE) && m.tex[MATERIAL_TEX_EMISSION] != NO_TEXTURE;
    bool cutout = PT_FEATURE_CUTOUT && (m.flags & MATERIAL_FLAG_CUTOUT);
    if (textured || cutout) {
        float2 uv = (float2)(b.x, b.y);
        if (tri.w & TRIANGLE_HAS_UVS)
            uv = (1.0f - b.x - b.y) * scene->uvs[tri.x] + b.x * scene->uvs[tri.y] + b.y * scene->uvs[tri.z];
        if (textured)
            ls.radiance *= xyz(texture_eval(scene, m.tex[MATERIAL_TEX_EMISSION], uv, ls.position));
        /* A ray meets a cut-out emitter with probability opacity (the rest pass through), so
         * what BSDF sampling sees on average is emission x opacity: light sampling agrees. */
        if (cutout)
            ls.radiance *= material_opacity(scene, m, uv, ls.position);
    }
    ls.pdf_w = entry.pdf * (2.0f / double_area) * dist2 / cos_light;
    return ls;
}
