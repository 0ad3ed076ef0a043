#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the forest benchmark scene (issue 18): a ground quad and N instances of four small
procedural meshes (pine, broadleaf tree, bush, rock; 900-2200 triangles each), each placed at a
random point on the ground with a random turn about +y and a uniform scale, under a sky and a
directional sun; the camera looks over the forest from one edge.

    tools/make_forest.py [--count N] [--seed S] [OUT]      default OUT bench/forest-<N/1000>k

OUT gets scene.json, forest.mtl and one OBJ per mesh. Every instance names its mesh's OBJ, so the
renderer loads each OBJ once (shared/DESIGN.md "Objects"): memory grows with the four meshes, not
with N. The ground's side grows as sqrt(N), so the density of trees stays the same. Deterministic:
the same arguments give the same bytes. Generated folders are not committed (.gitignore: bench/forest-*/).
"""
import argparse
import json
import math
import os
import random
import sys

MTL = """# Forest benchmark materials (tools/make_forest.py). MIT.
newmtl ground
Kd 0.30 0.24 0.15
newmtl bark
Kd 0.25 0.16 0.09
newmtl needles
Kd 0.06 0.20 0.07
newmtl leaves
Kd 0.16 0.36 0.08
newmtl rock
Kd 0.42 0.41 0.38
"""

SPACING = 2.0  # mean distance between neighbouring instances, scene units (a pine is ~4.5 tall)
KINDS = [  # mesh, share of the instances
    ("pine", 0.45), ("broadleaf", 0.25), ("bush", 0.20), ("rock", 0.10)]


class Mesh:
    """Triangles grouped by material; vertices are shared within the mesh."""

    def __init__(self):
        self.v = []
        self.groups = {}

    def vertex(self, p):
        self.v.append(tuple(p))
        return len(self.v)  # OBJ indices count from 1

    def tri(self, material, a, b, c):
        self.groups.setdefault(material, []).append((a, b, c))

    def triangles(self):
        return sum(len(t) for t in self.groups.values())

    def write(self, path, name):
        with open(path, "w") as f:
            f.write(f"# {name}: procedural forest mesh (tools/make_forest.py). MIT.\nmtllib forest.mtl\n")
            f.writelines("v %.5f %.5f %.5f\n" % p for p in self.v)
            for material, tris in self.groups.items():
                f.write(f"usemtl {material}\n")
                f.writelines("f %d %d %d\n" % t for t in tris)


def add_cone(mesh, material, y0, y1, r0, r1, segments, rings, base_cap):
    """A frustum (r1 = 0: a cone) around +y, faces outward (counter-clockwise seen from outside)."""
    rows = []
    for i in range(rings + 1):
        t = i / rings
        y, r = y0 + (y1 - y0) * t, r0 + (r1 - r0) * t
        if r == 0:
            rows.append([mesh.vertex((0, y, 0))] * segments)
            continue
        rows.append([mesh.vertex((r * math.cos(2 * math.pi * k / segments), y,
                                  -r * math.sin(2 * math.pi * k / segments))) for k in range(segments)])
    for i in range(rings):
        lo, hi = rows[i], rows[i + 1]
        for k in range(segments):
            k1 = (k + 1) % segments
            mesh.tri(material, lo[k], lo[k1], hi[k1])
            if hi[k] != hi[k1]:
                mesh.tri(material, lo[k], hi[k1], hi[k])
    if base_cap:  # facing down
        centre = mesh.vertex((0, y0, 0))
        for k in range(segments):
            mesh.tri(material, centre, rows[0][(k + 1) % segments], rows[0][k])


def icosphere(level):
    """Unit icosphere: (points, triangles), counter-clockwise seen from outside."""
    t = (1 + math.sqrt(5)) / 2
    pts = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
           (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    pts = [tuple(c / math.sqrt(1 + t * t) for c in p) for p in pts]
    tris = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
            (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
            (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        cache, out = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(pts[a][i] + pts[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(c * c for c in m))
                pts.append(tuple(c / n for c in m))
                cache[key] = len(pts) - 1
            return cache[key]
        for a, b, c in tris:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        tris = out
    return pts, tris


def add_blob(mesh, material, rng, level, centre, radius, bumpiness):
    """A lumpy sphere: an icosphere displaced along its radius by a few random waves."""
    waves = [([rng.gauss(0, 1) for _ in range(3)], rng.uniform(0, 2 * math.pi)) for _ in range(6)]
    pts, tris = icosphere(level)
    ids = []
    for p in pts:
        d = sum(math.sin(3.0 * sum(w[i] * p[i] for i in range(3)) + phase) for w, phase in waves)
        r = [radius[i] * (1 + bumpiness * d / len(waves)) for i in range(3)]
        ids.append(mesh.vertex([centre[i] + r[i] * p[i] for i in range(3)]))
    for a, b, c in tris:
        mesh.tri(material, ids[a], ids[b], ids[c])


def make_meshes(rng):
    pine = Mesh()
    add_cone(pine, "bark", 0.0, 1.2, 0.16, 0.12, 12, 2, False)
    for i, (y, r, h) in enumerate([(0.9, 1.3, 1.8), (1.9, 1.0, 1.6), (2.9, 0.7, 1.6)]):
        add_cone(pine, "needles", y, y + h, r, 0.0, 32, 6, True)
    broadleaf = Mesh()
    add_cone(broadleaf, "bark", 0.0, 2.0, 0.2, 0.14, 12, 3, False)
    add_blob(broadleaf, "leaves", rng, 3, (0, 2.9, 0), (1.4, 1.2, 1.4), 0.25)
    bush = Mesh()
    for centre, r in [((0, 0.45, 0), 0.6), ((0.45, 0.35, 0.2), 0.45), ((-0.35, 0.35, -0.25), 0.5)]:
        add_blob(bush, "leaves", rng, 2, centre, (r, r * 0.85, r), 0.3)
    rock = Mesh()
    add_blob(rock, "rock", rng, 3, (0, 0.15, 0), (0.7, 0.45, 0.55), 0.35)
    return {"pine": pine, "broadleaf": broadleaf, "bush": bush, "rock": rock}


def ground_obj(half):
    return ("# Forest ground (tools/make_forest.py). MIT.\nmtllib forest.mtl\nusemtl ground\n"
            f"v {-half} 0 {-half}\nv {-half} 0 {half}\nv {half} 0 {half}\nv {half} 0 {-half}\n"
            "f 1 2 3\nf 1 3 4\n")


def scene_json(count, rng):
    side = SPACING * math.sqrt(count)  # instances spread over side x side
    half = side / 2
    objects = [{"obj": "ground.obj"}]
    names = [k for k, _ in KINDS]
    weights = [w for _, w in KINDS]
    for _ in range(count):
        kind = rng.choices(names, weights)[0]
        x, z = rng.uniform(-half, half), rng.uniform(-half, half)
        objects.append({"obj": f"{kind}.obj", "transform": [
            {"scale": round(rng.uniform(0.7, 1.3), 4)},
            {"rotate": {"axis": [0, 1, 0], "angle": round(rng.uniform(0, 360), 3)}},
            {"translate": [round(x, 4), 0, round(z, 4)]}]})
    scene = {
        # from beyond the near edge, a little above the trees: the far rows and the sky show
        "camera": {"eye": [0, round(0.2 * side + 6, 4), round(0.62 * side + 4, 4)],
                   "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 45.0},
        "film": {"width": 1024, "height": 576},
        "render": {"spp": 16, "max_depth": 8},
        "lights": [{"type": "directional", "direction": [-0.45, -0.75, -0.48],
                    "irradiance": [3.0, 2.8, 2.4]}],
        "background": [0.45, 0.6, 0.85],
        "objects": objects,
    }
    return scene, half


def write_scene(path, scene):
    """One object per line: readable, and diffs of the generator show up as diffs of lines."""
    objects = scene.pop("objects")
    text = "{\n" + "".join(f'  "{k}": {json.dumps(v, separators=(", ", ": "))},\n' for k, v in scene.items())
    text += '  "objects": [\n'
    text += ",\n".join("    " + json.dumps(o, separators=(", ", ": ")) for o in objects)
    text += "\n  ]\n}\n"
    scene["objects"] = objects
    with open(path, "w") as f:
        f.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", help="output folder (default bench/forest-<N/1000>k)")
    ap.add_argument("--count", type=int, default=10000, help="instances (default 10000)")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    if args.count < 1:
        ap.error("--count must be at least 1")
    out = args.out or os.path.join(os.path.relpath(os.path.dirname(os.path.abspath(__file__))), "..", "bench",
                                   f"forest-{args.count // 1000}k" if args.count >= 1000
                                   else f"forest-{args.count}")
    out = os.path.normpath(out)
    os.makedirs(out, exist_ok=True)
    rng = random.Random(args.seed)
    meshes = make_meshes(rng)
    with open(os.path.join(out, "forest.mtl"), "w") as f:
        f.write(MTL)
    for name, mesh in meshes.items():
        mesh.write(os.path.join(out, f"{name}.obj"), name)
    scene, half = scene_json(args.count, rng)
    with open(os.path.join(out, "ground.obj"), "w") as f:
        f.write(ground_obj(round(half + 2 * SPACING, 4)))
    write_scene(os.path.join(out, "scene.json"), scene)
    tris = {name: m.triangles() for name, m in meshes.items()}
    used = {name: 0 for name in meshes}
    for o in scene["objects"][1:]:
        used[o["obj"][:-4]] += 1
    total = 2 + sum(tris[n] * used[n] for n in used)
    print(f"{out}: {args.count} instances of " +
          ", ".join(f"{n} ({tris[n]} triangles) x{used[n]}" for n in meshes) +
          f"; {total} triangles in all, {2 + sum(tris.values())} distinct")
    return 0


if __name__ == "__main__":
    sys.exit(main())
