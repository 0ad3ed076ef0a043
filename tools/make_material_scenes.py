# SPDX-License-Identifier: MIT
"""The material validation scenes of tests/scenes/ (written by tools/make_test_scenes.py): JSON
materials (DESIGN.md "Materials") on small generated meshes, each checked against a Mitsuba 3
reference by tests/test_reference_materials.c.

  conductors/   rough gold (eta/k, r 0.3) and anisotropic rough copper (r 0.35, a 0.8) on a diffuse
                floor, area light
  glass/        rough glass (r 0.2) sphere and slab with Beer absorption, area light and a grey sky
  glass-clear/  the same without absorption: the rough dielectric apart from the medium
  normalmap/    a wall with a generated normal map (known pattern) lit at a grazing angle
  mix/          mix of diffuse and rough conductor (weight 0.3) and a Fresnel-1 mirror cube
  envmap/       a generated HDR sky (gradient + soft sun), rotation 30, rough gold and a diffuse cube
  envmap-diffuse/  the same with MTL (diffuse) materials only: the map apart from the materials

Deterministic, plain Python. The JSON materials replace the MTL materials of the same name.
Run on its own (`python3 tools/make_material_scenes.py`, as `make` does) it writes only the large
OBJ files that git does not keep (GENERATED_MESHES).
"""
import math
import os

import make_test_scenes as base
from make_test_scenes import HEADER, cross, fmt, normalize, sub

MTL_LIGHT = "newmtl light\nillum 2\nKd 0 0 0\nKe {0} {0} {0}\n"


class Obj:
    """An OBJ being written: vertices, texcoords and faces grouped by material."""

    def __init__(self, mtl):
        self.mtl, self.v, self.vt, self.faces = mtl, [], [], []

    def face(self, material, points, uvs=None):
        """One polygon, counter-clockwise seen from the side its normal points to."""
        base_v = len(self.v)
        self.v.extend(points)
        if uvs:
            base_t = len(self.vt)
            self.vt.extend(uvs)
            corners = [f"{base_v + i + 1}/{base_t + i + 1}" for i in range(len(points))]
        else:
            corners = [str(base_v + i + 1) for i in range(len(points))]
        self.faces.append((material, "f " + " ".join(corners)))

    def write(self, path):
        lines = [HEADER, f"mtllib {self.mtl}\n"]
        lines += [f"v {' '.join(fmt(c) for c in p)}\n" for p in self.v]
        lines += [f"vt {' '.join(fmt(c) for c in t)}\n" for t in self.vt]
        current = None
        for material, face in self.faces:
            if material != current:
                lines.append(f"usemtl {material}\n")
                current = material
            lines.append(face + "\n")
        with open(path, "w") as f:
            f.writelines(lines)


def add_icosphere(obj, material, center, radius, subdivisions=3):
    verts, faces = base.icosphere(subdivisions)
    for f in faces:
        obj.face(material, [[center[i] + radius * verts[k][i] for i in range(3)] for k in f])


def add_uv_sphere(obj, material, center, radius, nu=32, nv=16):
    """Flat-shaded sphere with u around +y (from -z toward +x) and v from the south pole (0) to
    the north pole (1): its dp/du tangents run along the parallels, the anisotropic axis."""
    def point(i, j):
        phi, theta = 2 * math.pi * i / nu, math.pi * (1 - j / nv)
        return [center[0] + radius * math.sin(theta) * math.sin(phi),
                center[1] + radius * math.cos(theta),
                center[2] - radius * math.sin(theta) * math.cos(phi)]
    for i in range(nu):
        for j in range(nv):
            quad = [(i, j), (i, j + 1), (i + 1, j + 1), (i + 1, j)]
            if j == 0:
                quad = [(i, 0), (i, 1), (i + 1, 1)]
            elif j == nv - 1:
                quad = [(i, j), (i, j + 1), (i + 1, j)]
            obj.face(material, [point(a, b) for a, b in quad], [[a / nu, b / nv] for a, b in quad])


def add_box(obj, material, center, size, angle_deg):
    """Box of size (sx, sy, sz) rotated about +y, per-face UVs, wound outward."""
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    corners = []
    for i in range(8):
        x, y, z = [(size[k] / 2 if i & (1 << k) else -size[k] / 2) for k in range(3)]
        corners.append([center[0] + c * x + s * z, center[1] + y, center[2] - s * x + c * z])
    for q in [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]]:
        obj.face(material, [corners[k] for k in q], [[0, 0], [1, 0], [1, 1], [0, 1]])


