// SPDX-License-Identifier: MIT
/* transform.c: see transform.h. Everything in double; the kernels get float rows at the end. */
#include "base/transform.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define PI 3.14159265358979323846

Affine affine_identity(void)
{
    return affine_scale(1.0, 1.0, 1.0);
}

Affine affine_translate(double x, double y, double z)
{
    Affine a = affine_identity();
    a.m[0][3] = x, a.m[1][3] = y, a.m[2][3] = z;
    return a;
}

Affine affine_scale(double x, double y, double z)
{
    Affine a;
    memset(&a, 0, sizeof a);
    a.m[0][0] = x, a.m[1][1] = y, a.m[2][2] = z;
    return a;
}

bool affine_rotate(const double axis[3], double degrees, Affine *out)
{
    double len = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (!(len > 0.0) || !isfinite(len) || !isfinite(degrees))
        return false;
    double x = axis[0] / len, y = axis[1] / len, z = axis[2] / len;
    double angle = degrees * PI / 180.0, c = cos(angle), s = sin(angle), k = 1.0 - c;
    /* Rodrigues: counter-clockwise about the axis, seen from its tip. */
    Affine a = affine_identity();
    a.m[0][0] = c + x * x * k, a.m[0][1] = x * y * k - z * s, a.m[0][2] = x * z * k + y * s;
    a.m[1][0] = y * x * k + z * s, a.m[1][1] = c + y * y * k, a.m[1][2] = y * z * k - x * s;
    a.m[2][0] = z * x * k - y * s, a.m[2][1] = z * y * k + x * s, a.m[2][2] = c + z * z * k;
    *out = a;
    return true;
}

bool affine_from_rows16(const double rows[16], Affine *out)
{
    if (rows[12] != 0.0 || rows[13] != 0.0 || rows[14] != 0.0 || rows[15] != 1.0)
        return false;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            out->m[r][c] = rows[4 * r + c];
    return true;
}

Affine affine_mul(const Affine *a, const Affine *b)
{
    Affine r;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 4; j++) {
            double sum = j == 3 ? a->m[i][3] : 0.0;
            for (int k = 0; k < 3; k++)
                sum += a->m[i][k] * b->m[k][j];
            r.m[i][j] = sum;
        }
    }
    return r;
}

double affine_det(const Affine *a)
{
    const double(*m)[4] = a->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

bool affine_is_finite(const Affine *a)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            if (!isfinite(a->m[i][j]))
                return false;
    return true;
}

bool affine_invert(const Affine *a, Affine *inverse)
{
    if (!affine_is_finite(a))
        return false;
    double scale = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            scale = fmax(scale, fabs(a->m[i][j]));
    double det = affine_det(a);
    if (!(fabs(det) > 1e-12 * scale * scale * scale) || !isfinite(1.0 / det))
        return false;
    const double(*m)[4] = a->m;
    Affine r;
    double inv = 1.0 / det;
    r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv;
    r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv;
    r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv;
    for (int i = 0; i < 3; i++)
        r.m[i][3] = -(r.m[i][0] * m[0][3] + r.m[i][1] * m[1][3] + r.m[i][2] * m[2][3]);
    *inverse = r;
    return affine_is_finite(inverse);
}

bool affine_is_identity(const Affine *a)
{
    Affine id = affine_identity();
    return affine_equal(a, &id);
}

bool affine_equal(const Affine *a, const Affine *b)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            if (a->m[i][j] != b->m[i][j])
                return false;
    return true;
}

