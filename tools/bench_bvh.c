// SPDX-License-Identifier: MIT
/* bench_bvh: BVH build and traversal throughput.
 *
 *   build/tools/bench_bvh [--device gpu|cpu|P:D] [--spp N] [--reps R] [--assets DIR]
 *                         [--max-triangles N] [--out DIR] [--order tiles|rows] [--count-steps]
 *
 * Build: bumpy tori of 10^3 .. 2*10^6 triangles and the dragon and skull assets; time on one core
 * (best of several runs, wall clock and thread CPU time), Mtris/s, node count, SAH cost, and for
 * meshes up to 200k triangles the SAH cost of the full-sweep reference build.
 * Trace: primary rays (480x320 pixels x spp samples in 4x4-pixel tiles, as tinybvh's speed test
 * orders them, or scanlines with --order rows; camera 1.4 bounding radii from the centre, 50
 * degrees field of view) and one diffuse bounce from their hits (cosine about the geometric
 * normal, origin from offset_ray_origin), each as closest-hit and any-hit queries, on the dragon,
 * the skull and tori of 10^3 .. 10^6 triangles (the scaling of time per ray). Kernel times come
 * from profiling events: the best of R runs after a warm-up run.
 * CSVs go to DIR/<device>/bvh_build.csv and bvh_trace.csv (DIR: bench/results); a table is
 * printed. Run from the repository root: the batch kernels are tests/cl/bvh_test.cl.
 * --count-steps: instead of timing, builds the traversal with its work counters
 * (-DBVH_COUNT_STEPS) and writes bvh_steps.csv: node visits and triangle (or pack) tests per
 * closest-hit query, and how full 32-lane warps are while the longest ray of each walks.
 * Experiments, kept to reproduce their measurements (bench/README.md), closest hits by:
 * BVH_PERSISTENT=K: persistent threads (K work items per compute unit taking rays from a global
 * counter; on NVIDIA one atomic per warp via inline PTX); no gain on the H100.
 * BVH_DYNAMIC=K: dynamic fetch (the same, but a work item starts a new ray as soon as its own is
 * done, on NVIDIA when DYNAMIC_FETCH_THRESHOLD lanes of the warp are idle); no gain on the H100.
 * Both are checked bit for bit against the plain kernel's hits. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "bench_common.h"
#include "accel/bvh.h"
#include "accel/bvh_wide.h"
#include "device/device.h"
#include "io/obj_loader.h"
#include "procedural_mesh.h"

#define KERNEL_FILE "tests/cl/bvh_test.cl"
#define IMAGE_WIDTH 480
#define IMAGE_HEIGHT 320

typedef struct {
    const char *device, *assets, *out;
    int spp, reps;
    uint32_t max_triangles;
    bool rows;        /* --order rows: pixels in scanline order instead of 4x4 tiles */
    bool count_steps; /* --count-steps: node visits and triangle tests per ray instead of timings */
} Options;

/* Ray as the batch kernels read it: origin with tmin in w, direction with tmax in w. */
typedef struct {
    float4 origin, dir;
} Ray;

static void usage(void)
{
    fprintf(stderr, "usage: bench_bvh [--device gpu|cpu|P:D] [--spp N] [--reps R] [--assets DIR] "
                    "[--max-triangles N] [--out DIR] [--order tiles|rows]\n"
                    "                 [--count-steps]\n");
    exit(2);
}

static Options parse_options(int argc, char **argv)
{
    Options o = {NULL, "../shared/assets", "bench/results", 16, 3, 2000000, false, false};
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--count-steps")) {
            o.count_steps = true;
            continue;
        }
        if (i + 1 >= argc)
            usage();
        const char *key = argv[i], *value = argv[++i];
        if (!strcmp(key, "--device"))
            o.device = value;
        else if (!strcmp(key, "--assets"))
            o.assets = value;
        else if (!strcmp(key, "--out"))
            o.out = value;
        else if (!strcmp(key, "--spp"))
            o.spp = atoi(value);
        else if (!strcmp(key, "--reps"))
            o.reps = atoi(value);
        else if (!strcmp(key, "--max-triangles"))
            o.max_triangles = (uint32_t)strtoul(value, NULL, 10);
        else if (!strcmp(key, "--order") && (!strcmp(value, "tiles") || !strcmp(value, "rows")))
            o.rows = !strcmp(value, "rows");
        else
            usage();
    }
    if (o.spp < 1 || o.reps < 1)
        usage();
    return o;
}

