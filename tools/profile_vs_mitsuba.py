#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Where the CPU time of a render goes, in pt on PoCL and in Mitsuba 3's llvm_ad_rgb, measured
with perf on the same scene: ray traversal (pt's walks, TRAVERSAL_SYMBOLS; Mitsuba's
libembree3) against everything else (pt's kernels otherwise; Mitsuba's JIT-compiled kernels and
its runtime), as CPU nanoseconds per path. Both renderers use every core; Mitsuba runs with
pt's Russian roulette (rr_depth 5: from the fifth vertex) so that both trace the same number of
rays per path in expectation.

    python3 tools/profile_vs_mitsuba.py SCENE [--width 512 --height 512 --spp 16 --max-depth 8]
        [--pt build/pt] [--python .venv-mitsuba/bin/python] [--csv FILE]

The traversal share times the render's CPU seconds (wall seconds x cores, the cores being busy
throughout) gives the traversal's CPU time. Mitsuba's perf samples also hold its warm-up render,
scene loading and Python; the split uses the samples in Embree and in the JIT kernels (plus
Dr.Jit's thread pool), which are the renders. Needs perf (linux-perf) that may sample user code.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

# The walks as PoCL leaves them out of line (the rest is inlined into the kernels' bodies): one
# ray's, two levels', and the packets' (with their setup and triangle test).
TRAVERSAL_SYMBOLS = ("trace_bvh", "trace_scene_bvh", "trace_packet", "ray_packet", "packet_triangle",
                     "walk_wide")


def perf_shares(data, sort):
    """{name: percent} from perf report --sort dso or sym, self time."""
    out = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", sort, "--stdio",
                          "-g", "none"], capture_output=True, text=True, check=True).stdout
    shares = {}
    for line in out.splitlines():
        m = re.match(r"\s*([0-9.]+)%\s+(?:\[\.\]\s+|\[k\]\s+)?(.+?)\s*$", line)
        if m:
            shares[m.group(2)] = shares.get(m.group(2), 0.0) + float(m.group(1))
    return shares


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--width", type=int, default=512)
    ap.add_argument("--height", type=int, default=512)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--max-depth", type=int, default=8)
    ap.add_argument("--pt", default="build/pt")
    ap.add_argument("--python", default=".venv-mitsuba/bin/python")
    ap.add_argument("--csv")
    args = ap.parse_args()
    cores = os.cpu_count() or 1
    paths = args.width * args.height * args.spp
    film = ["--width", str(args.width), "--height", str(args.height), "--spp", str(args.spp),
            "--max-depth", str(args.max_depth)]
    with tempfile.TemporaryDirectory(prefix="profile_vs_mitsuba-") as tmp:
        pt_data, mi_data = os.path.join(tmp, "pt.data"), os.path.join(tmp, "mi.data")
        run = subprocess.run(["perf", "record", "-q", "-F", "2000", "-o", pt_data, "--", args.pt, "render",
                              args.scene, *film, "-o", os.path.join(tmp, "pt.exr")],
                             capture_output=True, text=True)
        m = re.search(r"in ([0-9.]+) s: ([0-9.]+) Mpaths/s", run.stdout + run.stderr)
        if run.returncode != 0 or not m:
            print(f"profile_vs_mitsuba: pt render failed:\n{run.stdout}{run.stderr}", file=sys.stderr)
            return 1
        pt_seconds = float(m.group(1))
        sym = perf_shares(pt_data, "sym")
        pt_total = sum(v for k, v in sym.items())
        pt_trace = sum(v for k, v in sym.items() if k in TRAVERSAL_SYMBOLS) / pt_total

        bench = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bench_mitsuba.py")
        run = subprocess.run(["perf", "record", "-q", "-F", "2000", "-o", mi_data, "--", args.python, bench,
                              args.scene, *film, "--reps", "3", "--rr-depth", "5"],
                             capture_output=True, text=True)
        times = [float(t) for t in re.findall(r": ([0-9.]+) ms, [0-9.]+ Mpaths/s", run.stdout)]
        if run.returncode != 0 or not times:
            print(f"profile_vs_mitsuba: Mitsuba failed:\n{run.stdout}{run.stderr}", file=sys.stderr)
            return 1
        mi_seconds = sorted(times)[len(times) // 2] * 1e-3
        dso = perf_shares(mi_data, "dso")
        embree = sum(v for k, v in dso.items() if "embree" in k)
        jit = sum(v for k, v in dso.items() if k.startswith("[JIT]") or "nanothread" in k)
        mi_trace = embree / (embree + jit)

    rows = []
    print(f"{args.scene}: {args.width}x{args.height}, {args.spp} spp, depth {args.max_depth}, "
          f"{cores} cores; CPU ns per path")
    print(f"{'renderer':22s} {'Mpaths/s':>9s} {'traversal':>10s} {'the rest':>9s} {'all':>7s} "
          f"{'traversal share':>16s}")
    for name, seconds, share in (("pt (PoCL)", pt_seconds, pt_trace),
                                 ("Mitsuba (rr_depth 5)", mi_seconds, mi_trace)):
        per_path = seconds * cores / paths * 1e9
        rows.append((name, paths / seconds * 1e-6, per_path * share, per_path * (1 - share), per_path, share))
        print(f"{name:22s} {rows[-1][1]:9.2f} {rows[-1][2]:10.0f} {rows[-1][3]:9.0f} {per_path:7.0f} "
              f"{share * 100:15.1f}%")
    goal = rows[1][4] / 1.5
    print(f"1.5x Mitsuba needs {goal:.0f} ns per path in all; Mitsuba's traversal alone takes "
          f"{rows[1][2]:.0f}, pt's {rows[0][2]:.0f}")
    if args.csv:
        new = not os.path.exists(args.csv) or os.path.getsize(args.csv) == 0
        with open(args.csv, "a") as f:
            if new:
                f.write("scene,renderer,cores,mpaths_per_s,traversal_ns_per_path,rest_ns_per_path,"
                        "all_ns_per_path,traversal_share\n")
            for r in rows:
                f.write(f"{args.scene},{r[0]},{cores},{r[1]:.3f},{r[2]:.1f},{r[3]:.1f},{r[4]:.1f},{r[5]:.4f}\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