void affine_point(const Affine *a, const double p[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a->m[i][0] * p[0] + a->m[i][1] * p[1] + a->m[i][2] * p[2] + a->m[i][3];
    memcpy(out, r, sizeof r);
}

void affine_vector(const Affine *a, const double v[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a->m[i][0] * v[0] + a->m[i][1] * v[1] + a->m[i][2] * v[2];
    memcpy(out, r, sizeof r);
}

void affine_normal(const Affine *inverse, const double n[3], double out[3])
{
    double r[3];
    for (int j = 0; j < 3; j++)
        r[j] = inverse->m[0][j] * n[0] + inverse->m[1][j] * n[1] + inverse->m[2][j] * n[2];
    memcpy(out, r, sizeof r);
}

/* A box of transformed points in double, grown point by point, then rounded outwards to floats
 * so that the float box holds the exact one. */
typedef struct {
    double lo[3], hi[3];
} ExactBox;

static ExactBox exact_box_empty(void)
{
    return (ExactBox){{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
}

static void exact_box_add(ExactBox *b, const Affine *a, double x, double y, double z)
{
    double p[3] = {x, y, z};
    affine_point(a, p, p);
    for (int k = 0; k < 3; k++)
        b->lo[k] = fmin(b->lo[k], p[k]), b->hi[k] = fmax(b->hi[k], p[k]);
}

static void exact_box_round(const ExactBox *b, float out_lo[3], float out_hi[3])
{
    for (int k = 0; k < 3; k++) {
        out_lo[k] = nextafterf((float)b->lo[k], -INFINITY);
        out_hi[k] = nextafterf((float)b->hi[k], INFINITY);
    }
}

void affine_box(const Affine *a, const float lo[3], const float hi[3], float out_lo[3],
                float out_hi[3])
{
    ExactBox b = exact_box_empty();
    for (int corner = 0; corner < 8; corner++)
        exact_box_add(&b, a, corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1],
                      corner & 4 ? hi[2] : lo[2]);
    exact_box_round(&b, out_lo, out_hi);
}

void affine_points_box(const Affine *a, const float4 *points, size_t n, float out_lo[3],
                       float out_hi[3])
{
    ExactBox b = exact_box_empty();
    for (size_t i = 0; i < n; i++)
        exact_box_add(&b, a, points[i].s[0], points[i].s[1], points[i].s[2]);
    exact_box_round(&b, out_lo, out_hi);
}

void affine_to_rows(const Affine *a, float4 rows[3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            rows[i].s[j] = (float)a->m[i][j];
}

/* ---- T R S ---------------------------------------------------------------------------------- */

typedef double Mat3[3][3];

static void mat3_of(const Affine *a, Mat3 out)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out[i][j] = a->m[i][j];
}

static double mat3_det(Mat3 m)
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* The inverse transpose of m; false when singular. */
static bool mat3_inverse_transpose(Mat3 m, Mat3 out)
{
    double det = mat3_det(m);
    if (!(fabs(det) > 0.0) || !isfinite(1.0 / det))
        return false;
    double inv = 1.0 / det;
    /* (m^-1)^T = cofactor matrix / det. */
    out[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv;
    out[0][1] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv;
    out[0][2] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv;
    out[1][0] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv;
    out[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv;
    out[1][2] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv;
    out[2][0] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv;
    out[2][1] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv;
    out[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv;
    return true;
}

/* The unit quaternion of a proper rotation matrix (Shepperd's method). */
static void quaternion_of(Mat3 r, double q[4])
{
    double trace = r[0][0] + r[1][1] + r[2][2];
    if (trace > 0.0) {
        double s = 2.0 * sqrt(trace + 1.0);
        q[3] = 0.25 * s;
        q[0] = (r[2][1] - r[1][2]) / s;
        q[1] = (r[0][2] - r[2][0]) / s;
        q[2] = (r[1][0] - r[0][1]) / s;
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        double s = 2.0 * sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]);
        q[3] = (r[2][1] - r[1][2]) / s;
        q[0] = 0.25 * s;
        q[1] = (r[0][1] + r[1][0]) / s;
        q[2] = (r[0][2] + r[2][0]) / s;
    } else if (r[1][1] > r[2][2]) {
        double s = 2.0 * sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]);
        q[3] = (r[0][2] - r[2][0]) / s;
        q[0] = (r[0][1] + r[1][0]) / s;
        q[1] = 0.25 * s;
        q[2] = (r[1][2] + r[2][1]) / s;
    } else {
        double s = 2.0 * sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]);
        q[3] = (r[1][0] - r[0][1]) / s;
        q[0] = (r[0][2] + r[2][0]) / s;
        q[1] = (r[1][2] + r[2][1]) / s;
        q[2] = 0.25 * s;
    }
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (int k = 0; k < 4; k++)
        q[k] /= len;
}

static void rotation_of(const double q[4], Mat3 r)
{
    double x = q[0], y = q[1], z = q[2], w = q[3];
    r[0][0] = 1 - 2 * (y * y + z * z), r[0][1] = 2 * (x * y - z * w), r[0][2] = 2 * (x * z + y * w);
    r[1][0] = 2 * (x * y + z * w), r[1][1] = 1 - 2 * (x * x + z * z), r[1][2] = 2 * (y * z - x * w);
    r[2][0] = 2 * (x * z - y * w), r[2][1] = 2 * (y * z + x * w), r[2][2] = 1 - 2 * (x * x + y * y);
}

bool trs_decompose(const Affine *a, Trs *out)
{
    if (!affine_is_finite(a))
        return false;
    Mat3 m, r, it;
    mat3_of(a, m);
    double det = mat3_det(m);
    if (!(fabs(det) > 0.0))
        return false;
    /* A mirror goes into S: decompose -M, whose rotation part is proper. */
    double sign = det < 0.0 ? -1.0 : 1.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r[i][j] = sign * m[i][j];
    /* Polar decomposition by Newton's iteration R <- (R + R^-T) / 2 (Higham; pbrt-v3's
     * AnimatedTransform::Decompose). */
    for (int iteration = 0; iteration < 100; iteration++) {
        if (!mat3_inverse_transpose(r, it))
            return false;
        double change = 0.0;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                double next = 0.5 * (r[i][j] + it[i][j]);
                change = fmax(change, fabs(next - r[i][j]));
                r[i][j] = next;
            }
        if (change < 1e-15)
            break;
    }
    /* S = R^T M (symmetric up to rounding: symmetrised). */
    double s[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            s[i][j] = r[0][i] * m[0][j] + r[1][i] * m[1][j] + r[2][i] * m[2][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out->s[i][j] = 0.5 * (s[i][j] + s[j][i]);
    quaternion_of(r, out->q);
    for (int k = 0; k < 3; k++)
        out->t[k] = a->m[k][3];
    return true;
}

Affine trs_compose(const Trs *trs)
{
    Mat3 r;
    rotation_of(trs->q, r);
    Affine a;
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++)
            a.m[i][j] = r[i][0] * trs->s[0][j] + r[i][1] * trs->s[1][j] + r[i][2] * trs->s[2][j];
        a.m[i][3] = trs->t[i];
    }
    return a;
}

