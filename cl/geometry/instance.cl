/* SPDX-License-Identifier: MIT */
/* instance.cl: an instance's transform at a path's time (shared.h Instance, InstanceMotion;
 * shared/DESIGN.md "Objects"), and what it does to points, vectors and normals. A static
 * instance's matrices come from the host as they are; a moving one's are recomposed from
 * T(s) R(s) S(s) at s = (time - open) / (close - open), as the host's trs_interpolate does. */

/* Rows of a 3x4 affine matrix: p' = (dot(r0.xyz, p) + r0.w, ...). */
typedef struct {
    float4 r0, r1, r2;
} Affine;

inline float3 affine_point(Affine m, float3 p)
{
    return (float3)(dot(xyz(m.r0), p) + m.r0.w, dot(xyz(m.r1), p) + m.r1.w,
                    dot(xyz(m.r2), p) + m.r2.w);
}

inline float3 affine_vector(Affine m, float3 v)
{
    return (float3)(dot(xyz(m.r0), v), dot(xyz(m.r1), v), dot(xyz(m.r2), v));
}

/* A normal through the inverse transpose, given the inverse: n' = (M^-1)^T n (not normalised). */
inline float3 affine_normal(Affine inverse, float3 n)
{
    return n.x * xyz(inverse.r0) + n.y * xyz(inverse.r1) + n.z * xyz(inverse.r2);
}

/* Slerp along the shortest arc (the host stores dot(a, b) >= 0); nearly equal rotations lerp. */
inline float4 quaternion_slerp(float4 a, float4 b, float s)
{
    float c = clamp(dot(a, b), -1.0f, 1.0f);
    if (c > 0.9995f)
        return normalize(mix(a, b, s));
    float theta = acos(c);
    return (sin((1.0f - s) * theta) * a + sin(s * theta) * b) / sin(theta);
}

/* M(s) = T R S and its inverse S^-1 R^T (x - T), from the motion's two key transforms. */
inline void motion_at(const global InstanceMotion *motion, float s, Affine *to_world,
                      Affine *to_object)
{
    float4 q = quaternion_slerp(motion->rotation[0], motion->rotation[1], s);
    float x = q.x, y = q.y, z = q.z, w = q.w;
    float3 r0 = (float3)(1.0f - 2.0f * (y * y + z * z), 2.0f * (x * y - z * w), 2.0f * (x * z + y * w));
    float3 r1 = (float3)(2.0f * (x * y + z * w), 1.0f - 2.0f * (x * x + z * z), 2.0f * (y * z - x * w));
    float3 r2 = (float3)(2.0f * (x * z - y * w), 2.0f * (y * z + x * w), 1.0f - 2.0f * (x * x + y * y));
    float3 s0 = mix(xyz(motion->scale[0]), xyz(motion->scale[3]), s);
    float3 s1 = mix(xyz(motion->scale[1]), xyz(motion->scale[4]), s);
    float3 s2 = mix(xyz(motion->scale[2]), xyz(motion->scale[5]), s);
    float3 t = mix(xyz(motion->translation[0]), xyz(motion->translation[1]), s);
    /* L = R S, row i of L = (row i of R) S = r.x s0 + r.y s1 + r.z s2. */
    float3 l0 = r0.x * s0 + r0.y * s1 + r0.z * s2;
    float3 l1 = r1.x * s0 + r1.y * s1 + r1.z * s2;
    float3 l2 = r2.x * s0 + r2.y * s1 + r2.z * s2;
    to_world->r0 = (float4)(l0, t.x);
    to_world->r1 = (float4)(l1, t.y);
    to_world->r2 = (float4)(l2, t.z);
    /* L^-1 = adj(L) / det(L), by the rows' cross products: its columns are l1 x l2, l2 x l0,
     * l0 x l1 over det. */
    float3 c0 = cross(l1, l2), c1 = cross(l2, l0), c2 = cross(l0, l1);
    float inv_det = 1.0f / dot(l0, c0);
    float3 i0 = (float3)(c0.x, c1.x, c2.x) * inv_det;
    float3 i1 = (float3)(c0.y, c1.y, c2.y) * inv_det;
    float3 i2 = (float3)(c0.z, c1.z, c2.z) * inv_det;
    to_object->r0 = (float4)(i0, -dot(i0, t));
    to_object->r1 = (float4)(i1, -dot(i1, t));
    to_object->r2 = (float4)(i2, -dot(i2, t));
}

/* Instance i's matrices at shutter fraction s (the path's path_time: time = open + s (close -
 * open)): the stored ones for a static instance (or without PT_FEATURE(MOTION)), else the
 * motion's at s. */
inline void instance_at(const global Instance *instances, const global InstanceMotion *motions,
                        uint i, float s, Affine *to_world, Affine *to_object)
{
    const global Instance *inst = &instances[i];
    if (PT_FEATURE(MOTION) && inst->motion != INSTANCE_STATIC) {
        motion_at(&motions[inst->motion], s, to_world, to_object);
        return;
    }
    to_world->r0 = inst->to_world[0];
    to_world->r1 = inst->to_world[1];
    to_world->r2 = inst->to_world[2];
    to_object->r0 = inst->to_object[0];
    to_object->r1 = inst->to_object[1];
    to_object->r2 = inst->to_object[2];
}

/* Only the inverse, for the traversal (rays go into object space). */
inline Affine instance_to_object(const global Instance *instances,
                                 const global InstanceMotion *motions, uint i, float s)
{
    Affine to_world, to_object;
    const global Instance *inst = &instances[i];
    if (PT_FEATURE(MOTION) && inst->motion != INSTANCE_STATIC) {
        motion_at(&motions[inst->motion], s, &to_world, &to_object);
        return to_object;
    }
    to_object.r0 = inst->to_object[0];
    to_object.r1 = inst->to_object[1];
    to_object.r2 = inst->to_object[2];
    return to_object;
}
