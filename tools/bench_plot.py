#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plots a wavefront.csv written by tools/bench.sh: Mpaths/s per scene with and without compaction,
and Mpaths/s against resolution. Without matplotlib it says so and exits 0 (the CSV has it all).

    python3 tools/bench_plot.py bench/results/<device>"""
import csv
import os
import sys


def main():
    folder = sys.argv[1]
    path = os.path.join(folder, "wavefront.csv")
    rows = list(csv.DictReader(open(path, newline="")))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("bench_plot: matplotlib not installed; see", path)
        return
    full = [r for r in rows if r["width"] == "1024" and r["height"] == "1024"]
    scenes = sorted({r["scene"] for r in full}, key=[r["scene"] for r in full].index)
    fig, ax = plt.subplots(figsize=(7, 4))
    for i, mode in enumerate(["compaction", "no-compaction"]):
        values = [next((float(r["mpaths_per_s"]) for r in full if r["scene"] == s and r["mode"] == mode), 0)
                  for s in scenes]
        ax.bar([j + 0.4 * i for j in range(len(scenes))], values, 0.4, label=mode)
    ax.set_xticks([j + 0.2 for j in range(len(scenes))])
    ax.set_xticklabels([os.path.basename(s) for s in scenes], rotation=20, fontsize=8)
    ax.set_ylabel("Mpaths/s (1024², depth 8)")
    ax.set_title(rows[0]["device"])
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "wavefront_scenes.png"), dpi=120)
    box = [r for r in rows if r["scene"].endswith("cornell-box") or r["scene"].endswith("scene.json")]
    box = [r for r in box if "cornell-box" in r["scene"] and r["mode"] == "compaction"]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx([int(r["width"]) * int(r["height"]) for r in box], [float(r["mpaths_per_s"]) for r in box], "o-")
    ax.set_xlabel("pixels")
    ax.set_ylabel("Mpaths/s (Cornell box, depth 8)")
    ax.set_title(rows[0]["device"])
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "wavefront_resolution.png"), dpi=120)
    print("bench_plot: wrote", folder + "/wavefront_scenes.png", "and wavefront_resolution.png")


if __name__ == "__main__":
    main()