def add_floor(obj, material, half, y=0.0):
    obj.face(material, [[-half, y, half], [half, y, half], [half, y, -half], [-half, y, -half]],
             [[0, 0], [1, 0], [1, 1], [0, 1]])


def add_light(obj, center, half, y):
    """A square facing down."""
    x, z = center
    obj.face("light", [[x - half, y, z - half], [x + half, y, z - half], [x + half, y, z + half],
                       [x - half, y, z + half]])


def write(out, name, mtl, obj, scene):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, f"{name}.mtl"), "w") as f:
        f.write(HEADER + "# The JSON materials of scene.json replace these (same names).\n" + mtl)
    obj.write(os.path.join(out, f"{name}.obj"))
    scene["objects"] = [{"obj": f"{name}.obj"}]
    base.write_scene_json(os.path.join(out, "scene.json"), scene)


CAMERA = {"eye": [0, 1.7, 4.2], "target": [0, 0.45, 0], "up": [0, 1, 0], "fov_y": 36.0}
PLAIN_MTL = "".join(f"newmtl {n}\nillum 2\nKd 0.5 0.5 0.5\n" for n in ("floor", "a", "b", "c"))


def write_conductors(out):
    obj = Obj("conductors.mtl")
    add_floor(obj, "floor", 2.5)
    add_icosphere(obj, "a", [-0.7, 0.6, 0.0], 0.6)
    add_uv_sphere(obj, "b", [0.7, 0.6, 0.0], 0.6)
    add_light(obj, (0.3, 0.6), 0.5, 3.0)
    write(out, "conductors", PLAIN_MTL + MTL_LIGHT.format(14), obj, {
        "camera": CAMERA, "film": {"width": 80, "height": 80}, "render": {"spp": 64, "max_depth": 6},
        "materials": {
            "floor": {"type": "diffuse", "albedo": [0.5, 0.5, 0.45]},
            "a": {"type": "conductor", "eta": [0.143, 0.374, 1.442], "k": [3.983, 2.385, 1.603],
                  "roughness": 0.3},
            "b": {"type": "conductor", "eta": [0.200, 0.924, 1.102], "k": [3.912, 2.452, 2.142],
                  "roughness": 0.35, "anisotropy": 0.8}},
        "background": [0.12, 0.12, 0.15]})


def write_glass(out, absorption=(0.1, 0.6, 1.4)):
    name = os.path.basename(out)
    obj = Obj(f"{name}.mtl")
    add_floor(obj, "floor", 2.5)
    add_icosphere(obj, "a", [-0.55, 0.62, 0.1], 0.6)
    add_box(obj, "a", [0.8, 0.45, -0.2], [0.3, 0.9, 1.2], -30)
    add_light(obj, (-0.2, 0.2), 0.75, 3.0)
    glass = {"type": "dielectric", "ior": 1.5, "roughness": 0.2}
    if any(absorption):
        glass["absorption"] = list(absorption)
    write(out, name, PLAIN_MTL + MTL_LIGHT.format(6), obj, {
        "camera": CAMERA, "film": {"width": 80, "height": 80}, "render": {"spp": 64, "max_depth": 8},
        "materials": {
            "floor": {"type": "diffuse", "albedo": [0.6, 0.55, 0.5]},
            "a": glass},
        "background": [0.3, 0.3, 0.32]})


