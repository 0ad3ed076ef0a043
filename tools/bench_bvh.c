// SPDX-License-Identifier: MIT
/* bench_bvh: BVH build and traversal throughput.
 *
 *   build/tools/bench_bvh [--device gpu|cpu|P:D] [--spp N] [--reps R] [--assets DIR]
 *                         [--max-triangles N] [--out DIR] [--order tiles|rows|random] [--count-steps]
 *                         [--write-rays DIR]
 *
 * Build: bumpy tori of 10^3 .. 2*10^6 triangles and the dragon and skull assets; time on one core
 * (best of several runs, wall clock and thread CPU time), Mtris/s, node count, SAH cost, and for
 * meshes up to 200k triangles the SAH cost of the full-sweep reference build.
 * Trace: primary rays (480x320 pixels x spp samples in 4x4-pixel tiles, as tinybvh's speed test
 * orders them, or scanlines with --order rows, or shuffled with --order random; camera 1.4
 * bounding radii from the centre, 50 degrees field of view) and one diffuse bounce from their hits
 * (cosine about the geometric normal, origin from offset_ray_origin), each as closest-hit and
 * any-hit queries, on the dragon,
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
 * BVH_PACKET=1 (8-wide layout): closest and any hits by trace_packet, eight consecutive rays per
 * work item walked together (cl/geometry/bvh_traverse_packet.cl, what the CPU megakernel uses).
 * All are checked bit for bit against the plain kernels' hits.
 * --write-rays DIR: also writes each traced mesh's triangles (NAME.tris: 9 floats per triangle)
 * and its primary and diffuse rays (NAME-primary.rays, NAME-diffuse.rays: origin, tmin,
 * direction, tmax as 8 floats per ray), little-endian float32, so that
 * tools/bench_bvh_mitsuba.py can time Mitsuba 3 (Embree on CPUs, OptiX on GPUs) on the same rays. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "bench_bvh_options.h"
#include "bench_bvh_trace.h"
#include "bench_common.h"
#include "accel/bvh.h"
#include "device/device.h"
#include "io/obj_loader.h"
#include "procedural_mesh.h"

#define KERNEL_FILE "tests/cl/bvh_test.cl"

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

static void bench_build(FILE *csv, const char *name, const TestMesh *mesh)
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

/* ---- Main ------------------------------------------------------------------------------------- */

static bool load_asset(const Options *o, const char *relative, TestMesh *mesh)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", o->assets, relative);
    Mesh obj;
    Error err = {0};
    warnings_set_quiet(true);
    if (!obj_load(path, &obj, &err)) {
        fprintf(stderr, "bench_bvh: skipping %s: %s\n", relative, err.message);
        return false;
    }
    *mesh = mesh_from_obj(&obj);
    mesh_free(&obj);
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
    if (!device_build(&dev, PROGRAM_FEATURES_ALL, source, KERNEL_FILE, &err))
        die("%s", err.message);
    free(source);
    char device_folder[256], folder[1024];
    bench_folder_name(dev.name, device_folder, sizeof device_folder);
    snprintf(folder, sizeof folder, "%s/%s", o.out, device_folder);
    printf("bench_bvh: %s (%s, %s), %d-wide BVH%s, %d spp, rays in %s, ", dev.name,
           dev.platform_name, dev.driver_version, dev.bvh_width,
           dev.bvh_quantized ? " (quantised nodes)" : "", o.spp,
           o.order == ORDER_ROWS     ? "scanline order"
           : o.order == ORDER_RANDOM ? "random order"
                                     : "4x4-pixel tiles");
    if (o.count_steps)
        printf("work counts\n");
    else
        printf("best of %d\n", o.reps);

    const uint32_t sizes[] = {1000, 10000, 100000, 1000000, 2000000};
    const struct {
        const char *name, *path;
    } assets[] = {{"dragon", "stanford-dragon/dragon.obj"}, {"skull", "skull/skull.obj"}};
    TestMesh meshes[7];
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
            test_mesh_free(&meshes[i]);
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
        test_mesh_free(&meshes[i]);
    device_close(&dev);
    return 0;
}