void trs_align(const Trs *a, Trs *b)
{
    double d = a->q[0] * b->q[0] + a->q[1] * b->q[1] + a->q[2] * b->q[2] + a->q[3] * b->q[3];
    if (d < 0.0)
        for (int k = 0; k < 4; k++)
            b->q[k] = -b->q[k];
}

Trs trs_interpolate(const Trs *a, const Trs *b, double f)
{
    Trs r;
    for (int k = 0; k < 3; k++)
        r.t[k] = (1.0 - f) * a->t[k] + f * b->t[k];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            r.s[i][j] = (1.0 - f) * a->s[i][j] + f * b->s[i][j];
    double c = a->q[0] * b->q[0] + a->q[1] * b->q[1] + a->q[2] * b->q[2] + a->q[3] * b->q[3];
    double sign = c < 0.0 ? -1.0 : 1.0;
    c = fmin(1.0, fabs(c));
    double wa = 1.0 - f, wb = f;
    if (c < 0.9995) {
        double theta = acos(c), sn = sin(theta);
        wa = sin((1.0 - f) * theta) / sn;
        wb = sin(f * theta) / sn;
    }
    double len = 0.0;
    for (int k = 0; k < 4; k++) {
        r.q[k] = wa * a->q[k] + wb * sign * b->q[k];
        len += r.q[k] * r.q[k];
    }
    len = sqrt(len);
    for (int k = 0; k < 4; k++)
        r.q[k] /= len;
    return r;
}

static double norm3(const double v[3]) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

void trs_swept_box(const Trs *a, const Trs *b, const float lo[3], const float hi[3],
                   float out_lo[3], float out_hi[3])
{
    /* Each corner c moves along p(f) = T(f) + R(f) S(f) c. Sampled at N + 1 fractions, every
     * point of the path lies within (1 / 2N) max |dp/df| of a sample, and
     * |dp/df| <= |T1 - T0| + theta max(|S0 c|, |S1 c|) + |(S1 - S0) c|, theta the rotation angle
     * from a to b (slerp turns at a constant rate): the sampled box padded by that is
     * conservative. */
    enum { N = 32 };
    double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    double dq = fabs(a->q[0] * b->q[0] + a->q[1] * b->q[1] + a->q[2] * b->q[2] + a->q[3] * b->q[3]);
    double theta = 2.0 * acos(fmin(1.0, dq));
    double dt[3] = {b->t[0] - a->t[0], b->t[1] - a->t[1], b->t[2] - a->t[2]};
    double speed = 0.0;
    for (int corner = 0; corner < 8; corner++) {
        double c[3] = {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1],
                       corner & 4 ? hi[2] : lo[2]};
        double sa[3], sb[3], ds[3];
        for (int i = 0; i < 3; i++) {
            sa[i] = a->s[i][0] * c[0] + a->s[i][1] * c[1] + a->s[i][2] * c[2];
            sb[i] = b->s[i][0] * c[0] + b->s[i][1] * c[1] + b->s[i][2] * c[2];
            ds[i] = sb[i] - sa[i];
        }
        double v = norm3(dt) + theta * fmax(norm3(sa), norm3(sb)) + norm3(ds);
        speed = fmax(speed, v);
    }
    for (int step = 0; step <= N; step++) {
        Trs at = trs_interpolate(a, b, (double)step / N);
        Affine m = trs_compose(&at);
        for (int corner = 0; corner < 8; corner++) {
            double p[3] = {corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1],
                           corner & 4 ? hi[2] : lo[2]};
            affine_point(&m, p, p);
            for (int k = 0; k < 3; k++)
                blo[k] = fmin(blo[k], p[k]), bhi[k] = fmax(bhi[k], p[k]);
        }
    }
    double pad = speed / (2.0 * N);
    for (int k = 0; k < 3; k++) {
        /* The kernels' float recomposition differs from this double one by rounding: a relative
         * margin of 1e-5 of the box's reach covers it. */
        double reach = fmax(fabs(blo[k]), fabs(bhi[k]));
        out_lo[k] = nextafterf((float)(blo[k] - pad - 1e-5 * reach), -INFINITY);
        out_hi[k] = nextafterf((float)(bhi[k] + pad + 1e-5 * reach), INFINITY);
    }
}

void rows16_mul(const double a[16], const double b[16], double out[16])
{
    double t[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            t[4 * i + j] = a[4 * i] * b[j] + a[4 * i + 1] * b[4 + j] + a[4 * i + 2] * b[8 + j] +
                           a[4 * i + 3] * b[12 + j];
    memcpy(out, t, sizeof t);
}
