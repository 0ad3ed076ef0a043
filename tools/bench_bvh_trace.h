/* SPDX-License-Identifier: MIT */
/* bench_bvh_trace.h: tools/bench_bvh's trace benchmark: a mesh's BVH on the device, primary rays
 * and one diffuse bounce from their hits, each timed as closest-hit and any-hit queries (or, with
 * --count-steps, their work counted), a table row and a CSV row per query. Header-only (static
 * functions), like bench_common.h, so that tools/bench_bvh.c stays one translation unit. */
#ifndef PT_BENCH_BVH_TRACE_H
#define PT_BENCH_BVH_TRACE_H

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel/bvh.h"
#include "accel/bvh_wide.h"
#include "base/error.h"
#include "base/fs.h"
#include "bench_bvh_options.h"
#include "bench_bvh_rays.h"
#include "device/device.h"
#include "procedural_mesh.h"

typedef struct {
    Device *dev;
    cl_kernel closest, any, bounce;
    cl_mem nodes, tris, corners;
    uint32_t num_tris;
    /* BVH_PERSISTENT=K (experiment): closest hits by the persistent-thread kernel, K work items
     * per compute unit, taking rays from counter. */
    cl_kernel persistent;
    cl_mem counter;
    size_t persistent_items;
    uint32_t num_prims; /* entries of tris: triangles, or packs of the wide layout */
    cl_kernel count;    /* --count-steps: bvh_test_count_steps, else NULL */
    /* BVH_PACKET=1 (experiment, 8-wide layout): closest and any hits by the packet kernels, eight
     * rays per work item, checked bit for bit against the plain kernels. */
    cl_kernel packet_closest, packet_any;
} GpuMesh;

static cl_mem upload(Device *dev, const char *name, size_t size, const void *data)
{
    Error err = {0};
    cl_mem buf = device_buffer(dev, name, data ? CL_MEM_READ_ONLY : CL_MEM_READ_WRITE, size, data, &err);
    if (!buf)
        die("%s", err.message);
    return buf;
}

/* Best kernel time in ms over reps runs after a warm-up run. */
static double time_query(GpuMesh *g, cl_kernel kernel, cl_mem rays, uint32_t n, cl_mem out, int reps)
{
    cl_uint num_rays = n;
    KERNEL_ARG(kernel, 0, g->nodes);
    KERNEL_ARG(kernel, 1, g->tris);
    KERNEL_ARG(kernel, 2, g->num_prims);
    KERNEL_ARG(kernel, 3, rays);
    KERNEL_ARG(kernel, 4, num_rays);
    KERNEL_ARG(kernel, 5, out);
    size_t items = n;
    if (kernel == g->packet_closest || kernel == g->packet_any)
        items = (n + 7u) / 8u;
    if (kernel == g->persistent) {
        KERNEL_ARG(kernel, 6, g->counter);
        if (g->persistent_items < items)
            items = g->persistent_items;
    }
    double best = INFINITY;
    for (int r = 0; r <= reps; r++) {
        double ms;
        if (kernel == g->persistent) {
            cl_uint zero = 0;
            CL_CHECK(clEnqueueFillBuffer(g->dev->queue, g->counter, &zero, sizeof zero, 0,
                                         sizeof zero, 0, NULL, NULL));
        }
        device_run(g->dev, kernel, items, 0, &ms);
        if (r > 0 && ms < best)
            best = ms;
    }
    return best;
}

/* The persistent and dynamic kernels hand rays to work items in another order, which must not
 * change any ray's result: they are checked bit for bit against the plain kernel. */
static void check_same_hits_of(GpuMesh *g, cl_kernel kernel, size_t size, cl_mem rays, uint32_t n,
                              cl_mem hits)
{
    cl_mem plain = upload(g->dev, "plain_hits", n * size, NULL);
    time_query(g, kernel, rays, n, plain, 0);
    char *a = malloc(2 * (size_t)n * size);
    if (!a)
        die("out of memory for %u hits", n);
    device_read(g->dev, hits, 0, n * size, a);
    device_read(g->dev, plain, 0, n * size, a + n * size);
    for (uint32_t i = 0; i < n; i++)
        if (memcmp(a + i * size, a + (n + i) * size, size))
            die("ray %u: the persistent, dynamic or packet kernel's hit differs from the plain kernel's", i);
    free(a);
    CL_CHECK(clReleaseMemObject(plain));
}

/* --count-steps: per closest-hit query, node visits and triangle tests (packs on the wide
 * layouts), their means, and their SIMD efficiency on 32-lane warps: the mean over the mean of
 * each warp's largest count, i.e. the share of lanes busy while a warp walks as long as its
 * longest ray (rays in launch order, one per work item). */
