#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the memory-scaling scene of issue 18: N instances (default 10,000) of the 100k-triangle
Stanford dragon on a square grid, each turned about +y by a random angle, on a ground quad under a
sky and a directional sun, seen whole from above one edge. 10^4 x 10^5 = 10^9 triangles: only
instancing (one copy of the mesh, one BVH, a TLAS over the instances) makes it loadable.

    tools/make_dragons.py [--count N] [--seed S] [--dragon OBJ] [OUT]     default OUT bench/dragons

OUT gets scene.json, ground.obj and ground.mtl. The dragon is referenced, not copied (Stanford's
terms; 3.3 MB): by its path relative to OUT, from ../shared/assets/stanford-dragon/dragon.obj
beside the repository unless --dragon says otherwise. Deterministic. Not committed (.gitignore).
"""
import argparse
import math
import os
import random
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_forest import write_scene  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
DRAGON = os.path.join(HERE, "..", "..", "shared", "assets", "stanford-dragon", "dragon.obj")
# The dragon's bounds (as in tools/make_bench_scenes.py): x +-7.05, y 0 .. 9.94, z +-3.15; turned
# about +y it stays within a radius of 7.72 of its axis.
DRAGON_RADIUS = 7.72
SPACING = 18.0  # grid pitch: neighbours never touch, whatever their turns

MTL = """# Ground of the dragons scene (tools/make_dragons.py). MIT.
newmtl ground
Kd 0.5 0.5 0.5
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", default=os.path.join(os.path.relpath(HERE), "..", "bench", "dragons"))
    ap.add_argument("--count", type=int, default=10000, help="instances (default 10000)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--dragon", default=DRAGON, help="the 100k-triangle dragon OBJ")
    args = ap.parse_args()
    if args.count < 1:
        ap.error("--count must be at least 1")
    out = os.path.normpath(args.out)
    if not os.path.isfile(args.dragon):
        print(f"make_dragons: {args.dragon}: no such file (give --dragon)", file=sys.stderr)
        return 1
    os.makedirs(out, exist_ok=True)
    dragon = os.path.relpath(os.path.abspath(args.dragon), os.path.abspath(out))
    rng = random.Random(args.seed)
    n = math.ceil(math.sqrt(args.count))  # n x n grid, filled row by row
    half = SPACING * (n - 1) / 2
    objects = [{"obj": "ground.obj"}]
    for i in range(args.count):
        x, z = -half + SPACING * (i % n), -half + SPACING * (i // n)
        objects.append({"obj": dragon, "material": "dragon", "transform": [
            {"rotate": {"axis": [0, 1, 0], "angle": round(rng.uniform(0, 360), 3)}},
            {"translate": [round(x, 4), 0, round(z, 4)]}]})
    extent = half + DRAGON_RADIUS  # the grid's half side, dragons included
    scene = {
        # above the near edge, looking down at 40 degrees: the far corners fit a 50-degree fov
        "camera": {"eye": [0, round(1.15 * extent + 10, 4), round(2.1 * extent + 10, 4)],
                   "target": [0, 0, round(-0.1 * extent, 4)], "up": [0, 1, 0], "fov_y": 50.0},
        "film": {"width": 1024, "height": 768},
        "render": {"spp": 16, "max_depth": 8},
        "lights": [{"type": "directional", "direction": [-0.4, -0.8, -0.45],
                    "irradiance": [3.0, 2.8, 2.4]}],
        "background": [0.45, 0.6, 0.85],
        # the OBJ names a dragon.mtl that does not exist: a JSON material, so that every renderer
        # sees the same one (a missing MTL gives pt grey 0.8, tinyobjloader's rules black)
        "materials": {"dragon": {"type": "diffuse", "albedo": [0.65, 0.5, 0.3]}},
        "objects": objects,
    }
    g = round(extent + SPACING, 4)
    with open(os.path.join(out, "ground.mtl"), "w") as f:
        f.write(MTL)
    with open(os.path.join(out, "ground.obj"), "w") as f:
        f.write("# Dragons ground (tools/make_dragons.py). MIT.\nmtllib ground.mtl\nusemtl ground\n"
                f"v {-g} 0 {-g}\nv {-g} 0 {g}\nv {g} 0 {g}\nv {g} 0 {-g}\nf 1 2 3\nf 1 3 4\n")
    write_scene(os.path.join(out, "scene.json"), scene)
    print(f"{out}: {args.count} dragons ({dragon}) on a {n} x {n} grid, pitch {SPACING}: "
          f"{args.count * 100000 + 2} triangles, 100002 distinct")
    return 0


if __name__ == "__main__":
    sys.exit(main())
