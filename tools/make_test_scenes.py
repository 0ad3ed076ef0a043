#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the generated validation scenes under tests/scenes/ (textured/, furnace/, and the material
scenes of tools/make_material_scenes.py).

Deterministic: no randomness, no timestamps, fixed float formatting, so running it twice gives
byte-identical files (the PNG is written with a fixed zlib level). Plain Python 3, no packages.

After writing, every OBJ is read back with the OBJ/MTL reader of tools/mitsuba_reference.py
(tinyobjloader's rules: 1-based or negative indices, n-gons, usemtl/mtllib) and checked: indices in
range, every material defined, textures present and decodable, closed meshes wound
counter-clockwise seen from outside (positive signed volume), and the lights facing down.

    python3 tools/make_test_scenes.py [OUT_DIR]     (default: tests/scenes next to this tool)
"""
import json
import math
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import mitsuba_reference as reader  # noqa: E402  (its OBJ/MTL reader needs no third-party package)

FIELD = 6  # decimals written for coordinates; enough for these scenes, stable across platforms


def fmt(x):
    s = f"{x:.{FIELD}f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


# ---- PNG writing (8-bit RGB, no filtering) -------------------------------------------------------

def write_png(path, width, height, rgb_rows):
    """rgb_rows: list of rows (top row first), each a list of (r, g, b) bytes. Row 0 is the image's
    top, as in every image file: OBJ's v = 1 lands there."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in rgb_rows)
    png = (b"\x89PNG\r\n\x1a\n" +
           chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
           chunk(b"sRGB", b"\x00") +  # says the 8-bit values are sRGB-encoded
           chunk(b"IDAT", zlib.compress(raw, 9)) +
           chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def checker_texture(size=64):
    """An asymmetric test texture, row 0 = top (v = 1):
    - 8x8-texel checker squares; light squares full brightness, dark ones at 35 %,
    - red rises with u (left to right), blue rises with v (bottom to top), green is a mid-grey
      level (sRGB 128, linear 0.216: a missing sRGB decode makes it 0.5, clearly visible),
    - a pure green 16x16 marker in the top-left corner (u < 0.25, v > 0.75): a v flip moves it to
      the bottom-left, a u flip to the top-right."""
    rows = []
    for y in range(size):
        row = []
        for x in range(size):
            if x < 16 and y < 16:
                row.append((0, 255, 0))
                continue
            r = 40 + round(215 * x / (size - 1))
            b = 40 + round(215 * (size - 1 - y) / (size - 1))
            g = 128
            if ((x // 8) + (y // 8)) % 2:
                r, g, b = (round(c * 0.35) for c in (r, g, b))
            row.append((r, g, b))
        rows.append(row)
    return rows


# ---- geometry helpers ----------------------------------------------------------------------------

def sub(a, b): return [a[i] - b[i] for i in range(3)]
def cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def dot(a, b): return sum(a[i] * b[i] for i in range(3))


def normalize(a):
    n = math.sqrt(dot(a, a))
    return [c / n for c in a]


def cube(center, size, angle_deg):
    """8 corners and 6 quads (corner indices), each quad counter-clockwise seen from outside, with
    per-quad UVs (0,0) (1,0) (1,1) (0,1) in quad order, rotated angle_deg about +y."""
    h = size / 2
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    corners = []
    for i in range(8):
        x, y, z = (h if i & 1 else -h), (h if i & 2 else -h), (h if i & 4 else -h)
        corners.append([center[0] + c * x + s * z, center[1] + y, center[2] - s * x + c * z])
    quads = [[0, 4, 6, 2], [1, 3, 7, 5],   # -x, +x
             [0, 1, 5, 4], [2, 6, 7, 3],   # -y, +y
             [0, 2, 3, 1], [4, 5, 7, 6]]   # -z, +z
    return corners, quads


def icosphere(subdivisions):
    t = (1 + math.sqrt(5)) / 2
    verts = [normalize(v) for v in [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0],
                                    [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
                                    [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
             [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
             [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    for _ in range(subdivisions):
        midpoint = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in midpoint:
                verts.append(normalize([(verts[a][i] + verts[b][i]) / 2 for i in range(3)]))
                midpoint[key] = len(verts) - 1
            return midpoint[key]
        new_faces = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new_faces += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = new_faces
    for f in faces:  # outward = counter-clockwise seen from outside
        p = [verts[i] for i in f]
        assert dot(cross(sub(p[1], p[0]), sub(p[2], p[0])), p[0]) > 0, "icosphere face wound inward"
    return verts, faces


# ---- scene writers -------------------------------------------------------------------------------

HEADER = "# Generated by tools/make_test_scenes.py (deterministic). License: MIT, like the project.\n"


def write_scene_json(path, scene):
    with open(path, "w") as f:
        json.dump(scene, f, indent=2)
        f.write("\n")


def write_textured(out):
    os.makedirs(out, exist_ok=True)
    write_png(os.path.join(out, "checker.png"), 64, 64, checker_texture(64))
    with open(os.path.join(out, "textured.mtl"), "w") as f:
        f.write(HEADER)
        f.write("\n# Kd 1 is written out: tinyobjloader gives map_Kd without Kd a Kd of 0.6.\n")
        f.write("newmtl checker\nillum 2\nKd 1 1 1\nmap_Kd checker.png\n\n")
        f.write("newmtl blue\nillum 2\nKd 0.15 0.35 0.75\n\n")
        f.write("newmtl light\nillum 2\nKd 0.5 0.5 0.5\nKe 12 11 9\n")

    v, vt, vn, lines = [], [], [], [HEADER, "mtllib textured.mtl\n"]

    def add_v(p):
        v.append(p)
        return len(v)

    def add_vt(uv):
        vt.append(uv)
        return len(vt)

    def add_vn(n):
        vn.append(n)
        return len(vn)

    # Floor: 4 x 4 at y = 0, u along +x, v along -z (v = 1 at the back), normal up. One quad.
    lines.append("\no floor\nusemtl checker\n")
    floor = [[-2, 0, 2], [2, 0, 2], [2, 0, -2], [-2, 0, -2]]
    floor_uv = [[0, 0], [1, 0], [1, 1], [0, 1]]
    idx = [(add_v(p), add_vt(t)) for p, t in zip(floor, floor_uv)]
    lines.append("f " + " ".join(f"{a}/{b}" for a, b in idx) + "\n")

    # Textured cube (flat: no vn), each face showing the whole texture.
    lines.append("\no textured_cube\nusemtl checker\n")
    corners, quads = cube([0.25, 0.5, 1.0], 1.0, 25)
    base = len(v)
    for p in corners:
        add_v(p)
    for q in quads:
        t = [add_vt(uv) for uv in floor_uv]
        lines.append("f " + " ".join(f"{base + 1 + c}/{ti}" for c, ti in zip(q, t)) + "\n")

    # Plain blue cube with explicit per-face normals (exercises v//vn).
    lines.append("\no blue_cube\nusemtl blue\n")
    corners, quads = cube([1.15, 0.4, -0.7], 0.8, -20)
    base = len(v)
    for p in corners:
        add_v(p)
    for q in quads:
        p = [corners[c] for c in q]
        n = add_vn(normalize(cross(sub(p[1], p[0]), sub(p[2], p[0]))))
        lines.append("f " + " ".join(f"{base + 1 + c}//{n}" for c in q) + "\n")

    # Light: 1 x 1 quad at y = 3, off centre, wound so its geometric normal points down.
    lines.append("\no light\nusemtl light\n")
    light = [[-0.1, 3, -0.6], [0.9, 3, -0.6], [0.9, 3, 0.4], [-0.1, 3, 0.4]]
    idx = [add_v(p) for p in light]
    lines.append("f " + " ".join(str(i) for i in idx) + "\n")

    body = ("".join(f"v {' '.join(fmt(c) for c in p)}\n" for p in v) +
            "".join(f"vt {' '.join(fmt(c) for c in t)}\n" for t in vt) +
            "".join(f"vn {' '.join(fmt(c) for c in n)}\n" for n in vn))
    with open(os.path.join(out, "textured.obj"), "w") as f:
        f.write(lines[0] + lines[1] + body + "".join(lines[2:]))

    write_scene_json(os.path.join(out, "scene.json"), {
        "camera": {"eye": [0.6, 2.6, 5.2], "target": [0, 0.35, 0], "up": [0, 1, 0], "fov_y": 42.0},
        "film": {"width": 128, "height": 128},
        "render": {"spp": 64, "max_depth": 6},
        "objects": [{"obj": "textured.obj"}],
        "background": [0.2, 0.2, 0.25],
    })


def write_furnace(out):
    os.makedirs(out, exist_ok=True)
    verts, faces = icosphere(3)
    with open(os.path.join(out, "sphere.mtl"), "w") as f:
        f.write(HEADER + "\nnewmtl grey80\nillum 2\nKd 0.8 0.8 0.8\n")
    with open(os.path.join(out, "sphere.obj"), "w") as f:
        f.write(HEADER + "# Unit icosphere, 3 subdivisions, no vn: shaded flat.\n")
        f.write("mtllib sphere.mtl\no sphere\n")
        f.writelines(f"v {' '.join(fmt(c) for c in p)}\n" for p in verts)
        f.write("usemtl grey80\n")
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)
    write_scene_json(os.path.join(out, "scene.json"), {
        "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40.0},
        "film": {"width": 128, "height": 128},
        "render": {"spp": 64, "max_depth": 8},
        "objects": [{"obj": "sphere.obj"}],
        "background": [1, 1, 1],
    })


# ---- checks on what was written ------------------------------------------------------------------

def signed_volume(mesh):
    return sum(dot(mesh.positions[a], cross(mesh.positions[b], mesh.positions[c]))
               for a, b, c in mesh.triangles) / 6


def check_obj(path, closed_groups=(), down_facing=()):
    """Reads path back with the reference tool's reader and checks what a loader relies on."""
    groups = reader.load_obj(path)
    for g in groups:
        if g.material is None:
            raise SystemExit(f"{path}: faces without a defined material")
        tex = g.material.map_kd
        if tex:
            reader.read_png_size(tex)  # raises on a corrupt file
        for tri in g.triangles:
            p = [g.positions[i] for i in tri]
            n = cross(sub(p[1], p[0]), sub(p[2], p[0]))
            if dot(n, n) == 0:
                raise SystemExit(f"{path}: degenerate triangle in '{g.material.name}'")
            if g.material.name in down_facing and not normalize(n)[1] < -0.999:
                raise SystemExit(f"{path}: light triangle does not face down")
    return groups


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "tests", "scenes")
    write_textured(os.path.join(out, "textured"))
    write_furnace(os.path.join(out, "furnace"))

    groups = check_obj(os.path.join(out, "textured", "textured.obj"), down_facing=("light",))
    names = sorted(g.material.name for g in groups)
    assert names == ["blue", "checker", "light"], names
    sphere = check_obj(os.path.join(out, "furnace", "sphere.obj"))
    assert len(sphere) == 1 and len(sphere[0].triangles) == 1280
    volume = signed_volume(sphere[0])
    assert 4.0 < volume < 4 * math.pi / 3, f"icosphere volume {volume}: wound inward?"
    # Each cube must be closed and wound outward. The floor (all at y = 0) adds no volume.
    for g in groups:
        expected = {"blue": 0.8 ** 3, "checker": 1.0}.get(g.material.name)
        assert expected is None or abs(signed_volume(g) - expected) < 1e-4, f"{g.material.name}: not closed/outward"
    import make_material_scenes  # noqa: E402  (imports this module's helpers)
    names = make_material_scenes.write_all(out)
    print(f"make_test_scenes: wrote {os.path.normpath(out)}/textured, furnace, {', '.join(names)}; "
          "checks passed")


if __name__ == "__main__":
    main()