#define STEPS_WARP 32
static void count_steps(FILE *csv, GpuMesh *g, const char *name, const char *kind, cl_mem rays,
                        uint32_t n)
{
    cl_mem counts_buf = upload(g->dev, "step_counts", n * sizeof(cl_uint2), NULL);
    time_query(g, g->count, rays, n, counts_buf, 0);
    cl_uint2 *counts = malloc(n * sizeof *counts);
    if (!counts)
        die("out of memory for %u counts", n);
    device_read(g->dev, counts_buf, 0, n * sizeof *counts, counts);
    CL_CHECK(clReleaseMemObject(counts_buf));
    /* part 0: node visits, part 1: triangle (or pack) tests */
    double mean[2] = {0, 0}, warp_max[2] = {0, 0};
    for (uint32_t w = 0; w < n; w += STEPS_WARP) {
        uint32_t lanes = n - w < STEPS_WARP ? n - w : STEPS_WARP;
        for (int part = 0; part < 2; part++) {
            uint32_t most = 0;
            for (uint32_t i = w; i < w + lanes; i++) {
                mean[part] += counts[i].s[part];
                most = counts[i].s[part] > most ? counts[i].s[part] : most;
            }
            warp_max[part] += (double)most * lanes;
        }
    }
    free(counts);
    for (int part = 0; part < 2; part++) {
        warp_max[part] /= n;
        mean[part] /= n;
    }
    printf("%-16s %9u %-8s %9u %9.2f %9.2f %6.3f %9.2f %9.2f %6.3f\n", name, g->num_tris, kind, n,
           mean[0], warp_max[0], mean[0] / warp_max[0], mean[1], warp_max[1], mean[1] / warp_max[1]);
    fprintf(csv, "%s,%u,%s,%u,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", name, g->num_tris, kind, n, mean[0],
            warp_max[0], mean[0] / warp_max[0], mean[1], warp_max[1], mean[1] / warp_max[1]);
    fflush(stdout);
}

/* Times closest and any hit for one batch; returns the hit fraction and leaves hits in `hits`. */
static void bench_queries(FILE *csv, GpuMesh *g, const char *name, const char *kind, cl_mem rays,
                          uint32_t n, cl_mem hits, cl_mem occluded, int reps)
{
    if (g->count) {
        time_query(g, g->closest, rays, n, hits, 0); /* the hits the diffuse rays start from */
        count_steps(csv, g, name, kind, rays, n);
        return;
    }
    cl_kernel closest = g->persistent ? g->persistent : g->packet_closest ? g->packet_closest : g->closest;
    double closest_ms = time_query(g, closest, rays, n, hits, reps);
    if (g->persistent || g->packet_closest)
        check_same_hits_of(g, g->closest, sizeof(float4), rays, n, hits);
    double any_ms = time_query(g, g->packet_any ? g->packet_any : g->any, rays, n, occluded, reps);
    if (g->packet_any)
        check_same_hits_of(g, g->any, sizeof(cl_uint), rays, n, occluded);
    cl_uint *flags = malloc(n * sizeof *flags);
    device_read(g->dev, occluded, 0, n * sizeof *flags, flags);
    uint32_t num_hits = 0;
    for (uint32_t i = 0; i < n; i++)
        num_hits += flags[i];
    free(flags);
    double hit_fraction = n ? (double)num_hits / n : 0.0;
    printf("%-16s %9u %-8s %9u %6.3f %10.2f %9.2f %10.2f %9.2f %9.1f\n", name, g->num_tris, kind, n,
           hit_fraction, closest_ms, n / closest_ms * 1e-3, any_ms, n / any_ms * 1e-3,
           closest_ms * 1e6 / n);
    fprintf(csv, "%s,%u,%s,closest,%u,%.4f,%.4f,%.4f\n", name, g->num_tris, kind, n, closest_ms,
            n / closest_ms * 1e-3, hit_fraction);
    fprintf(csv, "%s,%u,%s,any,%u,%.4f,%.4f,%.4f\n", name, g->num_tris, kind, n, any_ms,
            n / any_ms * 1e-3, hit_fraction);
    fflush(stdout);
}

/* --write-rays: DIR/NAME-SUFFIX, count records of `size` bytes. */
static void write_records(const char *dir, const char *name, const char *suffix, const void *data,
                          size_t size, size_t count)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s%s", dir, name, suffix);
    FILE *f = fs_make_parent_dirs(path) ? fopen(path, "wb") : NULL;
    if (!f)
        die("cannot write %s: %s", path, strerror(errno));
    if (fwrite(data, size, count, f) != count || fclose(f) != 0)
        die("cannot write %s: %s", path, strerror(errno));
}

