/* SPDX-License-Identifier: MIT */
/* surface.cl: what a hit means: position, geometric and shading normals, uv, material. */

typedef struct {
    float3 position;
    float3 geometric_normal; /* unit, counter-clockwise front */
    float3 shading_normal;   /* unit; interpolated vertex normals when the mesh has them */
    float2 uv;
    uint material;
} SurfaceHit;

PT_INLINE SurfaceHit surface_at(const SceneView *scene, Hit hit)
{
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