static double seconds(clockid_t clock)
{
    struct timespec ts;
    clock_gettime(clock, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* bench_common.h's CSV opener (it creates the folders) plus the header line. */
static FILE *open_csv(const char *folder, const char *name, const char *header)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", folder, name);
    FILE *f = bench_open_csv(path);
    fprintf(f, "%s\n", header);
    return f;
}

/* ---- Build ------------------------------------------------------------------------------------ */

static void bench_build(FILE *csv, const char *name, const Mesh *mesh)
{
    uint32_t n = mesh->num_triangles;
    int runs = n <= 100000 ? 7 : 3;
    double best_wall = INFINITY, best_cpu = INFINITY;
    Bvh bvh = {0};
    for (int r = 0; r < runs; r++) {
        bvh_free(&bvh);
        double wall = seconds(CLOCK_MONOTONIC), cpu = seconds(CLOCK_THREAD_CPUTIME_ID);
        bvh_build(&bvh, mesh->positions, mesh->triangles, n);
        cpu = seconds(CLOCK_THREAD_CPUTIME_ID) - cpu;
        wall = seconds(CLOCK_MONOTONIC) - wall;
        best_wall = wall < best_wall ? wall : best_wall;
        best_cpu = cpu < best_cpu ? cpu : best_cpu;
    }
    /* The reference is O(n log^2 n) with qsort: only where it takes seconds, not minutes. */
    double full_sweep = NAN;
    if (n <= 200000) {
        Bvh reference;
        bvh_build_full_sweep(&reference, mesh->positions, mesh->triangles, n);
        full_sweep = reference.sah_cost;
        bvh_free(&reference);
    }
    printf("%-16s %9u %10.2f %9.2f %9.2f %9u %9.2f %9.2f %+8.2f%%\n", name, n, best_wall * 1e3,
           n / best_wall * 1e-6, n / best_cpu * 1e-6, bvh.num_nodes, bvh.sah_cost, full_sweep,
           100.0 * (bvh.sah_cost / full_sweep - 1.0));
    fprintf(csv, "%s,%u,%.4f,%.4f,%.4f,%.4f,%u,%.4f,%.4f\n", name, n, best_wall * 1e3, best_cpu * 1e3,
            n / best_wall * 1e-6, n / best_cpu * 1e-6, bvh.num_nodes, bvh.sah_cost, full_sweep);
    fflush(stdout);
    bvh_free(&bvh);
}

/* ---- Trace ------------------------------------------------------------------------------------ */

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
} GpuMesh;

static cl_mem upload(Device *dev, const char *name, size_t size, const void *data)
{
    Error err = {0};
    cl_mem buf = device_buffer(dev, name, data ? CL_MEM_READ_ONLY : CL_MEM_READ_WRITE, size, data, &err);
    if (!buf)
        die("%s", err.message);
    return buf;
}

/* Pinhole camera 1.4 bounding radii (half the bounds' diagonal) from the centre, looking at it
 * from a fixed oblique direction, 50 degrees vertical field of view: the meshes fill most of the
 * frame (a view that fits the whole bounding sphere, 91 degrees, leaves 90% of the rays to
 * miss). Rays are stored as tinybvh's speed test stores them: pixels in 4x4 tiles, each pixel's
 * samples together, stratified on a k x k grid when spp = k^2 (jittered within each cell, from
 * splitmix64). A warp so holds two neighbouring pixels and a GPU core's resident rays a compact
 * patch of the image; rows (--order rows) spread that patch along a scanline. */