static void bench_trace(FILE *csv, Device *dev, const char *name, const TestMesh *mesh, const Options *o)
{
    GpuMesh g = {dev, device_kernel(dev, "bvh_test_trace_closest"),
                 device_kernel(dev, "bvh_test_trace_any"), device_kernel(dev, "bvh_test_bounce_rays"),
                 NULL, NULL, NULL, mesh->num_triangles, NULL, NULL, 0, 0,
                 o->count_steps ? device_kernel(dev, "bvh_test_count_steps") : NULL, NULL, NULL};
    const char *persistent = getenv("BVH_PERSISTENT"), *dynamic = getenv("BVH_DYNAMIC");
    if (dynamic && atoi(dynamic) > 0)
        persistent = dynamic;
    if (persistent && atoi(persistent) > 0) {
        Error err = {0};
        g.persistent = device_kernel(dev, persistent == dynamic ? "bvh_test_trace_closest_dynamic"
                                                                : "bvh_test_trace_closest_persistent");
        g.counter = device_buffer(dev, "ray_counter", CL_MEM_READ_WRITE, sizeof(cl_uint), NULL, &err);
        if (!g.counter)
            die("%s", err.message);
        g.persistent_items = (size_t)dev->compute_units * (size_t)atoi(persistent);
    }
    if (getenv("BVH_PACKET") && atoi(getenv("BVH_PACKET")) > 0 && dev->bvh_width == 8) {
        g.packet_closest = device_kernel(dev, "bvh_test_trace_closest_packet");
        g.packet_any = device_kernel(dev, "bvh_test_trace_any_packet");
    }
    Bvh bvh;
    bvh_build_for_width(&bvh, mesh->positions, mesh->triangles, mesh->num_triangles, dev->bvh_width);
    BvhLayout layout;
    bvh_layout(&layout, &bvh, dev->bvh_width, dev->bvh_quantized);
    g.nodes = upload(dev, "bvh_nodes", layout.num_nodes * layout.node_size, layout.nodes);
    g.tris = upload(dev, "bvh_triangles", layout.num_prims * layout.prim_size, layout.prims);
    g.num_prims = layout.num_prims;
    bvh_layout_free(&layout);
    bvh_free(&bvh);
    float4 *corners = malloc(3 * (size_t)mesh->num_triangles * sizeof *corners);
    for (uint32_t i = 0; i < mesh->num_triangles; i++)
        for (int c = 0; c < 3; c++)
            corners[3 * i + c] = mesh->positions[mesh->triangles[i].v.s[c]];
    g.corners = upload(dev, "corners", 3 * (size_t)mesh->num_triangles * sizeof *corners, corners);
    if (o->write_rays) {
        float *tris = malloc(9 * (size_t)mesh->num_triangles * sizeof *tris);
        if (!tris)
            die("out of memory for %u triangles", mesh->num_triangles);
        for (size_t i = 0; i < 3 * (size_t)mesh->num_triangles; i++)
            for (int k = 0; k < 3; k++)
                tris[3 * i + (size_t)k] = corners[i].s[k];
        write_records(o->write_rays, name, ".tris", tris, 9 * sizeof *tris, mesh->num_triangles);
        free(tris);
    }
    free(corners);

    uint32_t n;
    Ray *rays = primary_rays(mesh, o->spp, o->order, &n);
    cl_mem ray_buf = upload(dev, "rays", n * sizeof(Ray), rays);
    cl_mem hits = upload(dev, "hits", n * sizeof(float4), NULL);
    cl_mem occluded = upload(dev, "occluded", n * sizeof(cl_uint), NULL);
    cl_mem bounce = upload(dev, "bounce_rays", n * sizeof(Ray), NULL);
    if (o->write_rays)
        write_records(o->write_rays, name, "-primary.rays", rays, sizeof(Ray), n);
    bench_queries(csv, &g, name, "primary", ray_buf, n, hits, occluded, o->reps);

    /* Diffuse bounce from the closest hits (left in `hits`), compacted to the rays that hit. */
    cl_uint num_rays = n, seed = 1, reflect = 1;
    KERNEL_ARG(g.bounce, 0, g.corners);
    KERNEL_ARG(g.bounce, 1, ray_buf);
    KERNEL_ARG(g.bounce, 2, hits);
    KERNEL_ARG(g.bounce, 3, num_rays);
    KERNEL_ARG(g.bounce, 4, seed);
    KERNEL_ARG(g.bounce, 5, reflect);
    KERNEL_ARG(g.bounce, 6, bounce);
    device_run(dev, g.bounce, n, 0, NULL);
    device_read(dev, bounce, 0, n * sizeof(Ray), rays);
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; i++)
        if (rays[i].dir.s[0] != 0.0f || rays[i].dir.s[1] != 0.0f || rays[i].dir.s[2] != 0.0f)
            rays[m++] = rays[i];
    device_write(dev, bounce, 0, m * sizeof(Ray), rays);
    if (o->write_rays)
        write_records(o->write_rays, name, "-diffuse.rays", rays, sizeof(Ray), m);
    bench_queries(csv, &g, name, "diffuse", bounce, m, hits, occluded, o->reps);

    free(rays);
    cl_mem buffers[] = {g.nodes, g.tris, g.corners, ray_buf, hits, occluded, bounce};
    for (size_t i = 0; i < sizeof buffers / sizeof buffers[0]; i++)
        CL_CHECK(clReleaseMemObject(buffers[i]));
    CL_CHECK(clReleaseKernel(g.closest));
    CL_CHECK(clReleaseKernel(g.any));
    CL_CHECK(clReleaseKernel(g.bounce));
    if (g.persistent) {
        CL_CHECK(clReleaseKernel(g.persistent));
        CL_CHECK(clReleaseMemObject(g.counter));
    }
}

#endif
