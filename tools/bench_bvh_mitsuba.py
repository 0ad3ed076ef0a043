#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Times Mitsuba 3's ray queries on the rays tools/bench_bvh traced: the traversal on its own,
against Embree (Mitsuba's CPU variants trace with it) or OptiX (its CUDA variants).

    build/tools/bench_bvh --device cpu --max-triangles 1000 --write-rays /tmp/rays
    .venv-mitsuba/bin/python tools/bench_bvh_mitsuba.py /tmp/rays [--variant llvm_ad_rgb]
        [--reps 5] [--csv FILE]

For every NAME.tris in the folder (9 float32 per triangle) it builds the mesh and traces
NAME-primary.rays and NAME-diffuse.rays (origin, tmin, direction, tmax: 8 float32 per ray) as
closest-hit queries (ray_intersect_preliminary: distance and triangle, no surface interaction,
as pt's closest queries) and any-hit queries (ray_test), in the file's order, in one launch each;
best of --reps after a warm-up that compiles the kernels. Rays keep bench_bvh's order: each
pixel's samples together in 4x4-pixel tiles (or as bench_bvh --order says), so consecutive rays
(one SIMD packet in Mitsuba's LLVM backend, which hands Embree packets of its vector width) start
at the same point; with --order random they do not. Prints
the hit fraction too: it must equal bench_bvh's for the same rays. Mitsuba has no tmin: the rays'
tmin are 0 (bench_bvh offsets the diffuse origins instead).
"""
import argparse
import glob
import os
import sys
import time

LLVM_CANDIDATES = ["/usr/lib/x86_64-linux-gnu/libLLVM-19.so", "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1",
                   "/usr/lib/llvm-19/lib/libLLVM.so"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--csv")
    args = ap.parse_args()
    if "DRJIT_LIBLLVM_PATH" not in os.environ:
        for path in LLVM_CANDIDATES:
            if os.path.exists(path):
                os.environ["DRJIT_LIBLLVM_PATH"] = path
                break
    import drjit as dr
    import mitsuba as mi
    import numpy as np
    mi.set_variant(args.variant)

    def timed(query):
        best = float("inf")
        for rep in range(args.reps + 1):  # the first compiles the kernel
            dr.sync_thread()
            start = time.perf_counter()
            result = query()
            dr.eval(result)
            dr.sync_thread()
            if rep:
                best = min(best, time.perf_counter() - start)
        return best, result

    tris_files = sorted(glob.glob(os.path.join(args.folder, "*.tris")))
    if not tris_files:
        print(f"bench_bvh_mitsuba: no *.tris in {args.folder} (bench_bvh --write-rays writes them)",
              file=sys.stderr)
        return 1
    rows = []
    print(f"mitsuba {mi.__version__} {args.variant}, best of {args.reps}")
    print(f"{'mesh':10s} {'triangles':>9s} {'rays':8s} {'count':>9s} {'hits':>6s} {'closest ms':>10s} "
          f"{'Mrays/s':>9s} {'any ms':>10s} {'Mrays/s':>9s}")
    for tris_path in tris_files:
        name = os.path.basename(tris_path)[:-len(".tris")]
        corners = np.fromfile(tris_path, dtype="<f4").reshape(-1, 3)
        num_tris = corners.shape[0] // 3
        mesh = mi.Mesh(name, corners.shape[0], num_tris)
        params = mi.traverse(mesh)
        params["vertex_positions"] = mi.Float(corners.ravel())
        params["faces"] = mi.UInt32(np.arange(corners.shape[0], dtype=np.uint32))
        params.update()
        scene = mi.load_dict({"type": "scene", "mesh": mesh})
        for kind in ("primary", "diffuse"):
            ray_path = os.path.join(args.folder, f"{name}-{kind}.rays")
            if not os.path.exists(ray_path):
                continue
            r = np.fromfile(ray_path, dtype="<f4").reshape(-1, 8)
            n = r.shape[0]
            col = [mi.Float(np.ascontiguousarray(r[:, k])) for k in range(8)]
            ray = mi.Ray3f(mi.Point3f(col[0], col[1], col[2]), mi.Vector3f(col[4], col[5], col[6]))
            ray.maxt = col[7]
            dr.eval(ray)
            closest_s, pi = timed(lambda: scene.ray_intersect_preliminary(ray).t)
            any_s, _ = timed(lambda: scene.ray_test(ray))
            hits = float(np.count_nonzero(np.isfinite(np.array(pi)))) / n
            print(f"{name:10s} {num_tris:9d} {kind:8s} {n:9d} {hits:6.3f} {closest_s * 1e3:10.2f} "
                  f"{n / closest_s * 1e-6:9.2f} {any_s * 1e3:10.2f} {n / any_s * 1e-6:9.2f}", flush=True)
            rows.append((name, num_tris, kind, "closest", n, closest_s * 1e3, n / closest_s * 1e-6, hits))
            rows.append((name, num_tris, kind, "any", n, any_s * 1e3, n / any_s * 1e-6, hits))
    if args.csv:
        with open(args.csv, "w") as f:
            f.write("renderer,variant,mesh,triangles,rays,query,count,ms,mrays_per_s,hit_fraction\n")
            for row in rows:
                f.write(f"mitsuba-{mi.__version__},{args.variant},{row[0]},{row[1]},{row[2]},{row[3]},"
                        f"{row[4]},{row[5]:.4f},{row[6]:.4f},{row[7]:.4f}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
