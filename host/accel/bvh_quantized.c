// SPDX-License-Identifier: MIT
/* bvh_quantized.c: 32-byte 2-wide nodes from the 64-byte ones of bvh.h. Each axis of a node gets
 * a frame, an origin p and a power-of-two step s, with every child plane on the grid p + q s,
 * q = 0..255, rounded outwards. The margin: the traversal computes a plane's distance as
 * q * (s / d) + (p - o) / d, whose rounding that is not relative to the distance is at most
 * 2^-14 s (box_test.cl); planes are pushed out by PLANE_MARGIN = 2^-10 s beyond the exact
 * box, so the quantised box the traversal sees still holds the exact one. Arithmetic is in double,
 * where p + q s and the differences below are exact. */
#include "accel/bvh_quantized.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"

#define PLANE_MARGIN_BITS 10 /* margin = step * 2^-10 */
#define STEPS 255
/* The smallest step: keeps the margin and the origin far above float denormals. */
#define MIN_STEP_EXPONENT (-100)
#define MAX_STEP_EXPONENT 126

static uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

static float bits_float(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* The largest float <= x whose low 8 mantissa bits are zero (they will hold the exponent). */
static float origin_at_or_below(double x)
{
    float f = (float)x;
    if ((double)f > x)
        f = nextafterf(f, -INFINITY);
    if (fabs(f) < ldexp(1.0, MIN_STEP_EXPONENT))
        return -(float)ldexp(1.0, MIN_STEP_EXPONENT); /* no denormals, which GPUs may flush */
    uint32_t u = float_bits(f);
    /* Positive: clearing bits lowers the value; negative: raise the magnitude instead. */
    u = (u >> 31) ? (u + 0xffu) & ~0xffu : u & ~0xffu;
    return bits_float(u);
}

typedef struct {
    double origin, step, margin;
    uint32_t bits; /* origin's bits with the biased exponent of step in the low byte */
} AxisFrame;

/* The frame of one axis that holds [lo, hi] with the margin on both sides, finest first. */
static AxisFrame axis_frame(float lo, float hi)
{
    double extent = (double)hi - lo;
    int e;
    frexp(extent / (STEPS - 4), &e); /* 2^e >= extent / 251: room for the margins and rounding */
    if (e < MIN_STEP_EXPONENT)
        e = MIN_STEP_EXPONENT;
    for (; e <= MAX_STEP_EXPONENT; e++) {
        AxisFrame f;
        f.step = ldexp(1.0, e);
        f.margin = ldexp(f.step, -PLANE_MARGIN_BITS);
        float origin = origin_at_or_below((double)lo - f.margin);
        f.origin = origin;
        if (isfinite(origin) && f.origin + STEPS * f.step >= (double)hi + f.margin) {
            f.bits = (float_bits(origin) & ~0xffu) | (uint32_t)(e + 127);
            return f;
        }
    }
    die("BVH: a node's box [%g, %g] cannot be quantised", (double)lo, (double)hi);
}

static uint32_t plane_lo(const AxisFrame *f, float v)
{
    double q = floor(((double)v - f->margin - f->origin) / f->step);
    return q < 0.0 ? 0u : (uint32_t)q;
}

static uint32_t plane_hi(const AxisFrame *f, float v)
{
    double q = ceil(((double)v + f->margin - f->origin) / f->step);
    return q > STEPS ? STEPS : (uint32_t)q;
}

/* The quantised reference of a float node's child (bvh.h: ~first and a count lane for leaves). */
static uint32_t child_ref(float4 lo, float4 hi)
{
    uint32_t ref = float_bits(lo.s[3]);
    if ((int32_t)ref >= 0)
        return ref;
    uint32_t first = ~ref, count = float_bits(hi.s[3]);
    if (count >> BVH_QUANTIZED_COUNT_BITS)
        die("BVH: a leaf of %u triangles does not fit the quantised node", count);
    return BVH_QUANTIZED_LEAF | first << BVH_QUANTIZED_COUNT_BITS | count;
}

static BvhNodeQuantized quantize_node(const BvhNode *node)
{
    const float4 *lo[2] = {&node->lmin, &node->rmin}, *hi[2] = {&node->lmax, &node->rmax};
    bool empty[2];
    for (int c = 0; c < 2; c++)
        empty[c] = !(lo[c]->s[0] <= hi[c]->s[0]);
    uint32_t frame_bits[3], words[3];
    for (int axis = 0; axis < 3; axis++) {
        float a = INFINITY, b = -INFINITY;
        for (int c = 0; c < 2; c++)
            if (!empty[c]) {
                a = fminf(a, lo[c]->s[axis]);
                b = fmaxf(b, hi[c]->s[axis]);
            }
        if (a > b)
            a = b = 0.0f; /* both children empty: any frame */
        AxisFrame f = axis_frame(a, b);
        frame_bits[axis] = f.bits;
        words[axis] = 0;
        for (int c = 0; c < 2; c++) {
            /* An empty child gets the inverted box [255, 0] on every axis; its leaf has no
             * triangles besides, so a ray that passes the box test finds nothing. */
            uint32_t qlo = empty[c] ? STEPS : plane_lo(&f, lo[c]->s[axis]);
            uint32_t qhi = empty[c] ? 0u : plane_hi(&f, hi[c]->s[axis]);
            words[axis] |= (qlo | qhi << 8) << (16 * c);
        }
    }
    BvhNodeQuantized q;
    q.frame = (uint4){{frame_bits[0], frame_bits[1], frame_bits[2], words[0]}};
    q.refs = (uint4){{words[1], words[2], child_ref(node->lmin, node->lmax),
                      child_ref(node->rmin, node->rmax)}};
    return q;
}

BvhNodeQuantized *bvh_quantize(const Bvh *bvh)
{
    if (bvh->num_tris >= BVH_QUANTIZED_MAX_TRIANGLES)
        die("BVH: %u triangles; the quantised nodes address fewer than %u (PT_BVH_QUANTIZED=0 "
            "lifts the limit)", bvh->num_tris, BVH_QUANTIZED_MAX_TRIANGLES);
    BvhNodeQuantized *nodes = malloc((bvh->num_nodes ? bvh->num_nodes : 1) * sizeof *nodes);
    if (!nodes)
        die("out of memory for the quantised BVH (%u nodes)", bvh->num_nodes);
    for (uint32_t i = 0; i < bvh->num_nodes; i++)
        nodes[i] = quantize_node(&bvh->nodes[i]);
    return nodes;
}

void bvh_quantized_child_box(const BvhNodeQuantized *node, int c, double lo[3], double hi[3])
{
    const uint32_t frame[3] = {node->frame.s[0], node->frame.s[1], node->frame.s[2]};
    const uint32_t words[3] = {node->frame.s[3], node->refs.s[0], node->refs.s[1]};
    for (int axis = 0; axis < 3; axis++) {
        double origin = bits_float(frame[axis] & ~0xffu);
        double step = ldexp(1.0, (int)(frame[axis] & 0xffu) - 127);
        uint32_t bytes = words[axis] >> (16 * c);
        lo[axis] = origin + (bytes & 0xffu) * step;
        hi[axis] = origin + ((bytes >> 8) & 0xffu) * step;
    }
}
