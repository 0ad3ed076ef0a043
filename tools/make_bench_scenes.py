#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes scenes/bench/: the benchmark scenes that put a public mesh (read from ../shared/assets, not
copied: Stanford's terms) inside a lit box sized to the mesh. The box is ours (MIT): floor, back,
ceiling, red left and green right walls facing inward, an emissive ceiling quad facing down, open
front. Deterministic; run again after changing it. It also writes scenes/bench-materials/ (the
dragon in rough gold on a normal-mapped floor behind rough glass; the same under an HDR map).

With --tori DIR it writes procedural scenes instead (too large to commit; tools/bench.sh makes
them on the fly): DIR/torus-N.json, a bumpy torus of about N triangles (N = 10^3 .. 10^6) in the
same lit box, for the triangle-count scaling and the 1M-triangle scene of the suite. With
--normal-walls DIR: DIR/normal-walls.json, a room of tiled, normal-mapped walls (6000 triangles:
each wall a grid) under a ceiling light, issue 41's "normal-mapped walls" scene type."""
import json
import math
import os
import sys

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


def torus_obj(n_triangles):
    """A bumpy torus (major radius 1, minor 0.35, bumps of 0.03) of 2 nu nv ~ n_triangles, lying
    on y = 0, as OBJ text; returns the text and its bounds."""
    nu = max(4, round(math.sqrt(n_triangles)))
    nv = max(3, nu // 2)
    big, small = 1.0, 0.35
    lines = ["# Procedural bumpy torus (tools/make_bench_scenes.py). MIT.", "usemtl white"]
    for i in range(nu):
        u = 2 * math.pi * i / nu
        for j in range(nv):
            v = 2 * math.pi * j / nv
            r = small + 0.03 * math.sin(7 * u) * math.sin(5 * v)
            x = (big + r * math.cos(v)) * math.cos(u)
            z = (big + r * math.cos(v)) * math.sin(u)
            y = r * math.sin(v) + small + 0.03
            lines.append(f"v {x:.6f} {y:.6f} {z:.6f}")
    for i in range(nu):
        for j in range(nv):
            a = i * nv + j + 1
            b = ((i + 1) % nu) * nv + j + 1
            c = ((i + 1) % nu) * nv + (j + 1) % nv + 1
            d = i * nv + (j + 1) % nv + 1
            lines.append(f"f {a} {d} {c}")
            lines.append(f"f {a} {c} {b}")
    top = 2 * (small + 0.03) + 0.01
    return "\n".join(lines) + "\n", (-1.4, 0.0, -1.4), (1.4, top, 1.4), 2 * nu * nv


def write_tori(out):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "lit-box.mtl"), "w") as f:
        f.write(MTL)
    for n in (1000, 10000, 100000, 1000000):
        obj, lo, hi, count = torus_obj(n)
        with open(os.path.join(out, f"torus-{n}.obj"), "w") as f:
            f.write("mtllib lit-box.mtl\n" + obj)
        box, camera = box_obj(lo, hi)
        with open(os.path.join(out, f"torus-{n}-box.obj"), "w") as f:
            f.write(box)
        scene = {"camera": camera, "film": {"width": 1024, "height": 1024},
                 "render": {"spp": 16, "max_depth": 8},
                 "objects": [{"obj": f"torus-{n}.obj"}, {"obj": f"torus-{n}-box.obj"}]}
        with open(os.path.join(out, f"torus-{n}.json"), "w") as f:
            json.dump(scene, f, indent=2)
            f.write("\n")
        print(f"{out}/torus-{n}.json: {count} torus triangles")


def tile_normals(size=128, tiles=4, bevel=0.18):
    """A normal map of tiles with bevelled edges (rows top first, 8-bit linear): flat (0, 0, 1)
    inside each tile, tilted 40 degrees outward across the bevel, so it tiles seamlessly."""
    t = math.tan(math.radians(40))
    rows = []
    for y in range(size):
        row = []
        for x in range(size):
            fx, fy = (x + 0.5) * tiles / size % 1, (y + 0.5) * tiles / size % 1
            tx = -t if fx < bevel else (t if fx > 1 - bevel else 0.0)
            ty = t if fy < bevel else (-t if fy > 1 - bevel else 0.0)  # row 0 = top = +v
            n = [tx, ty, 1.0]
            length = math.sqrt(sum(c * c for c in n))
            row.append(tuple(round((c / length * 0.5 + 0.5) * 255) for c in n))
        rows.append(row)
    return rows


