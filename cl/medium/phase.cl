/* SPDX-License-Identifier: MIT */
/* phase.cl: the Henyey-Greenstein phase function of a medium (shared/DESIGN.md "Media"). cos is
 * the cosine of the scattering angle, between the arriving ray's direction and the new one: g > 0
 * scatters forward (wi near the ray's direction), g < 0 back; it integrates to 1 over the sphere. */

inline float phase_hg(float g, float cos_theta)
{
    float denom = 1.0f + g * g - 2.0f * g * cos_theta;
    return (1.0f - g * g) / (4.0f * M_PI_F * denom * sqrt(fmax(denom, 1e-12f)));
}

/* A direction around d (the arriving ray's, unit) with density phase_hg(g, dot(d, wi)), which
 * goes to *pdf; the weight (phase / pdf) is 1. Inverts the cdf of cos (pbrt-v4, 11.3.1). */
inline float3 phase_hg_sample(float g, float3 d, float u1, float u2, float *pdf)
{
    float cos_theta;
    if (fabs(g) < 1e-3f) {
        cos_theta = 1.0f - 2.0f * u1;
    } else {
        float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u1);
        cos_theta = (1.0f + g * g - s * s) / (2.0f * g);
    }
    cos_theta = clamp(cos_theta, -1.0f, 1.0f);
    float sin_theta = sqrt(fmax(0.0f, 1.0f - cos_theta * cos_theta));
    float2 cs = cos_sin_turns(u2);
    Frame f = frame_from_normal(d);
    *pdf = phase_hg(g, cos_theta);
    return frame_to_world(f, (float3)(sin_theta * cs.x, sin_theta * cs.y, cos_theta));
}
