/* SPDX-License-Identifier: MIT */
/* surface.cl: what a hit means: position, geometric and shading normals, uv, material; and the
 * triangle's uv parameterisation (dp/du, dp/dv) for the materials that need a tangent frame.
 *
 * Vertex data are in the instance's object space (cl/shared.h "Instances"); with
 * PT_FEATURE(INSTANCES) the hit is taken to world space through its instance at the path's time:
 * points and dp/du, dp/dv by to_world, normals by the inverse transpose (to_object transposed),
 * never flipped by det: the front of a mirrored instance is the side its inverse-transposed
 * normal points to (shared/DESIGN.md "Objects"), so its emitters shine and its glass refracts as
 * the unmirrored mesh's do. Textures are evaluated in object space (DESIGN "Textures": noise
 * sticks to a moving or instanced object), at object_position. One-level scenes have a single
 * world-space mesh: object space is world space and none of this is compiled. */

typedef struct {
    float3 position;         /* world space */
    float3 object_position;  /* object space: where textures are evaluated (texture_eval) */
    float3 geometric_normal; /* unit, world; counter-clockwise front in object space */
    float3 shading_normal;   /* unit, world; interpolated vertex normals when the mesh has them */
    float2 uv;
    uint material;
    Affine to_world; /* the hit's instance at the path's time (surface_uv_derivatives, MIS); set
                        only with PT_FEATURE(INSTANCES), a private struct's field costing nothing
                        when unread, so that code reads it behind if rather than #if */
} SurfaceHit;

/* time: the path's shutter fraction, where a moving instance is (path_time). */
PT_INLINE SurfaceHit surface_at(const SceneView *scene, Hit hit, float time)
{
    SurfaceHit s;
    const global float4 *positions = scene->positions, *normals = scene->normals;
    const global float2 *uvs = scene->uvs;
    uint4 tri = scene->triangles[hit.prim].v;
    float3 p0 = xyz(positions[tri.x]), p1 = xyz(positions[tri.y]), p2 = xyz(positions[tri.z]);
    float w0 = 1.0f - hit.u - hit.v;
    s.object_position = w0 * p0 + hit.u * p1 + hit.v * p2;
    float3 ng = cross(p1 - p0, p2 - p0);
    Affine to_object;
    if (PT_FEATURE(INSTANCES)) {
        instance_at(scene->instances, scene->instance_motion, hit.instance, time, &s.to_world,
                    &to_object);
        s.position = affine_point(s.to_world, s.object_position);
        ng = affine_normal(to_object, ng);
    } else {
        s.position = s.object_position;
    }
    s.geometric_normal = normalize(ng);
    s.shading_normal = s.geometric_normal;
    if (tri.w & TRIANGLE_HAS_NORMALS) {
        float3 n = w0 * xyz(normals[tri.x]) + hit.u * xyz(normals[tri.y]) + hit.v * xyz(normals[tri.z]);
        if (PT_FEATURE(INSTANCES))
            n = affine_normal(to_object, n);
        float len = length(n);
        if (len > 0.0f && isfinite(len))
            s.shading_normal = n / len;
    }
    if (tri.w & TRIANGLE_HAS_UVS)
        s.uv = w0 * uvs[tri.x] + hit.u * uvs[tri.y] + hit.v * uvs[tri.z];
    else
        s.uv = (float2)(hit.u, hit.v);
    s.material = scene->material_ids[hit.prim];
    return s;
}

/* The uv and object-space position of barycentrics (u, v) on triangle prim (what surface_at
 * computes, for the stages that need only these: the cut-out test during traversal, whose
 * textures are evaluated in object space as everywhere). */
inline float2 surface_uv_at(const SceneView *scene, uint prim, float u, float v, float3 *position)
{
    uint4 tri = scene->triangles[prim].v;
    float w0 = 1.0f - u - v;
    *position = w0 * xyz(scene->positions[tri.x]) + u * xyz(scene->positions[tri.y]) +
                v * xyz(scene->positions[tri.z]);
    if (tri.w & TRIANGLE_HAS_UVS)
        return w0 * scene->uvs[tri.x] + u * scene->uvs[tri.y] + v * scene->uvs[tri.z];
    return (float2)(u, v);
}

/* dp/du and dp/dv of the hit's triangle, constant over it (pbrt's Triangle::Intersect): in world
 * space (dpdu, dpdv: the tangent frame's) and in object space (object_dpdu, object_dpdv: steps
 * along the surface where textures are evaluated, as bump mapping's finite differences take). A
 * triangle without uvs uses its barycentrics as uv, so dp/du = p1 - p0 and dp/dv = p2 - p0: an
 * arbitrary but fixed frame (DESIGN "Conventions"). Degenerate uvs (zero or non-finite
 * determinant) fall back to an orthonormal basis around the geometric normal (in object space,
 * carried to world like the rest, so that both pairs stay one frame). Vectors go to world by
 * to_world's linear part: tangents stay tangent under any affine map. */
inline void surface_uv_derivatives(const SceneView *scene, uint prim, const SurfaceHit *surf,
                                   float3 *dpdu, float3 *dpdv, float3 *object_dpdu,
                                   float3 *object_dpdv)
{
    uint4 tri = scene->triangles[prim].v;
    float3 p0 = xyz(scene->positions[tri.x]);
    float3 e1 = xyz(scene->positions[tri.y]) - p0, e2 = xyz(scene->positions[tri.z]) - p0;
    float2 d1 = (float2)(1.0f, 0.0f), d2 = (float2)(0.0f, 1.0f);
    if (tri.w & TRIANGLE_HAS_UVS) {
        float2 uv0 = scene->uvs[tri.x];
        d1 = scene->uvs[tri.y] - uv0;
        d2 = scene->uvs[tri.z] - uv0;
    }
    float det = d1.x * d2.y - d1.y * d2.x;
    float inv = 1.0f / det;
    if (!(fabs(det) > 1e-20f) || !isfinite(inv)) {
        float3 n = PT_FEATURE(INSTANCES) ? normalize(cross(e1, e2)) : surf->geometric_normal;
        make_basis(n, object_dpdu, object_dpdv);
    } else {
        *object_dpdu = (d2.y * e1 - d1.y * e2) * inv;
        *object_dpdv = (d1.x * e2 - d2.x * e1) * inv;
    }
    if (PT_FEATURE(INSTANCES)) {
        *dpdu = affine_vector(surf->to_world, *object_dpdu);
        *dpdv = affine_vector(surf->to_world, *object_dpdv);
    } else {
        *dpdu = *object_dpdu;
        *dpdv = *object_dpdv;
    }
}