def write_materials_bench(out):
    """scenes/bench-materials/: the dragon (100k) in rough gold on a normal-mapped tiled floor,
    seen through a rough glass slab (materials.json, an area light and a dim sky), and the same
    dragon under the Venice sunset map (env.json, issue 17). The floor and slab are ours (MIT)."""
    sys.path.insert(0, HERE)
    from make_test_scenes import write_png
    os.makedirs(out, exist_ok=True)
    write_png(os.path.join(out, "tiles-normal.png"), 128, 128, tile_normals())
    with open(os.path.join(out, "stage.mtl"), "w") as f:
        f.write("# Stage of the material benchmark (tools/make_bench_scenes.py). MIT. The JSON\n"
                "# materials of the scenes replace these.\n"
                "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl slab\nKd 0.5 0.5 0.5\n"
                "newmtl light\nKd 0 0 0\nKe 30 27 22\n")
    verts, faces, uvs = [], [], []

    def face(points, uv=None):
        base = len(verts) + 1
        verts.extend(points)
        if uv:
            uvs.extend(uv)
            faces.append("f " + " ".join(f"{base + i}/{len(uvs) - len(uv) + i + 1}" for i in range(len(points))))
        else:
            faces.append("f " + " ".join(str(base + i) for i in range(len(points))))
    faces.append("usemtl floor")  # 40 x 40, the tiles repeat 10 times
    face([(-20, 0, 20), (20, 0, 20), (20, 0, -20), (-20, 0, -20)], [(0, 0), (10, 0), (10, 10), (0, 10)])
    faces.append("usemtl slab")  # 12 wide, 7 high, 0.6 thick, between the camera and the dragon
    x0, x1, y0, y1, z0, z1 = -6.0, 6.0, 0.0, 7.0, 5.0, 5.6
    c = [(x0 if i & 1 == 0 else x1, y0 if i & 2 == 0 else y1, z0 if i & 4 == 0 else z1) for i in range(8)]
    for q in [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]]:
        face([c[k] for k in q])
    stage = ["# Stage of the material benchmark (tools/make_bench_scenes.py). MIT.", "mtllib stage.mtl"]
    stage += [f"v {x:.6g} {y:.6g} {z:.6g}" for x, y, z in verts]
    stage += [f"vt {u:.6g} {v:.6g}" for u, v in uvs] + faces
    with open(os.path.join(out, "stage.obj"), "w") as f:
        f.write("\n".join(stage) + "\n")
    with open(os.path.join(out, "light.obj"), "w") as f:  # 6 x 6 at y = 22, facing down
        f.write("# Light of the material benchmark. MIT.\nmtllib stage.mtl\nusemtl light\n"
                "v -3 22 -3\nv 3 22 -3\nv 3 22 3\nv -3 22 3\nf 1 2 3 4\n")
    dragon = MESHES["dragon"][0]  # the same depth below the repository as scenes/bench
    gold = {"type": "conductor", "eta": [0.143, 0.374, 1.442], "k": [3.983, 2.385, 1.603], "roughness": 0.3}
    floor = {"type": "diffuse", "albedo": [0.55, 0.5, 0.45], "normal_map": "tiles"}
    camera = {"eye": [4.0, 9.0, 26.0], "target": [0.0, 4.0, 0.0], "up": [0, 1, 0], "fov_y": 38.0}
    common = {"camera": camera, "film": {"width": 1024, "height": 1024}, "render": {"spp": 16, "max_depth": 8},
              "textures": {"tiles": {"file": "tiles-normal.png", "encoding": "linear"}}}
    scenes = {
        "materials.json": dict(common, materials={
            "gold": gold, "floor": floor,
            "slab": {"type": "dielectric", "ior": 1.5, "roughness": 0.15, "absorption": [0.05, 0.03, 0.02]}},
            objects=[{"obj": dragon, "material": "gold"}, {"obj": "stage.obj"}, {"obj": "light.obj"}],
            background=[0.08, 0.09, 0.11]),
        "env.json": dict(common, materials={"gold": gold, "floor": floor},
                         objects=[{"obj": dragon, "material": "gold"}, {"obj": "floor.obj"}],
                         environment={"file": "../venice/venice_sunset_1k.hdr",
                                      "scale": 1.0, "rotation": 0}),
    }
    with open(os.path.join(out, "floor.obj"), "w") as f:  # the stage's floor alone, for env.json
        f.write("# Floor of the env-lit benchmark. MIT.\nmtllib stage.mtl\nusemtl floor\n"
                "v -20 0 20\nv 20 0 20\nv 20 0 -20\nv -20 0 -20\n"
                "vt 0 0\nvt 10 0\nvt 10 10\nvt 0 10\nf 1/1 2/2 3/3 4/4\n")
    for name, scene in scenes.items():
        with open(os.path.join(out, name), "w") as f:
            json.dump(scene, f, indent=2)
            f.write("\n")


