#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plots tools/bench_bvh's CSVs: build throughput against mesh size, and time per ray against mesh
size (primary and diffuse rays, closest and any hit) for every device under bench/results.

    python3 tools/bench_bvh.py [RESULTS_DIR]     (default bench/results)

Writes bvh_build.png and bvh_trace.png beside each device's CSVs. Without matplotlib it says so
and exits 0: the CSVs and bench_bvh's table hold the same numbers."""
import csv
import os
import sys


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def plot_device(plt, folder):
    device = os.path.basename(folder)
    build_path = os.path.join(folder, "bvh_build.csv")
    if os.path.exists(build_path):
        rows = [r for r in read_rows(build_path) if r["mesh"] == "torus"]
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.semilogx([int(r["triangles"]) for r in rows], [float(r["mtris_per_s_cpu"]) for r in rows],
                    "o-", label="binned SAH build (thread CPU time)")
        ax.axhline(3.0, color="gray", linestyle=":", label="goal: 3 Mtris/s")
        ax.set_xlabel("triangles (bumpy torus)")
        ax.set_ylabel("Mtris/s, one core")
        ax.set_title(f"BVH build: {device}")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(folder, "bvh_build.png"), dpi=120)
        plt.close(fig)
    trace_path = os.path.join(folder, "bvh_trace.csv")
    if os.path.exists(trace_path):
        rows = [r for r in read_rows(trace_path) if r["mesh"] == "torus"]
        fig, ax = plt.subplots(figsize=(6, 4))
        for kind in ("primary", "diffuse"):
            for query in ("closest", "any"):
                sel = [r for r in rows if r["rays"] == kind and r["query"] == query]
                if sel:
                    ax.loglog([int(r["triangles"]) for r in sel],
                              [float(r["ms"]) * 1e6 / int(r["count"]) for r in sel], "o-",
                              label=f"{kind}, {query} hit")
        ax.set_xlabel("triangles (bumpy torus)")
        ax.set_ylabel("ns per ray (kernel time)")
        ax.set_title(f"BVH traversal: {device}")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(folder, "bvh_trace.png"), dpi=120)
        plt.close(fig)
    print(f"bench_bvh.py: plots written to {folder}")


def main():
    results = sys.argv[1] if len(sys.argv) > 1 else "bench/results"
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("bench_bvh.py: matplotlib is not installed: no plots (the CSVs are in "
              f"{results}/<device>/bvh_*.csv)")
        return 0
    if not os.path.isdir(results):
        print(f"bench_bvh.py: {results} not found: run build/tools/bench_bvh first")
        return 1
    for name in sorted(os.listdir(results)):
        folder = os.path.join(results, name)
        if os.path.isdir(folder) and any(f.startswith("bvh_") for f in os.listdir(folder)):
            plot_device(plt, folder)
    return 0


if __name__ == "__main__":
    sys.exit(main())