def normal_map_texels(size=64):
    """Rows top first (v = 1). Left half: ridges across u (normals tilting to -x and +x, 4 periods);
    top-right quarter: tilted toward +v (up the wall); bottom-right: toward -v. Up to 35 degrees."""
    rows = []
    t = math.tan(math.radians(35))
    for y in range(size):
        row = []
        for x in range(size):
            if x < size // 2:
                tx, ty = t * math.sin(2 * math.pi * 4 * (x + 0.5) / (size // 2)), 0.0
            else:
                tx, ty = 0.0, (t if y < size // 2 else -t)
            n = normalize([tx, ty, 1.0])
            row.append(tuple(max(0, min(255, round((c * 0.5 + 0.5) * 255))) for c in n))
        rows.append(row)
    return rows


def write_normalmap(out):
    os.makedirs(out, exist_ok=True)
    base.write_png(os.path.join(out, "normals.png"), 64, 64, normal_map_texels(64))
    obj = Obj("normalmap.mtl")
    # The wall: z = 0, facing +z, u along +x, v along +y (not mirrored), 2 x 2.
    obj.face("wall", [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], [[0, 0], [1, 0], [1, 1], [0, 1]])
    # The light: right of the wall, just in front of it and above its middle, facing -x: light
    # arrives 10-25 degrees above the wall's plane from +x and from above, so the tilts toward +u
    # and toward +v are the brighter ones.
    obj.face("light", [[2.4, 0.2, 0.35], [2.4, 0.2, 1.0], [2.4, 1.2, 1.0], [2.4, 1.2, 0.35]])
    write(out, "normalmap", "newmtl wall\nillum 2\nKd 0.5 0.5 0.5\n" + MTL_LIGHT.format(20), obj, {
        "camera": {"eye": [0, 0, 3.2], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 36.0},
        "film": {"width": 64, "height": 64}, "render": {"spp": 64, "max_depth": 4},
        "textures": {"bumps": {"file": "normals.png", "encoding": "linear"}},
        "materials": {"wall": {"type": "diffuse", "albedo": [0.8, 0.8, 0.8], "normal_map": "bumps"}}})


def write_mix(out):
    obj = Obj("mix.mtl")
    add_floor(obj, "floor", 2.5)
    add_icosphere(obj, "a", [-0.55, 0.6, 0.1], 0.6)
    add_box(obj, "b", [0.85, 0.4, -0.3], [0.8, 0.8, 0.8], 35)
    add_light(obj, (0.0, 0.5), 0.5, 3.0)
    write(out, "mix", PLAIN_MTL + MTL_LIGHT.format(14), obj, {
        "camera": CAMERA, "film": {"width": 80, "height": 80}, "render": {"spp": 64, "max_depth": 6},
        "materials": {
            "floor": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
            "red": {"type": "diffuse", "albedo": [0.7, 0.12, 0.08]},
            "steel": {"type": "conductor", "eta": [2.87, 2.92, 2.59], "k": [3.09, 2.93, 2.77],
                      "roughness": 0.25},
            "a": {"type": "mix", "a": "red", "b": "steel", "weight": 0.3},
            "b": {"type": "conductor", "roughness": 0, "reflectance": [0.9, 0.85, 0.7]}},
        "background": [0.1, 0.1, 0.12]})


def sky_texels(width=128, height=64):
    """Linear RGB rows, top first: a blue-to-white sky above the horizon, a brown ground below, and
    a soft sun (Gaussian, 6 degrees) at u = 0.62, 30 degrees up. Smooth over several texels, so a
    bilinear lookup and a piecewise-constant one see nearly the same map."""
    sun_u, sun_elev, sigma = 0.62, math.radians(30), math.radians(6)
    sun = [math.cos(sun_elev) * math.sin(2 * math.pi * (sun_u - 0.5)), math.sin(sun_elev),
           -math.cos(sun_elev) * math.cos(2 * math.pi * (sun_u - 0.5))]
    rows = []
    for j in range(height):
        theta = math.pi * (j + 0.5) / height
        row = []
        for i in range(width):
            phi = 2 * math.pi * ((i + 0.5) / width - 0.5)
            d = [math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi)]
            if d[1] > 0:
                h = d[1] ** 0.5
                c = [0.9 - 0.6 * h, 1.0 - 0.45 * h, 1.2 - 0.1 * h]
            else:
                c = [0.35, 0.28, 0.2]
            angle = math.acos(max(-1.0, min(1.0, sum(a * b for a, b in zip(d, sun)))))
            glow = 40.0 * math.exp(-0.5 * (angle / sigma) ** 2)
            row.append([c[0] + glow, c[1] + 0.9 * glow, c[2] + 0.75 * glow])
        rows.append(row)
    return rows


def write_hdr(path, rows):
    """Radiance RGBE, flat (not run-length encoded) scanlines, top row first."""
    def rgbe(c):
        m = max(c)
        if m < 1e-32:
            return bytes(4)
        e = math.frexp(m)[1]
        scale = 256.0 / 2.0 ** e
        return bytes([min(255, int(x * scale)) for x in c] + [e + 128])
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {len(rows)} +X {len(rows[0])}\n".encode())
        for row in rows:
            f.write(b"".join(rgbe(c) for c in row))


def write_envmap(out):
    os.makedirs(out, exist_ok=True)
    write_hdr(os.path.join(out, "sky.hdr"), sky_texels())
    obj = Obj("envmap.mtl")
    add_floor(obj, "floor", 2.0)
    add_icosphere(obj, "a", [-0.5, 0.6, 0.0], 0.6)
    add_box(obj, "b", [0.85, 0.35, 0.3], [0.7, 0.7, 0.7], 20)
    write(out, "envmap", PLAIN_MTL, obj, {
        "camera": CAMERA, "film": {"width": 80, "height": 80}, "render": {"spp": 64, "max_depth": 6},
        "materials": {
            "floor": {"type": "diffuse", "albedo": [0.45, 0.45, 0.45]},
            "a": {"type": "conductor", "eta": [0.143, 0.374, 1.442], "k": [3.983, 2.385, 1.603],
                  "roughness": 0.3},
            "b": {"type": "diffuse", "albedo": [0.2, 0.4, 0.7]}},
        "environment": {"file": "sky.hdr", "scale": 1.0, "rotation": 30}})


def write_envmap_diffuse(out):
    """envmap/ with MTL materials only (all diffuse): the map's orientation, rotation and sampling
    checked apart from the JSON materials."""
    os.makedirs(out, exist_ok=True)
    write_hdr(os.path.join(out, "sky.hdr"), sky_texels())
    obj = Obj("envmap-diffuse.mtl")
    add_floor(obj, "floor", 2.0)
    add_icosphere(obj, "a", [-0.5, 0.6, 0.0], 0.6)
    add_box(obj, "b", [0.85, 0.35, 0.3], [0.7, 0.7, 0.7], 20)
    mtl = ("newmtl floor\nillum 2\nKd 0.45 0.45 0.45\nnewmtl a\nillum 2\nKd 0.8 0.6 0.3\n"
           "newmtl b\nillum 2\nKd 0.2 0.4 0.7\n")
    write(out, "envmap-diffuse", mtl, obj, {
        "camera": CAMERA, "film": {"width": 80, "height": 80}, "render": {"spp": 64, "max_depth": 6},
        "environment": {"file": "sky.hdr", "scale": 1.0, "rotation": 30}})


def write_all(out):
    """Writes every scene under out/ and checks the OBJ files; returns the scene names."""
    writers = {"conductors": write_conductors, "glass": write_glass, "normalmap": write_normalmap,
               "glass-clear": lambda out: write_glass(out, (0, 0, 0)), "mix": write_mix, "envmap": write_envmap, "envmap-diffuse": write_envmap_diffuse}
    for name, writer in writers.items():
        writer(os.path.join(out, name))
        lights = ("light",) if name != "normalmap" else ()
        for g in base.check_obj(os.path.join(out, name, f"{name}.obj"), down_facing=lights):
            if g.material.name in ("a", "b"):  # closed meshes, wound outward
                assert base.signed_volume(g) > 0, f"{name}/{g.material.name}: wound inward"
    wall = base.check_obj(os.path.join(out, "normalmap", "normalmap.obj"))
    p = [g for g in wall if g.material.name == "light"][0].positions
    assert normalize(cross(sub(p[1], p[0]), sub(p[2], p[0])))[0] < -0.999, "light must face -x"
    return list(writers)


# The scenes whose OBJ is too large to keep in git (thousands of lines of generated vertices): the
# repository keeps their scene.json, MTL and maps, and `make` writes the OBJ (write_meshes) before
# the tests run. The generator is deterministic, so the meshes are the ones the Mitsuba references
# in tests/references/ were rendered from, byte for byte.
GENERATED_MESHES = ("conductors", "envmap", "envmap-diffuse", "glass", "glass-clear", "mix")


def write_meshes(scenes_dir):
    """Writes tests/scenes/<name>/<name>.obj for GENERATED_MESHES (through a scratch copy of every
    scene, so the writers and checks are the same as write_all's); a file already equal is left
    alone, so make sees nothing new."""
    import tempfile
    with tempfile.TemporaryDirectory(prefix="pt-meshes-") as scratch:
        write_all(scratch)
        copy_changed(scratch, scenes_dir, [os.path.join(name, f"{name}.obj") for name in GENERATED_MESHES])


def copy_changed(scratch, scenes_dir, paths):
    """Copies each of paths (relative) from scratch to scenes_dir, leaving a file already equal
    alone (make then sees nothing new); each copy replaces the old file in one rename."""
    import shutil
    for rel in paths:
        src, dst = os.path.join(scratch, rel), os.path.join(scenes_dir, rel)
        with open(src, "rb") as f:
            data = f.read()
        if os.path.exists(dst):
            with open(dst, "rb") as f:
                if f.read() == data:
                    continue
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copyfile(src, dst + ".tmp")
        os.replace(dst + ".tmp", dst)


if __name__ == "__main__":
    import sys
    here = os.path.dirname(os.path.abspath(__file__))
    write_meshes(sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "tests", "scenes"))