def write_normal_walls(out):
    """DIR/normal-walls.json: a 4 x 3 x 4 room open at the front (floor, ceiling, back, red left
    and green right walls), each wall a 30 x 20 grid of quads (1200 triangles, 6000 in all, and
    the light's 2) with bevelled tiles in its normal map (tile_normals, one repeat per unit, so
    the tiles are square on every wall), lit by a 1.2 x 1.2 quad just below the ceiling. Ours
    (MIT)."""
    sys.path.insert(0, HERE)
    from make_test_scenes import write_png
    os.makedirs(out, exist_ok=True)
    write_png(os.path.join(out, "tiles-normal.png"), 128, 128, tile_normals())
    verts, uvs, faces = [], [], []

    def grid(material, origin, du, dv, nu=30, nv=20):
        repeat = [math.sqrt(sum(c * c for c in d)) for d in (du, dv)]  # one tile set per unit
        faces.append("usemtl " + material)
        base = len(verts) + 1
        for j in range(nv + 1):
            for i in range(nu + 1):
                a, b = i / nu, j / nv
                verts.append(tuple(origin[k] + a * du[k] + b * dv[k] for k in range(3)))
                uvs.append((a * repeat[0], b * repeat[1]))
        for j in range(nv):
            for i in range(nu):
                q = [base + j * (nu + 1) + i, base + j * (nu + 1) + i + 1,
                     base + (j + 1) * (nu + 1) + i + 1, base + (j + 1) * (nu + 1) + i]
                faces.append("f " + " ".join(f"{v}/{v}" for v in q))
    # Each wall faces into the room (counter-clockwise seen from inside: du x dv points inward).
    grid("floor", (-2, 0, 2), (4, 0, 0), (0, 0, -4))
    grid("ceiling", (-2, 3, -2), (4, 0, 0), (0, 0, 4))
    grid("back", (-2, 0, -2), (4, 0, 0), (0, 3, 0))
    grid("left", (-2, 0, 2), (0, 0, -4), (0, 3, 0))
    grid("right", (2, 0, -2), (0, 0, 4), (0, 3, 0))
    n = len(verts)
    lines = ["# Normal-mapped room (tools/make_bench_scenes.py --normal-walls). MIT.",
             "mtllib walls.mtl"]
    lines += [f"v {x:.6g} {y:.6g} {z:.6g}" for x, y, z in verts]
    lines += [f"vt {u:.6g} {v:.6g}" for u, v in uvs] + faces
    lines += ["usemtl light", "v -0.6 2.99 -0.6", "v 0.6 2.99 -0.6", "v 0.6 2.99 0.6",
              "v -0.6 2.99 0.6", f"f {n + 1} {n + 2} {n + 3} {n + 4}"]
    with open(os.path.join(out, "walls.obj"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(out, "walls.mtl"), "w") as f:
        f.write("# Normal-mapped room (tools/make_bench_scenes.py). MIT.\n" +
                "".join(f"newmtl {m}\nKd 0.7 0.7 0.7\n"
                        for m in ("floor", "ceiling", "back", "left", "right")) +
                "newmtl light\nKd 0 0 0\nKe 15 13 10\n")

    def wall(albedo):
        return {"type": "diffuse", "albedo": albedo, "normal_map": "tiles"}
    white = [0.7, 0.7, 0.7]
    camera = {"eye": [0, 1.5, 6.2], "target": [0, 1.4, 0], "up": [0, 1, 0], "fov_y": 40.0}
    scene = {"camera": camera,
             "film": {"width": 1280, "height": 960}, "render": {"spp": 64, "max_depth": 8},
             "textures": {"tiles": {"file": "tiles-normal.png", "encoding": "linear"}},
             "materials": {"floor": wall(white), "ceiling": wall(white), "back": wall(white),
                           "left": wall([0.63, 0.065, 0.05]), "right": wall([0.14, 0.45, 0.091])},
             "objects": [{"obj": "walls.obj"}]}
    path = os.path.join(out, "normal-walls.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=2)
        f.write("\n")
    print(f"{path}: {len(faces) - 5} quads")


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--tori":
        write_tori(sys.argv[2])
        return
    if len(sys.argv) == 3 and sys.argv[1] == "--normal-walls":
        write_normal_walls(sys.argv[2])
        return
    write_materials_bench(os.path.join(HERE, "..", "scenes", "bench-materials"))
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
