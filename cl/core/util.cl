/* SPDX-License-Identifier: MIT */
/* util.cl: small vector helpers shared by every stage. */

#define PT_INV_PI 0.31830988618379067154f

/* Functions a CPU compiler must inline: PoCL's LLVM leaves large ones out of line, and then passes
 * their struct arguments and results through memory, where the reloads stall on store forwarding
 * (perf: a sixth of the traversal's time). NVIDIA's compiler inlines everything anyway. */
#if defined(PT_VENDOR_NVIDIA) && !defined(PT_FORCE_INLINE)
#define PT_INLINE inline
#else
#define PT_INLINE inline __attribute__((always_inline))
#endif

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
