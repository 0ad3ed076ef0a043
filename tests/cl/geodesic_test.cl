/* SPDX-License-Identifier: MIT */
/* geodesic_test.cl: kernels for tests/test_black_holes_optics.c. */

/* Work item i: a ray entering hole[0]'s influence sphere (centre c, radius R) at impact parameter
 * b[i], moving along +x in the xy plane, stepped as integrate_geodesic steps it (geodesic_step)
 * until it leaves the sphere or reaches r <= 2M (1 + GEODESIC_HORIZON_EPSILON). Writes
 * out_dir[i] = (final unit direction, 0) and out_info[i] = (the largest |h - h0| / h0 over the
 * steps, steps, 1 if captured, r at the end). */
kernel void geodesic_test_trace(const global BlackHole *hole, const global float *b,
                                uint n, global float4 *out_dir, global float4 *out_info)
{
    uint i = get_global_id(0);
    if (i >= n)
        return;
    float3 anchor = xyz(hole->centre);
    float R = hole->normal.w, bi = b[i];
    float3 x = (float3)(-sqrt(R * R - bi * bi) * (1.0f - 1e-6f), bi, 0.0f), v = (float3)(1.0f, 0.0f, 0.0f);
    float h0 = length(cross(x, v)), worst = 0.0f, horizons = INFINITY;
    uint steps = 0u;
    bool captured = false;
    while (steps < GEODESIC_MAX_STEPS && geodesic_inside(hole, 1u, anchor, x)) {
        geodesic_step(hole, 1u, anchor, &x, &v);
        steps++;
        worst = fmax(worst, fabs(length(cross(x, v)) - h0) / h0);
        geodesic_nearest(hole, 1u, anchor, x, &horizons);
        if (horizons <= 1.0f + GEODESIC_HORIZON_EPSILON) {
            captured = true;
            break;
        }
    }
    out_dir[i] = (float4)(normalize(v), 0.0f);
    out_info[i] = (float4)(worst, (float)steps, captured ? 1.0f : 0.0f, length(x));
}
