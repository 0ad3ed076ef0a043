/* SPDX-License-Identifier: MIT */
/* surface.cl: what a hit means: position, geometric and shading normals, uv, material; and the
 * triangle's uv parameterisation (dp/du, dp/dv) for the materials that need a tangent frame. */

typedef struct {
    float3 position;
    float3 geometric_normal; /* unit, counter-clockwise front */
    float3 shading_normal;   /* unit; interpolated vertex normals when the mesh has them */
    float2 uv;
    uint material;
} SurfaceHit;

/* time: the path's shutter fraction, where a moving instance is (path_time). */
PT_INLINE SurfaceHit surface_at(const SceneView *scene, Hit hit, float time)
{
    (void)time;
    SurfaceHit s;
    const global float4 *positions = scene->positions, *normals = scene->normals;
    const global float2 *uvs = scene->uvs;
    uint4 tri = scene->triangles[hit.prim].v;
    float3 p0 = xyz(positions[tri.x]), p1 = xyz(positions[tri.y]), p2 = xyz(positions[tri.z]);
    float w0 = 1.0f - hit.u - hit.v;
    s.position = w0 * p0 + hit.u * p1 + hit.v * p2;
    s.geometric_normal = normalize(cross(p1 - p0, p2 - p0));
    s.shading_normal = s.geometric_normal;
    if (tri.w & TRIANGLE_HAS_NORMALS) {
        float3 n = w0 * xyz(normals[tri.x]) + hit.u * xyz(normals[tri.y]) + hit.v * xyz(normals[tri.z]);
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

/* The uv and position of barycentrics (u, v) on triangle prim (what surface_at computes, for the
 * stages that need only these: the cut-out test during traversal). */
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

/* dp/du and dp/dv of triangle prim, constant over it (pbrt's Triangle::Intersect). A triangle
 * without uvs uses its barycentrics as uv, so dp/du = p1 - p0 and dp/dv = p2 - p0: an arbitrary but
 * fixed frame (DESIGN "Conventions"). Degenerate uvs (zero or non-finite determinant) fall back to
 * an orthonormal basis around the geometric normal. */
inline void surface_uv_derivatives(const SceneView *scene, uint prim, float3 geometric_normal,
                                   float3 *dpdu, float3 *dpdv)
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
        make_basis(geometric_normal, dpdu, dpdv);
        return;
    }
    *dpdu = (d2.y * e1 - d1.y * e2) * inv;
    *dpdv = (d1.x * e2 - d2.x * e1) * inv;
}
