#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The media validation scenes of tests/scenes/ (/work/shared/DESIGN.md "Media"), each checked
against a Mitsuba 3 `volpath` reference by tests/test_reference.c:

  fog-room/    a room open at the front, its air filled with grey fog (sigma_a 0.04, sigma_s 0.3,
               g 0.5) by an invisible "interface" box, lit by a spot light above the fog (cone 25,
               falloff 18 degrees) past a plate whose shadow is a dark shaft through the fog
  smoke/       a procedural 32^3 density blob (smoke.vol, Mitsuba's format) with a chromatic albedo
               and g 0.3 inside an invisible "interface" box, over a floor, lit by the envmap
               scene's generated sky
  liquid/      a cylinder of coloured liquid (dielectric, ior 1.33, an interior medium that scatters
               and absorbs per channel, g 0.2) on a diffuse floor under an area light, all in a thin
               grey haze, the world medium ("medium": the camera, the light and every surface sit
               in it; g -0.2)
  subsurface/  a glass-like sphere (dielectric, ior 1.4, flat icosphere) filled with a dense
               skin-like medium (red travels furthest), area light: a random walk inside a closed mesh

The repository keeps scene.json and the MTL files; the meshes, the grid and the sky are generated
(`make` runs this tool before any test binary: write_generated), deterministic, byte for byte the
files the references were rendered from. Plain Python.

    python3 tools/make_media_scenes.py [SCENES_DIR]     (default: tests/scenes next to this tool)
"""
import math
import os
import sys
import tempfile

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_material_scenes as mat  # noqa: E402
import make_test_scenes as base  # noqa: E402
from mitsuba_vol import write_vol  # noqa: E402

MTL_LIGHT = mat.MTL_LIGHT
CAMERA = mat.CAMERA


def write_mtl(path, text):
    with open(path, "w") as f:
        f.write(base.HEADER + text)


def write_fog_room(out):
    """The fog fills an interface box below the spot light: a delta light inside a medium gives the
    in-scattered radiance infinite variance (1/r^2 near the light) in both renderers."""
    os.makedirs(out, exist_ok=True)
    write_mtl(os.path.join(out, "room.mtl"),
              "newmtl white\nillum 2\nKd 0.6 0.6 0.6\nnewmtl red\nillum 2\nKd 0.6 0.15 0.12\n"
              "newmtl green\nillum 2\nKd 0.15 0.5 0.15\nnewmtl plate\nillum 2\nKd 0.7 0.7 0.65\n"
              "newmtl fog\nillum 2\nKd 0.5 0.5 0.5\n")
    room = mat.Obj("room.mtl")
    w, h = 1.5, 2.5
    room.face("white", [[-w, 0, w], [w, 0, w], [w, 0, -w], [-w, 0, -w]])      # floor, up
    room.face("white", [[-w, h, -w], [w, h, -w], [w, h, w], [-w, h, w]])      # ceiling, down
    room.face("white", [[-w, 0, -w], [w, 0, -w], [w, h, -w], [-w, h, -w]])    # back wall, +z
    room.face("red", [[-w, 0, w], [-w, 0, -w], [-w, h, -w], [-w, h, w]])      # left wall, +x
    room.face("green", [[w, 0, -w], [w, 0, w], [w, h, w], [w, h, -w]])        # right wall, -x
    # A small plate 0.3 under the spot, beside its axis and above the fog: its shadow is a dark
    # shaft through the lit fog (the axis passes y = 2.1 at x = -0.1625, z = 0.1375).
    room.face("plate", [[-0.14, 2.1, 0.16], [-0.08, 2.1, 0.16], [-0.08, 2.1, 0.1], [-0.14, 2.1, 0.1]])
    room.write(os.path.join(out, "room.obj"))
    fog = mat.Obj("room.mtl")
    mat.add_box(fog, "fog", [0, 1.01, 0], [2.9, 1.98, 2.9], 0)  # y from 0.02 to 2.0, clear of the walls
    fog.write(os.path.join(out, "fog.obj"))
    base.write_scene_json(os.path.join(out, "scene.json"), {
        "camera": {"eye": [0, 1.25, 3.4], "target": [0, 1.0, -1.5], "up": [0, 1, 0], "fov_y": 42.0},
        "film": {"width": 64, "height": 64}, "render": {"spp": 64, "max_depth": 8},
        "media": {"fog": {"type": "homogeneous", "sigma_a": 0.04, "sigma_s": 0.3, "g": 0.5}},
        "materials": {"boundary": {"type": "interface"}},
        "lights": [{"type": "spot", "position": [-0.2, 2.4, 0.2], "direction": [0.3, -2.4, -0.5],
                    "intensity": [30, 28, 24], "cone_angle": 25, "falloff_angle": 18}],
        "objects": [{"obj": "room.obj"},
                    {"obj": "fog.obj", "material": "boundary", "interior": "fog"}]})


def smoke_density(x, y, z):
    """A lumpy blob in [0, 1]^3 (unit cube coordinates): three Gaussian puffs and a ripple, 0 at
    the faces' middles, so the grid's edge matters little."""
    puffs = [((0.5, 0.35, 0.5), 0.2, 1.0), ((0.38, 0.62, 0.45), 0.14, 0.8), ((0.64, 0.6, 0.58), 0.12, 0.7)]
    d = 0.0
    for (cx, cy, cz), r, a in puffs:
        d += a * math.exp(-((x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2) / (2 * r * r))
    d *= 0.8 + 0.2 * math.sin(17 * x + 3) * math.sin(13 * y + 1) * math.sin(11 * z + 2)
    return min(d, 1.0)


SMOKE_RES = 32
SMOKE_MIN, SMOKE_MAX = [-0.6, 0.05, -0.6], [0.6, 1.25, 0.6]


def write_smoke_vol(path):
    n = SMOKE_RES
    values = [round(smoke_density((i + 0.5) / n, (j + 0.5) / n, (k + 0.5) / n), 6)
              for k in range(n) for j in range(n) for i in range(n)]
    write_vol(path, (n, n, n), SMOKE_MIN, SMOKE_MAX, values)


def write_smoke(out):
    os.makedirs(out, exist_ok=True)
    write_smoke_vol(os.path.join(out, "smoke.vol"))
    mat.write_hdr(os.path.join(out, "sky.hdr"), mat.sky_texels())
    write_mtl(os.path.join(out, "smoke.mtl"), "newmtl floor\nillum 2\nKd 0.45 0.45 0.45\n"
              "newmtl box\nillum 2\nKd 0.5 0.5 0.5\n")
    floor = mat.Obj("smoke.mtl")
    mat.add_floor(floor, "floor", 2.0)
    floor.write(os.path.join(out, "floor.obj"))
    box = mat.Obj("smoke.mtl")
    # The interface box: a little larger than the grid's box, clear of the floor.
    lo, hi = [m - 0.05 for m in SMOKE_MIN], [m + 0.05 for m in SMOKE_MAX]
    lo[1] = 0.01
    mat.add_box(box, "box", [(a + b) / 2 for a, b in zip(lo, hi)], [b - a for a, b in zip(lo, hi)], 0)
    box.write(os.path.join(out, "box.obj"))
    base.write_scene_json(os.path.join(out, "scene.json"), {
        "camera": {"eye": [0, 1.3, 3.6], "target": [0, 0.6, 0], "up": [0, 1, 0], "fov_y": 36.0},
        "film": {"width": 64, "height": 64}, "render": {"spp": 64, "max_depth": 12},
        "media": {"smoke": {"type": "grid", "file": "smoke.vol", "density_scale": 8.0,
                            "albedo": [0.95, 0.75, 0.45], "g": 0.3}},
        "materials": {"boundary": {"type": "interface"}},
        "environment": {"file": "sky.hdr", "scale": 1.0, "rotation": 30},
        "objects": [{"obj": "floor.obj"},
                    {"obj": "box.obj", "material": "boundary", "interior": "smoke"}]})


def add_cylinder(obj, material, center, radius, height, segments=48):
    """A closed cylinder standing on center (its bottom's middle), flat-shaded, wound outward."""
    cx, y0, cz = center
    y1 = y0 + height
    ring = [(cx + radius * math.sin(2 * math.pi * i / segments),
             cz + radius * math.cos(2 * math.pi * i / segments)) for i in range(segments)]
    for i in range(segments):
        (x0, z0), (x1, z1) = ring[i], ring[(i + 1) % segments]
        obj.face(material, [[x0, y0, z0], [x1, y0, z1], [x1, y1, z1], [x0, y1, z0]])
        obj.face(material, [[cx, y1, cz], [x0, y1, z0], [x1, y1, z1]])
        obj.face(material, [[cx, y0, cz], [x1, y0, z1], [x0, y0, z0]])


def write_liquid(out):
    os.makedirs(out, exist_ok=True)
    write_mtl(os.path.join(out, "liquid.mtl"), "newmtl floor\nillum 2\nKd 0.5 0.5 0.5\n"
              "newmtl back\nillum 2\nKd 0.3 0.35 0.45\nnewmtl glass\nillum 2\nKd 0.5 0.5 0.5\n"
              + MTL_LIGHT.format(4))
    room = mat.Obj("liquid.mtl")
    mat.add_floor(room, "floor", 2.5)
    room.face("back", [[-2.5, 0, -1.5], [2.5, 0, -1.5], [2.5, 2.5, -1.5], [-2.5, 2.5, -1.5]])
    # Large: light reaches the liquid's inside only through paths that leave the dielectric and
    # hit it (no next-event estimation through a refracting surface, in either renderer).
    mat.add_light(room, (-0.4, 0.5), 1.0, 3.0)
    room.write(os.path.join(out, "room.obj"))
    glass = mat.Obj("liquid.mtl")
    add_cylinder(glass, "glass", [0.0, 0.002, 0.0], 0.45, 1.0)
    glass.write(os.path.join(out, "glass.obj"))
    base.write_scene_json(os.path.join(out, "scene.json"), {
        "camera": CAMERA, "film": {"width": 64, "height": 64}, "render": {"spp": 64, "max_depth": 16},
        "media": {"juice": {"type": "homogeneous", "sigma_a": [0.15, 0.7, 2.0],
                            "sigma_s": [2.2, 1.6, 1.0], "g": 0.2},
                  "haze": {"type": "homogeneous", "sigma_a": 0.02, "sigma_s": 0.08, "g": -0.2}},
        "medium": "haze",
        "materials": {"liquid": {"type": "dielectric", "ior": 1.33}},
        "objects": [{"obj": "room.obj"},
                    {"obj": "glass.obj", "material": "liquid", "interior": "juice"}]})


def write_subsurface(out):
    os.makedirs(out, exist_ok=True)
    write_mtl(os.path.join(out, "subsurface.mtl"), "newmtl floor\nillum 2\nKd 0.5 0.5 0.5\n"
              "newmtl skin\nillum 2\nKd 0.5 0.5 0.5\n" + MTL_LIGHT.format(5))
    room = mat.Obj("subsurface.mtl")
    mat.add_floor(room, "floor", 2.5)
    mat.add_light(room, (0.6, 0.4), 0.8, 2.6)  # large, and a bright sky: as in liquid/
    room.write(os.path.join(out, "room.obj"))
    sphere = mat.Obj("subsurface.mtl")
    mat.add_icosphere(sphere, "skin", [0.0, 0.62, 0.0], 0.6)
    sphere.write(os.path.join(out, "sphere.obj"))
    base.write_scene_json(os.path.join(out, "scene.json"), {
        "camera": CAMERA, "film": {"width": 64, "height": 64}, "render": {"spp": 64, "max_depth": 32},
        "media": {"skin": {"type": "homogeneous", "sigma_a": [0.08, 0.35, 0.8],
                           "sigma_s": [3.0, 3.6, 4.2], "g": 0.0}},
        "materials": {"skin": {"type": "dielectric", "ior": 1.4}},
        "background": [0.4, 0.4, 0.45],
        "objects": [{"obj": "room.obj"},
                    {"obj": "sphere.obj", "material": "skin", "interior": "skin"}]})


WRITERS = {"fog-room": write_fog_room, "smoke": write_smoke, "liquid": write_liquid,
           "subsurface": write_subsurface}
# What git does not keep (generated at make time); the rest (scene.json, MTL) is committed.
GENERATED = {"fog-room": ("room.obj", "fog.obj"), "smoke": ("floor.obj", "box.obj", "smoke.vol", "sky.hdr"),
             "liquid": ("room.obj", "glass.obj"), "subsurface": ("room.obj", "sphere.obj")}
CLOSED = {"fog-room": ("fog.obj", 2.9 * 1.98 * 2.9), "smoke": ("box.obj", 1.3 * 1.29 * 1.3),
          "liquid": ("glass.obj", None),
          "subsurface": ("sphere.obj", None)}


def write_all(out):
    """Writes every media scene under out/ and checks the meshes; returns the scene names."""
    for name, writer in WRITERS.items():
        writer(os.path.join(out, name))
        for f in GENERATED[name]:
            if f.endswith(".obj"):
                base.check_obj(os.path.join(out, name, f), down_facing=("light",))
        if name in CLOSED:  # the medium's boundary: closed and wound outward
            f, expected = CLOSED[name]
            (g,) = base.check_obj(os.path.join(out, name, f))
            volume = base.signed_volume(g)
            assert volume > 0, f"{name}/{f}: wound inward"
            assert expected is None or abs(volume - expected) < 1e-3, f"{name}/{f}: volume {volume}"
    return list(WRITERS)


def write_generated(scenes_dir):
    """Writes the GENERATED files into scenes_dir (through a scratch copy, so the checks are
    write_all's); a file already equal is left alone, so make sees nothing new."""
    with tempfile.TemporaryDirectory(prefix="pt-media-") as scratch:
        write_all(scratch)
        mat.copy_changed(scratch, scenes_dir, [os.path.join(name, f) for name, files in GENERATED.items()
                                               for f in files])

if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    write_generated(sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "tests", "scenes"))
