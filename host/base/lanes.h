/* SPDX-License-Identifier: MIT */
/* lanes.h: four floats at a time for the BVH builder (host/accel/bvh_build.c): SSE2 where the compiler offers
 * it (every x86-64), plain C with the same results elsewhere. Header-only: every helper is meant
 * to melt into the builder's loops. */
#ifndef PT_LANES_H
#define PT_LANES_H

#include <stdint.h>
#include <string.h>

/* GCC's -O2 inliner judges the plain versions of the helpers below too big and calls them, which
 * halves the speed of a plain build; they are all meant to melt into their loops. */
#ifdef __GNUC__
#define ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define ALWAYS_INLINE inline
#endif

/* lanes_min(a, b) and lanes_max(a, b) return b where a lane of either is NaN (SSE's rule; the
 * plain versions follow it). Build records hold no NaN (make_prims clamps their boxes), so boxes
 * grow accumulator first, which SSE's two-operand form does in one instruction; the two places
 * that do meet NaN (the bin clamp, the sweep's best sum) put the value to keep second. */
#ifdef __SSE2__
#include <immintrin.h>

typedef __m128 Lanes;

static ALWAYS_INLINE Lanes lanes_load(const float *aligned) { return _mm_load_ps(aligned); }
static ALWAYS_INLINE void lanes_store(float *aligned, Lanes a) { _mm_store_ps(aligned, a); }
static ALWAYS_INLINE Lanes lanes_splat(float x) { return _mm_set1_ps(x); }
static ALWAYS_INLINE Lanes lanes_min(Lanes a, Lanes b) { return _mm_min_ps(a, b); }
static ALWAYS_INLINE Lanes lanes_max(Lanes a, Lanes b) { return _mm_max_ps(a, b); }
static ALWAYS_INLINE Lanes lanes_add(Lanes a, Lanes b) { return _mm_add_ps(a, b); }
static ALWAYS_INLINE Lanes lanes_sub(Lanes a, Lanes b) { return _mm_sub_ps(a, b); }
static ALWAYS_INLINE Lanes lanes_mul(Lanes a, Lanes b) { return _mm_mul_ps(a, b); }

/* a < b ? if_less : otherwise, lane by lane. */
static ALWAYS_INLINE Lanes lanes_select_less(Lanes a, Lanes b, Lanes if_less, Lanes otherwise)
{
    Lanes less = _mm_cmplt_ps(a, b);
    return _mm_or_ps(_mm_and_ps(less, if_less), _mm_andnot_ps(less, otherwise));
}

/* Bit k set where lane k of a < lane k of b. */
static ALWAYS_INLINE int lanes_less_bits(Lanes a, Lanes b)
{
    return _mm_movemask_ps(_mm_cmplt_ps(a, b));
}

/* a <= b ? 1 : 0, lane by lane. */
static ALWAYS_INLINE Lanes lanes_one_if_less_equal(Lanes a, Lanes b)
{
    return _mm_and_ps(_mm_cmple_ps(a, b), _mm_set1_ps(1.0f));
}

/* Toward zero, as a C cast does; the caller keeps the lanes within int range. */
static ALWAYS_INLINE void lanes_truncate(Lanes a, int32_t out[4])
{
    _mm_storeu_si128((__m128i *)out, _mm_cvttps_epi32(a));
}

static ALWAYS_INLINE Lanes lanes_from_ints(const uint32_t in[4])
{
    return _mm_cvtepi32_ps(_mm_loadu_si128((const __m128i *)in));
}

/* Lanes x, y, z of three rows as three columns: column k holds (row0[k], row1[k], row2[k], 0). */
static ALWAYS_INLINE void lanes_transpose3(Lanes row0, Lanes row1, Lanes row2, Lanes column[3])
{
    Lanes zero = _mm_setzero_ps();
    Lanes xy01 = _mm_unpacklo_ps(row0, row1), zw01 = _mm_unpackhi_ps(row0, row1);
    Lanes xy2 = _mm_unpacklo_ps(row2, zero), zw2 = _mm_unpackhi_ps(row2, zero);
    column[0] = _mm_movelh_ps(xy01, xy2);
    column[1] = _mm_movehl_ps(xy2, xy01);
    column[2] = _mm_movelh_ps(zw01, zw2);
}
#else
typedef struct {
    float v[4];
} Lanes;

static ALWAYS_INLINE Lanes lanes_load(const float *aligned)
{
    Lanes r;
    memcpy(r.v, aligned, sizeof r.v);
    return r;
}
static ALWAYS_INLINE void lanes_store(float *aligned, Lanes a) { memcpy(aligned, a.v, sizeof a.v); }
static ALWAYS_INLINE Lanes lanes_splat(float x) { return (Lanes){{x, x, x, x}}; }

#define LANES_BINARY(name, expr)                        \
    static ALWAYS_INLINE Lanes name(Lanes a, Lanes b)          \
    {                                                   \
        Lanes r;                                        \
        for (int k = 0; k < 4; k++)                     \
            r.v[k] = (expr);                            \
        return r;                                       \
    }
LANES_BINARY(lanes_min, a.v[k] < b.v[k] ? a.v[k] : b.v[k])
LANES_BINARY(lanes_max, a.v[k] > b.v[k] ? a.v[k] : b.v[k])
LANES_BINARY(lanes_add, a.v[k] + b.v[k])
LANES_BINARY(lanes_sub, a.v[k] - b.v[k])
LANES_BINARY(lanes_mul, a.v[k] * b.v[k])
#undef LANES_BINARY

static ALWAYS_INLINE Lanes lanes_select_less(Lanes a, Lanes b, Lanes if_less, Lanes otherwise)
{
    Lanes r;
    for (int k = 0; k < 4; k++)
        r.v[k] = a.v[k] < b.v[k] ? if_less.v[k] : otherwise.v[k];
    return r;
}

static ALWAYS_INLINE int lanes_less_bits(Lanes a, Lanes b)
{
    int bits = 0;
    for (int k = 0; k < 4; k++)
        bits |= (a.v[k] < b.v[k]) << k;
    return bits;
}

static ALWAYS_INLINE Lanes lanes_one_if_less_equal(Lanes a, Lanes b)
{
    Lanes r;
    for (int k = 0; k < 4; k++)
        r.v[k] = a.v[k] <= b.v[k] ? 1.0f : 0.0f;
    return r;
}

static ALWAYS_INLINE void lanes_truncate(Lanes a, int32_t out[4])
{
    for (int k = 0; k < 4; k++)
        out[k] = (int32_t)a.v[k];
}

static ALWAYS_INLINE Lanes lanes_from_ints(const uint32_t in[4])
{
    return (Lanes){{(float)(int32_t)in[0], (float)(int32_t)in[1], (float)(int32_t)in[2],
                    (float)(int32_t)in[3]}};
}

static ALWAYS_INLINE void lanes_transpose3(Lanes row0, Lanes row1, Lanes row2, Lanes column[3])
{
    for (int k = 0; k < 3; k++)
        column[k] = (Lanes){{row0.v[k], row1.v[k], row2.v[k], 0.0f}};
}
#endif

#endif