#define RAY_TILE 4
_Static_assert(IMAGE_WIDTH % RAY_TILE == 0 && IMAGE_HEIGHT % RAY_TILE == 0, "whole tiles");
static Ray *primary_rays(const Mesh *mesh, int spp, bool rows, uint32_t *count)
{
    float lo[3], hi[3], center[3], radius = 0.0f;
    mesh_bounds(mesh, lo, hi);
    for (int k = 0; k < 3; k++) {
        center[k] = 0.5f * (lo[k] + hi[k]);
        radius += 0.25f * (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    radius = sqrtf(radius);
    const float view[3] = {0.57f, 0.42f, 0.71f}; /* from the centre toward the eye, unit length */
    float eye[3], forward[3], right[3], up[3];
    for (int k = 0; k < 3; k++) {
        eye[k] = center[k] + 1.4f * radius * view[k];
        forward[k] = -view[k];
    }
    /* right = forward x (0, 1, 0), up = right x forward */
    float rlen = sqrtf(forward[2] * forward[2] + forward[0] * forward[0]);
    right[0] = -forward[2] / rlen;
    right[1] = 0.0f;
    right[2] = forward[0] / rlen;
    up[0] = right[1] * forward[2] - right[2] * forward[1];
    up[1] = right[2] * forward[0] - right[0] * forward[2];
    up[2] = right[0] * forward[1] - right[1] * forward[0];
    float tan_half = tanf(0.5f * 50.0f * 3.14159265f / 180.0f), aspect = (float)IMAGE_WIDTH / IMAGE_HEIGHT;
    uint32_t n = (uint32_t)IMAGE_WIDTH * IMAGE_HEIGHT * (uint32_t)spp;
    Ray *rays = malloc(n * sizeof *rays);
    if (!rays)
        die("out of memory for %u rays", n);
    int strata = (int)sqrt((double)spp);
    if (strata * strata != spp)
        strata = 1;
    uint64_t rng = 1;
    uint32_t i = 0;
    for (uint32_t pixel = 0; pixel < (uint32_t)IMAGE_WIDTH * IMAGE_HEIGHT; pixel++) {
        int x = (int)(pixel % IMAGE_WIDTH), y = (int)(pixel / IMAGE_WIDTH);
        if (!rows) { /* IMAGE_WIDTH and IMAGE_HEIGHT are multiples of RAY_TILE */
            uint32_t tile = pixel / (RAY_TILE * RAY_TILE), within = pixel % (RAY_TILE * RAY_TILE);
            x = (int)(tile % (IMAGE_WIDTH / RAY_TILE) * RAY_TILE + within % RAY_TILE);
            y = (int)(tile / (IMAGE_WIDTH / RAY_TILE) * RAY_TILE + within / RAY_TILE);
        }
        for (int s = 0; s < spp; s++, i++) {
            float jx = ((float)(s % strata) + mesh_rng_float(&rng)) / (float)strata;
            float jy = ((float)(s / strata % strata) + mesh_rng_float(&rng)) / (float)strata;
            float sx = (2.0f * (x + jx) / IMAGE_WIDTH - 1.0f) * tan_half * aspect;
            float sy = (1.0f - 2.0f * (y + jy) / IMAGE_HEIGHT) * tan_half;
            float d[3];
            for (int k = 0; k < 3; k++)
                d[k] = forward[k] + sx * right[k] + sy * up[k];
            float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            float4 origin = {{eye[0], eye[1], eye[2], 0.0f}};
            float4 dir = {{d[0] / len, d[1] / len, d[2] / len, INFINITY}};
            rays[i].origin = origin;
            rays[i].dir = dir;
        }
    }
    *count = n;
    return rays;
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
static void check_same_hits(GpuMesh *g, cl_mem rays, uint32_t n, cl_mem hits)
{
    cl_mem plain = upload(g->dev, "plain_hits", n * sizeof(float4), NULL);
    time_query(g, g->closest, rays, n, plain, 0);
    float4 *a = malloc(2 * (size_t)n * sizeof *a);
    if (!a)
        die("out of memory for %u hits", n);
    device_read(g->dev, hits, 0, n * sizeof *a, a);
    device_read(g->dev, plain, 0, n * sizeof *a, a + n);
    for (uint32_t i = 0; i < n; i++)
        if (memcmp(&a[i], &a[n + i], sizeof *a))
            die("ray %u: the persistent or dynamic kernel's hit differs from the plain kernel's", i);
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
    double closest_ms = time_query(g, g->persistent ? g->persistent : g->closest, rays, n, hits, reps);
    if (g->persistent)
        check_same_hits(g, rays, n, hits);
    double any_ms = time_query(g, g->any, rays, n, occluded, reps);
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

static void bench_trace(FILE *csv, Device *dev, const char *name, const Mesh *mesh, const Options *o)
{
    GpuMesh g = {dev, device_kernel(dev, "bvh_test_trace_closest"),
                 device_kernel(dev, "bvh_test_trace_any"), device_kernel(dev, "bvh_test_bounce_rays"),
                 NULL, NULL, NULL, mesh->num_triangles, NULL, NULL, 0, 0,
                 o->count_steps ? device_kernel(dev, "bvh_test_count_steps") : NULL};
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
    free(corners);

    uint32_t n;
    Ray *rays = primary_rays(mesh, o->spp, o->rows, &n);
    cl_mem ray_buf = upload(dev, "rays", n * sizeof(Ray), rays);
    cl_mem hits = upload(dev, "hits", n * sizeof(float4), NULL);
    cl_mem occluded = upload(dev, "occluded", n * sizeof(cl_uint), NULL);
    cl_mem bounce = upload(dev, "bounce_rays", n * sizeof(Ray), NULL);
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

/* ---- Main ------------------------------------------------------------------------------------- */

static bool load_asset(const Options *o, const char *relative, Mesh *mesh)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", o->assets, relative);
    ObjMesh obj;
    Error err = {0};
    warnings_set_quiet(true);
    if (!obj_load(path, &obj, &err)) {
        fprintf(stderr, "bench_bvh: skipping %s: %s\n", relative, err.message);
        return false;
    }
    *mesh = mesh_from_obj(&obj);
    obj_free(&obj);
    return true;
}

int main(int argc, char **argv)
{
    Options o = parse_options(argc, argv);
    Device dev;
    Error err = {0};
    if (!device_open(&dev, o.device, &err))
        die("%s", err.message);
    char *source = NULL;
    FILE *f = fopen(KERNEL_FILE, "rb");
    if (!f)
        die("cannot read %s: run bench_bvh from the repository root", KERNEL_FILE);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    source = calloc((size_t)size + 1, 1);
    if (!source || fread(source, 1, (size_t)size, f) != (size_t)size)
        die("cannot read %s", KERNEL_FILE);
    fclose(f);
    if (o.count_steps) { /* the counters sit in the traversal itself, so they need their own build */
        size_t used = strlen(dev.build_options);
        snprintf(dev.build_options + used, sizeof dev.build_options - used, " -DBVH_COUNT_STEPS");
    }
    if (!device_build(&dev, source, KERNEL_FILE, &err))
        die("%s", err.message);
    free(source);
    char device_folder[256], folder[1024];
    bench_folder_name(dev.name, device_folder, sizeof device_folder);
    snprintf(folder, sizeof folder, "%s/%s", o.out, device_folder);
    printf("bench_bvh: %s (%s, %s), %d-wide BVH%s, %d spp, rays in %s, ", dev.name,
           dev.platform_name, dev.driver_version, dev.bvh_width,
           dev.bvh_quantized ? " (quantised nodes)" : "", o.spp,
           o.rows ? "scanline order" : "4x4-pixel tiles");
    if (o.count_steps)
        printf("work counts\n");
    else
        printf("best of %d\n", o.reps);

    const uint32_t sizes[] = {1000, 10000, 100000, 1000000, 2000000};
    const struct {
        const char *name, *path;
    } assets[] = {{"dragon", "stanford-dragon/dragon.obj"}, {"skull", "skull/skull.obj"}};
    Mesh meshes[7];
    char names[7][32];
    int count = 0;
    for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
        if (sizes[i] <= o.max_triangles) {
            meshes[count] = mesh_torus(sizes[i]);
            snprintf(names[count++], sizeof names[0], "torus");
        }
    for (size_t i = 0; i < sizeof assets / sizeof assets[0]; i++)
        if (load_asset(&o, assets[i].path, &meshes[count]))
            snprintf(names[count++], sizeof names[0], "%s", assets[i].name);

    if (o.count_steps) {
        printf("\nsteps per ray      triangles rays          count     nodes  warp max   SIMD     tests  warp max   SIMD\n");
        FILE *steps_csv = open_csv(folder, "bvh_steps.csv",
                                   "mesh,triangles,rays,count,nodes,nodes_warp_max,nodes_simd,tests,"
                                   "tests_warp_max,tests_simd");
        for (int i = 0; i < count; i++)
            if (meshes[i].num_triangles <= 1100000)
                bench_trace(steps_csv, &dev, names[i], &meshes[i], &o);
        fclose(steps_csv);
        printf("\nwrote %s/bvh_steps.csv\n", folder);
        for (int i = 0; i < count; i++)
            mesh_free(&meshes[i]);
        device_close(&dev);
        return 0;
    }
    printf("\nbuild (one core)  triangles    wall ms  Mtris/s  Mtris/s    nodes       SAH   SAH full  binned vs\n"
           "                                        (wall)    (cpu)                         sweep  full sweep\n");
    FILE *build_csv = open_csv(folder, "bvh_build.csv",
                               "mesh,triangles,build_ms,build_cpu_ms,mtris_per_s,mtris_per_s_cpu,nodes,"
                               "sah,sah_full_sweep");
    for (int i = 0; i < count; i++)
        bench_build(build_csv, names[i], &meshes[i]);
    fclose(build_csv);

    printf("\ntrace             triangles rays          count   hits closest ms   Mrays/s     any ms   "
           "Mrays/s  ns/ray\n");
    FILE *trace_csv = open_csv(folder, "bvh_trace.csv",
                               "mesh,triangles,rays,query,count,ms,mrays_per_s,hit_fraction");
    for (int i = 0; i < count; i++)
        if (meshes[i].num_triangles <= 1100000)
            bench_trace(trace_csv, &dev, names[i], &meshes[i], &o);
    fclose(trace_csv);
    printf("\nwrote %s/bvh_build.csv and %s/bvh_trace.csv\n", folder, folder);
    for (int i = 0; i < count; i++)
        mesh_free(&meshes[i]);
    device_close(&dev);
    return 0;
}
