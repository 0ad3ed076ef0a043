/* SPDX-License-Identifier: MIT */
/* vec3.h: the few float[3] helpers the host needs (camera frames, bounds). Kernels use OpenCL's
 * float3 built-ins instead. */
#ifndef PT_VEC3_H
#define PT_VEC3_H

#include <math.h>
#include <stdbool.h>

static inline float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline float length3(const float v[3]) { return sqrtf(dot3(v, v)); }

/* out = a x b; out may alias a or b. */
static inline void cross3(const float a[3], const float b[3], float out[3])
{
    float r0 = a[1] * b[2] - a[2] * b[1], r1 = a[2] * b[0] - a[0] * b[2], r2 = a[0] * b[1] - a[1] * b[0];
    out[0] = r0, out[1] = r1, out[2] = r2;
}

/* Scales v to unit length; false (v unchanged) when its length is 0, infinite or NaN. */
static inline bool normalize3(float v[3])
{
    float len = length3(v);
    if (!(len > 0.0f) || !isfinite(len))
        return false;
    v[0] /= len, v[1] /= len, v[2] /= len;
    return true;
}

#endif
