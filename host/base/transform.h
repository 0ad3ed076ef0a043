/* SPDX-License-Identifier: MIT */
/* transform.h: affine transforms of scene objects (shared/DESIGN.md "Objects"), in double: the
 * operations a scene's "transform" lists compose, inversion, the T R S decomposition that motion
 * blur interpolates, and what they do to points, vectors, normals and boxes. libc only. */
#ifndef PT_TRANSFORM_H
#define PT_TRANSFORM_H

#include <stdbool.h>

#include "base/shared_types.h"

/* p' = M p with M = [m | t]: rows of a 3x4 matrix, the fourth row (0 0 0 1) implied. */
typedef struct {
    double m[3][4];
} Affine;

Affine affine_identity(void);
Affine affine_translate(double x, double y, double z);
Affine affine_scale(double x, double y, double z);
/* Right-handed: counter-clockwise looking down the axis toward the origin. False (out unchanged)
 * when the axis has zero or non-finite length. */
bool affine_rotate(const double axis[3], double degrees, Affine *out);
/* From 16 numbers, row-major with column vectors (p' = M p); false when the last row is not
 * (0, 0, 0, 1) (a projective matrix). */
bool affine_from_rows16(const double rows[16], Affine *out);
/* out = a * b for 4 x 4 matrices stored as 16 rows-first doubles (the importers' node matrices,
 * which may be projective until checked); out may be a or b. */
void rows16_mul(const double a[16], const double b[16], double out[16]);
/* a b: b applied first, then a. */
Affine affine_mul(const Affine *a, const Affine *b);
double affine_det(const Affine *a);
/* False when a is singular (|det| below 1e-12 of the scale of its entries) or not finite. */
bool affine_invert(const Affine *a, Affine *inverse);
bool affine_is_finite(const Affine *a);
bool affine_is_identity(const Affine *a);
bool affine_equal(const Affine *a, const Affine *b);

void affine_point(const Affine *a, const double p[3], double out[3]);
void affine_vector(const Affine *a, const double v[3], double out[3]);
/* (M^-1)^T n, given the inverse; not normalised. */
void affine_normal(const Affine *inverse, const double n[3], double out[3]);
/* The box around the 8 transformed corners of [lo, hi]. */
void affine_box(const Affine *a, const float lo[3], const float hi[3], float out_lo[3],
                float out_hi[3]);
/* The box around n transformed points (xyz of each float4), rounded outwards like affine_box:
 * exact where affine_box of their bounds is loose (a turned instance). */
void affine_points_box(const Affine *a, const float4 *points, size_t n, float out_lo[3],
                       float out_hi[3]);
/* Rows as the kernels read them (shared.h Instance.to_world / to_object). */
void affine_to_rows(const Affine *a, float4 rows[3]);

/* M = T R S (polar decomposition): translation t, rotation q (unit quaternion x, y, z, w, a
 * proper rotation) and a symmetric S that keeps any mirroring (det S < 0 when det M < 0). */
typedef struct {
    double t[3];
    double q[4];
    double s[3][3];
} Trs;

/* False when the linear part is singular or not finite. */
bool trs_decompose(const Affine *a, Trs *out);
Affine trs_compose(const Trs *trs);
/* At fraction f in [0, 1]: t and S linear, q slerped along the shortest arc (as
 * cl/geometry/instance.cl motion_at). */
Trs trs_interpolate(const Trs *a, const Trs *b, double f);
/* b's quaternion negated where needed so that dot(a.q, b.q) >= 0 (the shortest arc). */
void trs_align(const Trs *a, Trs *b);
/* The world box that [lo, hi] sweeps from a to b (f in [0, 1]), conservative for rotations. */
void trs_swept_box(const Trs *a, const Trs *b, const float lo[3], const float hi[3],
                   float out_lo[3], float out_hi[3]);

#endif
