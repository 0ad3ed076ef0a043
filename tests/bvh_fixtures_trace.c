// SPDX-License-Identifier: MIT
/* bvh_fixtures_trace.c: a mesh's BVH on the test device, traced by the batch kernels of
 * tests/cl/bvh_test.cl, and the random rays the BVH tests shoot into it (bvh_fixtures.h). */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh_wide.h"
#include "bvh_fixtures.h"

TraceScene trace_scene_create(Device *dev, TestMesh mesh)
{
    TraceScene scene = {dev, mesh, {0}, NULL, NULL, 0, NULL, {0}, {0}};
    Error err = {0};
    bvh_build_for_width(&scene.bvh, mesh.positions, mesh.triangles, mesh.num_triangles, dev->bvh_width);
    mesh_bounds(&mesh, scene.lo, scene.hi);
    BvhLayout layout;
    bvh_layout(&layout, &scene.bvh, dev->bvh_width, dev->bvh_quantized);
    scene.nodes = device_buffer(dev, "bvh_nodes", CL_MEM_READ_ONLY,
                                layout.num_nodes * layout.node_size, layout.nodes, &err);
    scene.tris = device_buffer(dev, "bvh_triangles", CL_MEM_READ_ONLY,
                               layout.num_prims * layout.prim_size, layout.prims, &err);
    scene.num_prims = layout.num_prims;
    bvh_layout_free(&layout);
    cr_assert(!error_is_set(&err), "%s", err.message);
    scene.spheres = malloc((mesh.num_triangles + 1) * sizeof *scene.spheres);
    for (uint32_t i = 0; i < mesh.num_triangles; i++) {
        /* Centre at the corners' mean, radius to the farthest corner, rounded up. */
        const float4 *p[3];
        double center[3] = {0, 0, 0}, radius = 0.0;
        for (int c = 0; c < 3; c++) {
            p[c] = &mesh.positions[mesh.triangles[i].v.s[c]];
            for (int k = 0; k < 3; k++)
                center[k] += p[c]->s[k] / 3.0;
        }
        for (int c = 0; c < 3; c++) {
            double d2 = 0.0;
            for (int k = 0; k < 3; k++)
                d2 += (p[c]->s[k] - center[k]) * (p[c]->s[k] - center[k]);
            radius = fmax(radius, sqrt(d2));
        }
        scene.spheres[i] =
            vec((float)center[0], (float)center[1], (float)center[2], (float)(radius * 1.001));
    }
    return scene;
}

void trace_scene_release(TraceScene *scene)
{
    clReleaseMemObject(scene->nodes);
    clReleaseMemObject(scene->tris);
    free(scene->spheres);
    bvh_free(&scene->bvh);
    test_mesh_free(&scene->mesh);
}

void trace(TraceScene *scene, const char *kernel_name, const Ray *rays, uint32_t n, void *out)
{
    Device *dev = scene->dev;
    Error err = {0};
    bool closest = strstr(kernel_name, "closest") != NULL;
    size_t out_size = n * (closest ? sizeof(float4) : sizeof(cl_uint));
    cl_mem ray_buf = device_buffer(dev, "rays", CL_MEM_READ_ONLY, n * sizeof(Ray), rays, &err);
    cl_mem out_buf = device_buffer(dev, "results", CL_MEM_WRITE_ONLY, out_size, NULL, &err);
    cr_assert(!error_is_set(&err), "%s", err.message);
    cl_kernel kernel = device_kernel(dev, kernel_name);
    cl_uint arg = 0, num_tris = scene->num_prims, num_rays = n;
    KERNEL_ARG(kernel, arg++, scene->nodes);
    KERNEL_ARG(kernel, arg++, scene->tris);
    KERNEL_ARG(kernel, arg++, num_tris);
    KERNEL_ARG(kernel, arg++, ray_buf);
    KERNEL_ARG(kernel, arg++, num_rays);
    KERNEL_ARG(kernel, arg++, out_buf);
    double ms = 0.0;
    device_run(dev, kernel, n, 0, &ms);
    if (getenv("BVH_TEST_TIMES"))
        cr_log_info("%s: %u rays, %u triangles: %.1f ms", kernel_name, n, num_tris, ms);
    device_read(dev, out_buf, 0, out_size, out);
    clReleaseKernel(kernel);
    clReleaseMemObject(ray_buf);
    clReleaseMemObject(out_buf);
}

void random_direction(uint64_t *rng, float dir[3])
{
    float z = 2.0f * mesh_rng_float(rng) - 1.0f, phi = 6.2831853f * mesh_rng_float(rng);
    float r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
    dir[0] = r * cosf(phi);
    dir[1] = r * sinf(phi);
    dir[2] = z;
}

/* A mix of the rays a renderer traces and the awkward ones: from outside the bounds toward points
 * inside them, from inside the bounds in any direction, exactly axis-parallel (with +0 and -0 in
 * the other components, origins on vertex coordinates so they lie in box planes), aimed exactly
 * at vertices, some with tmin > 0 and some with finite tmax. */
Ray *random_rays(const TraceScene *scene, uint32_t n, uint64_t seed)
{
    Ray *rays = malloc(n * sizeof *rays);
    uint64_t rng = seed;
    float center[3], extent[3], radius = 0.0f;
    for (int k = 0; k < 3; k++) {
        center[k] = 0.5f * (scene->lo[k] + scene->hi[k]);
        extent[k] = scene->hi[k] - scene->lo[k];
        radius += 0.25f * extent[k] * extent[k];
    }
    radius = sqrtf(radius);
    const TestMesh *mesh = &scene->mesh;
    for (uint32_t i = 0; i < n; i++) {
        float kind = mesh_rng_float(&rng), origin[3], target[3], dir[3];
        const float4 vertex =
            mesh->positions[mesh->triangles[mesh_rng_next(&rng) % mesh->num_triangles].v.s[0]];
        for (int k = 0; k < 3; k++)
            target[k] = scene->lo[k] + extent[k] * mesh_rng_float(&rng);
        if (kind < 0.45f || kind >= 0.85f) {
            /* From a sphere around the bounds toward a point inside them or a vertex. */
            random_direction(&rng, dir);
            for (int k = 0; k < 3; k++) {
                origin[k] = center[k] + 1.5f * radius * dir[k];
                dir[k] = (kind >= 0.85f ? vertex.s[k] : target[k]) - origin[k];
            }
            normalize3(dir);
        } else if (kind < 0.7f) {
            memcpy(origin, target, sizeof origin);
            random_direction(&rng, dir);
        } else {
            int axis = (int)(mesh_rng_next(&rng) % 3);
            float sign = mesh_rng_float(&rng) < 0.5f ? -1.0f : 1.0f;
            for (int k = 0; k < 3; k++) {
                origin[k] = mesh_rng_float(&rng) < 0.5f ? vertex.s[k] : target[k];
                dir[k] = mesh_rng_float(&rng) < 0.5f ? 0.0f : -0.0f;
            }
            origin[axis] = center[axis] - sign * (mesh_rng_float(&rng) < 0.5f ? 2.0f * radius : 0.0f);
            dir[axis] = sign;
        }
        float tmin = mesh_rng_float(&rng) < 0.1f ? radius * mesh_rng_float(&rng) : 0.0f;
        float tmax = mesh_rng_float(&rng) < 0.2f ? tmin + 2.0f * radius * mesh_rng_float(&rng)
                                                 : INFINITY;
        rays[i] = make_ray(origin, dir, tmin, tmax);
    }
    return rays;
}
