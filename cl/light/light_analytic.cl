/* SPDX-License-Identifier: MIT */
/* light_analytic.cl: point, spot, directional and sun lights (AnalyticLight, shared.h;
 * shared/DESIGN.md "Lights"). Point, spot, directional and a sun of angle 0 are delta lights: only
 * next-event estimation reaches them (no BSDF ray can hit them), with MIS weight 1. A sun of angle
 * > 0 is a cone of uniform radiance L = E / (pi sin^2(half-angle)), so that a surface facing it
 * receives exactly E; NEE samples the cone uniformly and escaped rays inside it see L, with MIS. */

/* One light sample as next-event estimation uses it (analytic lights, triangles, environment). */
typedef struct {
    float3 position; /* on the light (unused at infinity) */
    float3 normal;   /* the light's unit geometric normal (its emitting side; unused for delta lights) */
    float3 direction; /* unit, from the shading point toward the light */
    uint at_infinity; /* 1: the environment, a directional light or the sun (the shadow ray has no end) */
    uint delta;      /* 1: a delta light: pdf_w is the pick probability alone, no MIS */
    float3 radiance; /* Le toward the shading point (for a delta light: the irradiance it gives at
                        normal incidence), 0 if it sees the back */
    float pdf_w;     /* solid-angle pdf at the shading point (delta: the pick probability) */
} LightSample;

/* The spot's profile at angle t from its axis: 1 inside the falloff angle, linear to 0 at the cone. */
inline float spot_profile(float t, float cone, float falloff)
{
    if (t <= falloff)
        return 1.0f;
    if (t >= cone)
        return 0.0f;
    return (cone - t) / (cone - falloff);
}

inline LightSample analytic_light_sample(AnalyticLight l, float pick_pdf, float3 from, float u1, float u2)
{
    LightSample ls;
    ls.delta = 1u;
    ls.pdf_w = pick_pdf;
    ls.normal = (float3)(0.0f, 1.0f, 0.0f);
    if (l.type == LIGHT_POINT || l.type == LIGHT_SPOT) {
        float3 to_light = xyz(l.position) - from;
        float dist2 = dot(to_light, to_light);
        ls.position = xyz(l.position);
        ls.direction = to_light * rsqrt(dist2);
        ls.at_infinity = 0u;
        ls.radiance = dist2 > 0.0f ? xyz(l.color) / dist2 : (float3)(0.0f);
        if (l.type == LIGHT_SPOT) {
            float t = acos(clamp(-dot(ls.direction, xyz(l.axis)), -1.0f, 1.0f));
            ls.radiance *= spot_profile(t, l.params.x, l.params.y);
        }
        return ls;
    }
    float3 toward = -xyz(l.position);
    ls.position = from;
    ls.at_infinity = 1u;
    ls.direction = toward;
    ls.radiance = xyz(l.color);
    if (l.type == LIGHT_SUN && l.params.z > 0.0f) {
        /* Uniform in the cone around the sun's centre: cos t uniform in [cos(half-angle), 1]. */
        float cos_t = 1.0f - u1 * (1.0f - l.params.x);
        float sin_t = sqrt(fmax(0.0f, 1.0f - cos_t * cos_t));
        float2 phi = cos_sin_turns(u2); /* 2 pi u2 */
        ls.direction = normalize(to_world((float3)(sin_t * phi.x, sin_t * phi.y, cos_t), toward));
        ls.radiance = xyz(l.color) * l.params.y;
        ls.pdf_w = pick_pdf * l.params.z;
        ls.delta = 0u;
    }
    ls.normal = -ls.direction;
    return ls;
}

/* What an escaped ray along d sees of the suns with an angle (delta lights are never hit), MIS
 * weighted against next-event estimation as environment_seen does. */
inline float3 suns_seen(constant RenderParams *p, const global AnalyticLight *lights, float3 d,
                        float prev_pdf_w, uint depth)
{
    float3 sum = (float3)(0.0f);
    for (uint i = 0u; i < p->scene.num_analytic; i++) {
        AnalyticLight l = lights[i];
        if (l.type != LIGHT_SUN || !(l.params.z > 0.0f) || -dot(d, xyz(l.position)) < l.params.x)
            continue;
        float3 L = xyz(l.color) * l.params.y;
        if (depth == 1u || prev_pdf_w == 0.0f || (p->flags & RENDER_NO_NEE))
            sum += L;
        else
            sum += L * mis_power(prev_pdf_w, l.params.w * l.params.z);
    }
    return sum;
}
