/* SPDX-License-Identifier: MIT */
/* light_sample.cl: next-event estimation on emissive triangles (one-sided: they emit on the side of
 * their counter-clockwise normal), chosen through the power-proportional alias table. */

typedef struct {
    float3 position;
    float3 radiance; /* Le toward the shading point, 0 if it sees the back */
    float pdf_w;     /* solid-angle pdf at the shading point */
} LightSample;

PT_INLINE LightSample light_sample(const SceneView *scene, uint num_lights, float3 from, float u_pick,
                                   float u1, float u2)
{
    const global LightEntry *lights = scene->lights;
    const global float4 *positions = scene->positions;
    const global Triangle *triangles = scene->triangles;
    const global uint *material_ids = scene->material_ids;
    const global Material *materials = scene->materials;
    LightSample ls;
    uint index = min((uint)(u_pick * (float)num_lights), num_lights - 1u);
    /* Reuse the pick's fractional part to choose between the entry and its alias. */
    float u_alias = u_pick * (float)num_lights - (float)index;
    LightEntry entry = lights[index];
    if (u_alias >= entry.prob)
        entry = lights[entry.alias];
    uint4 tri = triangles[entry.triangle].v;
    float3 p0 = xyz(positions[tri.x]), p1 = xyz(positions[tri.y]), p2 = xyz(positions[tri.z]);
    float2 b = sample_triangle_uniform(u1, u2);
    ls.position = (1.0f - b.x - b.y) * p0 + b.x * p1 + b.y * p2;
    float3 cross_n = cross(p1 - p0, p2 - p0);
    float double_area = length(cross_n);
    float3 n_light = cross_n / double_area;
    float3 to_light = ls.position - from;
    float dist2 = dot(to_light, to_light);
    float cos_light = -dot(to_light, n_light) * rsqrt(dist2);
    if (!(cos_light > 0.0f) || !(double_area > 0.0f)) {
        ls.radiance = (float3)(0.0f);
        ls.pdf_w = 0.0f;
        return ls;
    }
    ls.radiance = xyz(materials[material_ids[entry.triangle]].ke);
    ls.pdf_w = entry.pdf * (2.0f / double_area) * dist2 / cos_light;
    return ls;
}
