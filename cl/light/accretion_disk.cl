/* SPDX-License-Identifier: MIT */
/* accretion_disk.cl: what a ray sees where it crosses a black hole's thin accretion disk (BlackHole,
 * cl/shared/render.h): the emitted radiance and the noise that modulates it and the disk's opacity.
 * The caller (integrate_geodesic.cl) finds the crossing and draws the pass-through coin. */

/* Relative sRGB colour of a blackbody at temperature t (kelvin), luminance 1: Planck's law sampled
 * at the primaries' dominant wavelengths (610, 550, 465 nm), a cheap stand-in for the CIE
 * integral that keeps the hue's course from red (2000 K) through white (6500 K) to blue. */
inline float3 blackbody_colour(float t)
{
    const float c2 = 14387.77f; /* second radiation constant, micrometre kelvin */
    float3 lambda = (float3)(0.610f, 0.550f, 0.465f);
    float3 l5 = lambda * lambda * lambda * lambda * lambda;
    float3 b = 1.0f / (l5 * (exp(c2 / (lambda * t)) - 1.0f));
    float lum = 0.2126f * b.x + 0.7152f * b.y + 0.0722f * b.z;
    return lum > 0.0f ? b / lum : (float3)(1.0f, 0.0f, 0.0f);
}

/* The disk's noise at q (relative to the hole, in the disk plane) in [0, 1]; 1 without noise. fBm
 * (noise_fbm, texture.cl) in the disk's own coordinates after turning q by swirl x (inner / r)^1.5:
 * Keplerian rotation (angular speed ~ r^-1.5) has sheared the pattern into spiral streaks. fBm
 * stays near 1/2; its spread about 1/2 is stretched by DISK_NOISE_CONTRAST (then clamped), so that
 * the disk has gaps and bright lanes. */
#define DISK_NOISE_CONTRAST 2.5f
inline float disk_noise(const global BlackHole *h, float3 q, float r)
{
    float4 nz = h->noise;
    if (nz.y <= 0.0f)
        return 1.0f;
    float3 t1 = xyz(h->tangent), t2 = cross(xyz(h->normal), t1);
    float inner = h->radii.x;
    float angle = nz.z * pow(inner / r, 1.5f);
    float c = cos(angle), s = sin(angle);
    float u = dot(q, t1), w = dot(q, t2);
    float3 p = (float3)(c * u - s * w, s * u + c * w, 0.0f) / inner;
    float n = noise_fbm(p, nz.x, (uint)nz.y, 0x6a09e667u);
    return clamp(0.5f + DISK_NOISE_CONTRAST * (n - 0.5f), 0.0f, 1.0f);
}

/* Radiance the disk emits at q, r = |q| in [inner, outer], noise n: the emission scale, times the
 * blackbody colour of T = temperature (r / inner)^-3/4 and its T^4 ~ r^-3 fall-off when a
 * temperature is given, times n. */
inline float3 disk_emission(const global BlackHole *h, float r, float n)
{
    float3 L = xyz(h->emission) * n;
    float t_inner = h->radii.w;
    if (t_inner > 0.0f) {
        float x = h->radii.x / r; /* (T / T_inner)^(4/3) */
        L *= blackbody_colour(t_inner * pow(x, 0.75f)) * (x * x * x);
    }
    return L;
}
