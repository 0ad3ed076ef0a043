#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plots the CSVs that tools/bench.sh writes into bench/results/<device>/:
  wavefront_scenes.png      Mpaths/s per scene and mode (1024², depth 8) — the ablations
  wavefront_rays.png        extension and shadow Mrays/s per scene (default mode)
  wavefront_stages.png      per-stage ms per scene (profiled run)
  wavefront_live.png        live paths per wavefront step (Cornell box and dragon)
  wavefront_resolution.png  Mpaths/s against pixels (Cornell box)
  wavefront_triangles.png   Mpaths/s against triangle count (procedural tori in a lit box)
Without matplotlib it says so and exits 0 (the CSVs have it all).

    python3 tools/bench_plot.py bench/results/<device>"""
import csv
import os
import sys


def read(folder, name):
    path = os.path.join(folder, name)
    return list(csv.DictReader(open(path, newline=""))) if os.path.exists(path) else []


def short(scene):
    base = os.path.basename(scene)
    if base in ("scene.json", ""):
        return os.path.basename(os.path.dirname(scene))
    return base.replace(".json", "")


def main():
    folder = sys.argv[1]
    rows = read(folder, "wavefront.csv")
    stages = read(folder, "wavefront_stages.csv")
    live = read(folder, "wavefront_live.csv")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("bench_plot: matplotlib not installed; see the CSVs in", folder)
        return
    device = rows[0]["device"]
    full = [r for r in rows if r["width"] == "1024" and r["height"] == "1024"]
    scenes = list(dict.fromkeys(r["scene"] for r in full))
    modes = list(dict.fromkeys(r["mode"] for r in full))

    def save(fig, ax, name, title=None):
        ax.set_title(title or device, fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(folder, name), dpi=110)
        plt.close(fig)

    fig, ax = plt.subplots(figsize=(9, 4))
    width = 0.8 / len(modes)
    for i, mode in enumerate(modes):
        values = [next((float(r["mpaths_per_s"]) for r in full if r["scene"] == s and r["mode"] == mode), 0)
                  for s in scenes]
        ax.bar([j + width * i for j in range(len(scenes))], values, width, label=mode)
    ax.set_xticks([j + 0.4 - width / 2 for j in range(len(scenes))])
    ax.set_xticklabels([short(s) for s in scenes], rotation=20, fontsize=8)
    ax.set_ylabel("Mpaths/s (1024², depth 8)")
    ax.legend(fontsize=8)
    save(fig, ax, "wavefront_scenes.png")

    default = [next(r for r in full if r["scene"] == s and r["mode"] == modes[0]) for s in scenes]
    fig, ax = plt.subplots(figsize=(9, 4))
    ext = [float(r["mext_per_s"]) for r in default]
    shadow = [float(r["mshadow_per_s"]) for r in default]
    ax.bar(range(len(scenes)), ext, label="extension")
    ax.bar(range(len(scenes)), shadow, bottom=ext, label="shadow")
    ax.set_xticks(range(len(scenes)))
    ax.set_xticklabels([short(s) for s in scenes], rotation=20, fontsize=8)
    ax.set_ylabel("Mrays/s (%s)" % modes[0])
    ax.legend(fontsize=8)
    save(fig, ax, "wavefront_rays.png")

    if stages:
        st = [r for r in stages if r["width"] == "1024" and r["height"] == "1024"]
        names = list(dict.fromkeys(r["stage"] for r in st))
        fig, ax = plt.subplots(figsize=(9, 4))
        bottom = [0.0] * len(scenes)
        for name in names:
            ms = [next((float(r["ms"]) for r in st if r["scene"] == s and r["stage"] == name), 0) for s in scenes]
            ax.bar(range(len(scenes)), ms, bottom=bottom, label=name)
            bottom = [b + m for b, m in zip(bottom, ms)]
        ax.set_xticks(range(len(scenes)))
        ax.set_xticklabels([short(s) for s in scenes], rotation=20, fontsize=8)
        ax.set_ylabel("ms per stage (profiled run)")
        ax.legend(fontsize=7)
        save(fig, ax, "wavefront_stages.png")

    if live:
        fig, ax = plt.subplots(figsize=(6, 4))
        for s in scenes:
            if "cornell-box/scene.json" in s or "dragon" in s:
                pts = [r for r in live if r["scene"] == s and r["width"] == "1024"]
                ax.semilogy([int(r["step"]) for r in pts], [int(r["live_paths"]) for r in pts], "o-",
                            label=short(s))
        ax.set_xlabel("wavefront step")
        ax.set_ylabel("live paths (summed over windows)")
        ax.legend(fontsize=8)
        save(fig, ax, "wavefront_live.png")

    box = [r for r in rows if r["scene"].endswith("cornell-box/scene.json") and r["mode"] == modes[0]]
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.semilogx([int(r["width"]) * int(r["height"]) for r in box], [float(r["mpaths_per_s"]) for r in box], "o-")
    ax.set_xlabel("pixels")
    ax.set_ylabel("Mpaths/s (Cornell box, depth 8)")
    save(fig, ax, "wavefront_resolution.png")

    tori = [r for r in full if "torus-" in r["scene"] and r["mode"] == modes[0]]
    if tori:
        fig, ax = plt.subplots(figsize=(6, 4))
        n = [int(os.path.basename(r["scene"]).split("-")[1].split(".")[0]) for r in tori]
        ax.semilogx(n, [float(r["mpaths_per_s"]) for r in tori], "o-", label="Mpaths/s")
        ax.semilogx(n, [float(r["mrays_per_s"]) for r in tori], "s-", label="Mrays/s")
        ax.set_xlabel("torus triangles (in a lit box)")
        ax.legend(fontsize=8)
        save(fig, ax, "wavefront_triangles.png")
    print("bench_plot: wrote the wavefront_*.png plots in", folder)


if __name__ == "__main__":
    main()
