#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes scenes/bench/: the benchmark scenes that put a public mesh (read from ../shared/assets, not
copied: Stanford's terms) inside a lit box sized to the mesh. The box is ours (MIT): floor, back,
ceiling, red left and green right walls facing inward, an emissive ceiling quad facing down, open
front. Deterministic; run again after changing it."""
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "scenes", "bench")

MESHES = {
    # name: (path relative to scenes/bench, bounds min, bounds max)
    "dragon": ("../../../shared/assets/stanford-dragon/dragon.obj",
               (-7.0467, 0.0, -3.1513), (7.0467, 9.9399, 3.1513)),
    "skull": ("../../../shared/assets/skull/skull.obj",
              (-4.395434, 0.0, -5.621974), (4.293053, 13.902681, 6.489939)),
}

MTL = """# Lit box for the benchmark scenes (tools/make_bench_scenes.py). MIT.
newmtl white
Kd 0.73 0.73 0.73
newmtl red
Kd 0.63 0.065 0.05
newmtl green
Kd 0.14 0.45 0.091
newmtl light
Kd 0.78 0.78 0.78
Ke 12 10 7
"""


def quad(out, verts, a, b, c, d):
    """Appends a quad whose counter-clockwise side (a, b, c, d) faces where its normal points."""
    base = len(verts) + 1
    verts.extend([a, b, c, d])
    out.append(f"f {base} {base + 1} {base + 2} {base + 3}")


def box_obj(lo, hi):
    pad = [0.25 * (hi[i] - lo[i]) + 0.5 for i in range(3)]
    x0, x1 = lo[0] - pad[0], hi[0] + pad[0]
    y0, y1 = lo[1], hi[1] + pad[1]
    z0, z1 = lo[2] - pad[2], hi[2] + pad[2]
    verts, faces = [], []
    faces.append("usemtl white")
    quad(faces, verts, (x0, y0, z1), (x1, y0, z1), (x1, y0, z0), (x0, y0, z0))  # floor, normal +y
    quad(faces, verts, (x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1))  # ceiling, -y
    quad(faces, verts, (x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0))  # back wall, +z
    faces.append("usemtl red")
    quad(faces, verts, (x0, y0, z1), (x0, y0, z0), (x0, y1, z0), (x0, y1, z1))  # left wall, +x
    faces.append("usemtl green")
    quad(faces, verts, (x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0))  # right wall, -x
    faces.append("usemtl light")
    lx, lz = 0.2 * (x1 - x0), 0.2 * (z1 - z0)
    cx, cz, ly = 0.5 * (x0 + x1), 0.5 * (z0 + z1), y1 - 1e-3 * (y1 - y0)
    quad(faces, verts, (cx - lx, ly, cz - lz), (cx + lx, ly, cz - lz), (cx + lx, ly, cz + lz),
         (cx - lx, ly, cz + lz))  # light, facing down
    lines = ["# Lit box (tools/make_bench_scenes.py). MIT.", "mtllib lit-box.mtl"]
    lines += [f"v {x:.6g} {y:.6g} {z:.6g}" for x, y, z in verts] + faces
    camera = {"eye": [0.5 * (x0 + x1), 0.5 * (y0 + y1), z1 + 1.6 * (y1 - y0)],
              "target": [0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1)],
              "up": [0, 1, 0], "fov_y": 40.0}
    return "\n".join(lines) + "\n", camera


def main():
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, "lit-box.mtl"), "w") as f:
        f.write(MTL)
    for name, (path, lo, hi) in MESHES.items():
        obj, camera = box_obj(lo, hi)
        with open(os.path.join(OUT, f"{name}-box.obj"), "w") as f:
            f.write(obj)
        scene = {"camera": camera, "film": {"width": 1024, "height": 1024},
                 "render": {"spp": 16, "max_depth": 8},
                 "objects": [{"obj": path}, {"obj": f"{name}-box.obj"}]}
        with open(os.path.join(OUT, f"{name}.json"), "w") as f:
            json.dump(scene, f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main()
