/* SPDX-License-Identifier: MIT */
/* light_sample.cl: next-event estimation on emissive triangles (one-sided: they emit on the side of
 * their counter-clockwise normal), analytic lights (light_analytic.cl) and the environment map,
 * chosen through the power-proportional
 * alias table.
 *
 * With instances (PT_FEATURE(INSTANCES)) a table entry is an (instance, triangle) pair: the
 * triangle's object-space point goes to world through the instance at the path's time, its normal
 * through the inverse transpose (a mirrored instance's emitters shine where its normals point,
 * surface.cl), and the density per unit world area is entry.pdf / (its world area at that time).
 * The table's weights (host/scene/lights.c) use a moving instance's transform at shutter open:
 * emitter_area_ratio gives what an emitter hit by a BSDF ray must scale its MIS pdf by. */

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

/* Twice the world area of object-space edges e1, e2 under the linear part of m. */
inline float affine_double_area(Affine m, float3 e1, float3 e2)
{
    return length(cross(affine_vector(m, e1), affine_vector(m, e2)));
}

/* area at shutter open / area now of triangle prim of instance `instance`, whose transform now is
 * to_world (the hit's): the light table weighed a moving instance's triangles by their area at
 * open, so picking one and then a point on it has density entry.pdf / area now per unit area,
 * which is emission.w / total power x this ratio. 1 for a static instance. */
inline float emitter_area_ratio(const SceneView *scene, uint prim, uint instance, Affine to_world)
{
    const global Instance *inst = &scene->instances[instance];
    if (!PT_FEATURE(MOTION) || inst->motion == INSTANCE_STATIC)
        return 1.0f;
    uint4 tri = scene->triangles[prim].v;
    float3 p0 = xyz(scene->positions[tri.x]);
    float3 e1 = xyz(scene->positions[tri.y]) - p0, e2 = xyz(scene->positions[tri.z]) - p0;
    Affine open = {inst->to_world[0], inst->to_world[1], inst->to_world[2]};
    float now = affine_double_area(to_world, e1, e2);
    return now > 0.0f ? affine_double_area(open, e1, e2) / now : 1.0f;
}

/* A light point seen from `from` for bounce `bounce` of the path with key `key`: its dimensions
 * DIM_LIGHT_PICK and DIM_LIGHT_COIN choose the light, DIM_LIGHT_U and DIM_LIGHT_V the point on it
 * (on the environment map: the texel and the point in it, env_sample). time: the path's shutter fraction (where a moving
 * instance's emitters are). */
PT_INLINE LightSample light_sample(const SceneView *scene, const EnvMap *env, uint num_lights,
                                   float3 from, float time, RngKey key, uint bounce)
{
    const global LightEntry *lights = scene->lights;
    const global float4 *positions = scene->positions;
    const global Triangle *triangles = scene->triangles;
    const global uint *material_ids = scene->material_ids;
    const global Material *materials = scene->materials;
    LightSample ls;
    /* DIM_LIGHT_U, _V, _PICK, _COIN: one Sobol tuple, so the point is stratified with the pick. */
    uint4 bits = rng_bounce_bits4(key, bounce, DIM_LIGHT_U);
    LightEntry entry = light_pick(lights, num_lights, bits.z, uint_to_unit(bits.w));
    float u1 = uint_to_unit(bits.x), u2 = uint_to_unit(bits.y);
    if (PT_FEATURE(ENV) && entry.triangle == LIGHT_ENVIRONMENT) {
        EnvSample es = env_sample(env, bits.x, bits.y);
        ls.position = from;
        ls.normal = -es.direction;
        ls.direction = es.direction;
        ls.at_infinity = 1u;
        ls.delta = 0u;
        ls.radiance = es.radiance;
        ls.pdf_w = entry.pdf * es.pdf_w;
        return ls;
    }
    if (PT_FEATURE(ANALYTIC) && entry.triangle >= LIGHT_ANALYTIC_BASE)
        return analytic_light_sample(scene->analytic_lights[entry.triangle - LIGHT_ANALYTIC_BASE],
                                     entry.pdf, from, u1, u2);
    ls.at_infinity = 0u;
    ls.delta = 0u;
    uint4 tri = triangles[entry.triangle].v;
    float3 p0 = xyz(positions[tri.x]), p1 = xyz(positions[tri.y]), p2 = xyz(positions[tri.z]);
    float2 b = sample_triangle_uniform(u1, u2);
    float3 object_position = (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
    float3 cross_n = cross(p1 - p0, p2 - p0);
    float double_area;
    float3 n_light;
    if (PT_FEATURE(INSTANCES)) {
        Affine to_world, to_object;
        instance_at(scene->instances, scene->instance_motion, entry.instance, time, &to_world,
                    &to_object);
        ls.position = affine_point(to_world, object_position);
        double_area = affine_double_area(to_world, p1 - p0, p2 - p0);
        n_light = normalize(affine_normal(to_object, cross_n));
    } else {
        ls.position = object_position;
        double_area = length(cross_n);
        n_light = cross_n / double_area;
    }
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
    bool textured = PT_FEATURE(EMISSION_TEXTURE) && m.tex[MATERIAL_TEX_EMISSION] != NO_TEXTURE;
    bool cutout = PT_FEATURE(CUTOUT) && (m.flags & MATERIAL_FLAG_CUTOUT);
    if (textured || cutout) {
        float2 uv = (float2)(b.x, b.y);
        if (tri.w & TRIANGLE_HAS_UVS)
            uv = (1.0f - b.x - b.y) * scene->uvs[tri.x] + b.x * scene->uvs[tri.y] + b.y * scene->uvs[tri.z];
        if (textured)
            ls.radiance *= xyz(texture_eval(scene, m.tex[MATERIAL_TEX_EMISSION], uv, object_position));
        /* A ray meets a cut-out emitter with probability opacity (the rest pass through), so
         * what BSDF sampling sees on average is emission x opacity: light sampling agrees. */
        if (cutout)
            ls.radiance *= material_opacity(scene, m, uv, object_position);
    }
    ls.pdf_w = entry.pdf * (2.0f / double_area) * dist2 / cos_light;
    return ls;
}
