/* SPDX-License-Identifier: MIT */
/* util.cl: small vector helpers shared by every stage. */

#define PT_INV_PI 0.31830988618379067154f

/* Functions a CPU compiler must inline: PoCL's LLVM leaves large ones out of line, and then passes
 * their struct arguments and results through memory, where the reloads stall on store forwarding
 * (perf: a sixth of the traversal's time). NVIDIA's compiler inlines everything anyway. */
#ifdef PT_VENDOR_NVIDIA
#define PT_INLINE inline
#else
#define PT_INLINE inline __attribute__((always_inline))
#endif

/* Scene features the program is built for (render/session.c passes -DPT_FEATURE_*=0 for what the
 * scene lacks, so their code leaves the kernels: measured on the H200, the analytic-light and
 * environment branches cost 4-8% of shade_surface on scenes that have neither). Without the
 * options (tests, tools) every feature is in. */
#ifndef PT_FEATURE_ENV
#define PT_FEATURE_ENV 1
#endif
#ifndef PT_FEATURE_ANALYTIC
#define PT_FEATURE_ANALYTIC 1
#endif
#ifndef PT_FEATURE_BLACK_HOLES /* cl/stages/integrate_geodesic.cl */
#define PT_FEATURE_BLACK_HOLES 1
#endif
/* The same for materials: a mask of MATERIAL_FEATURE_* (shared.h). */
#ifndef PT_MATERIAL_FEATURES
#define PT_MATERIAL_FEATURES MATERIAL_FEATURE_ALL
#endif
#define PT_HAS_MATERIAL_FEATURE(name) ((PT_MATERIAL_FEATURES & MATERIAL_FEATURE_##name) != 0u)

inline float3 xyz(float4 v) { return (float3)(v.x, v.y, v.z); }

inline float max3(float3 v) { return fmax(v.x, fmax(v.y, v.z)); }

/* Orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis, Revisited"). */
inline void make_basis(float3 n, float3 *t, float3 *b)
{
    float sign = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + n.z);
    float c = n.x * n.y * a;
    *t = (float3)(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = (float3)(c, sign + n.y * n.y * a, -n.y);
}

inline float3 to_world(float3 v, float3 n)
{
    float3 t, b;
    make_basis(n, &t, &b);
    return v.x * t + v.y * b + v.z * n;
}
