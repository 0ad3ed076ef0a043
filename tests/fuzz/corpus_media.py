# SPDX-License-Identifier: MIT
"""Media (issue 40, shared/DESIGN.md "Media"): a scene with every media key at once (a fog box
through an "interface", a .vol smoke grid, a subsurface cube, a world and a camera medium) renders;
then every number under "media" and the subsurface keys is replaced in turn by infinity,
-infinity, a negative and a huge value (each ending in exit 0 or one "pt: ..." line); then hostile
cases, each one line naming the key: unknown names, open meshes, interfaces with keys or in a mix,
black holes with media, too many media, and corrupt or lying .vol files; and Mitsuba 3 XML
media (host/scene/mitsuba_media.c): valid ones render, hostile ones are one line.
"""
import json
import struct

from corpus_cases import TINY, case
from corpus_mitsuba import mitsuba_case, scene as mitsuba_scene
from corpus_scene_v2 import BAD, leaves, with_text_at

CUBE = ("v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
        "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n")
OPEN = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"


def vol(res=(4, 4, 4), values=None, magic=b"VOL\x03", encoding=1, channels=1, truncate=None):
    """A Mitsuba 3 .vol grid (little-endian; header then float32 values, x fastest)."""
    n = res[0] * res[1] * res[2] * channels if values is None else len(values)
    values = [0.25 * (i % 5) for i in range(n)] if values is None else values
    data = (magic + struct.pack("<iiiii", encoding, res[0], res[1], res[2], channels) +
            struct.pack("<6f", 0, 0, 0, 1, 1, 1) + struct.pack("<%df" % len(values), *values))
    return data if truncate is None else data[:truncate]


def media_scene():
    return {
        "camera": {"eye": [0, 0, 6], "target": [0, 0, 0], "fov_y": 40, "medium": "air"},
        "film": {"width": 8, "height": 8},
        "render": {"spp": 1, "max_depth": 4},
        "background": [1, 1, 1],
        "media": {
            "air": {"type": "homogeneous", "sigma_s": 0.01, "scale": 1, "g": 0.1},
            "fog": {"type": "homogeneous", "sigma_a": [0.2, 0.3, 0.4], "sigma_s": 0.5, "g": 0.3,
                    "emission": [0.1, 0.1, 0.1]},
            "smoke": {"type": "grid", "file": "smoke.vol", "grid": "density", "density_scale": 2,
                      "sigma_t": [1, 2, 3], "albedo": [0.8, 0.8, 0.8], "g": -0.2,
                      "emission": 0, "transform": [{"scale": 2}, {"translate": [-1, -1, -1]}]}},
        "medium": "air",
        "materials": {"box": {"type": "interface"},
                      "skin": {"type": "principled", "base_color": [0.8, 0.5, 0.3],
                               "subsurface": 0.8, "subsurface_radius": [0.5, 0.2, 0.1]}},
        "objects": [
            {"obj": "cube.obj", "material": "box", "interior": "fog", "exterior": "air"},
            {"obj": "cube.obj", "material": "box", "interior": "smoke",
             "transform": [{"translate": [3, 0, 0]}]},
            {"obj": "cube.obj", "material": "skin", "transform": [{"translate": [-3, 0, 0]}]}],
    }


def media_case(name, scene, expect="any", needle=None, files=None):
    text = scene if isinstance(scene, str) else json.dumps(scene)
    inputs = {"cube.obj": CUBE, "open.obj": OPEN, "smoke.vol": vol(), "scene.json": text}
    inputs.update(files or {})
    case("json-media-" + name, inputs, ["render", "scene.json"] + TINY, expect, needle=needle,
         timeout=900)


def changed(change):
    scene = media_scene()
    change(scene)
    return scene


def media_cases():
    scene = media_scene()
    media_case("every-key", scene, "ok")
    # Every number under "media" and the subsurface keys, by each of BAD.
    paths = [p for p in leaves(scene)
             if p[0] == "media" or (p[0] == "materials" and p[2].startswith("subsurface"))]
    for path in paths:
        name = ".".join(str(k) for k in path)
        for label, text in BAD:
            media_case("%s=%s" % (name, label), with_text_at(scene, path, text))
    # Hostile values and names: one line naming the key.
    hostile = [
        ("g-one", lambda s: s["media"]["fog"].update(g=1), "media.fog.g"),
        ("g-below", lambda s: s["media"]["fog"].update(g=-1.5), "media.fog.g"),
        ("sigma-negative", lambda s: s["media"]["fog"].update(sigma_a=[0.1, -1, 0]), "media.fog.sigma_a"),
        ("sigma-string", lambda s: s["media"]["fog"].update(sigma_s="thick"), "media.fog.sigma_s"),
        ("sigma-short", lambda s: s["media"]["fog"].update(sigma_s=[1, 2]), "media.fog.sigma_s"),
        ("scale-overflow", lambda s: s["media"]["fog"].update(sigma_s=1e30, scale=1e30), "media.fog.sigma_s"),
        ("unknown-key", lambda s: s["media"]["fog"].update(density=1), "media.fog.density"),
        ("grid-key-on-homogeneous", lambda s: s["media"]["fog"].update(file="x.vol"), "media.fog.file"),
        ("no-type", lambda s: s["media"]["fog"].pop("type"), "media.fog.type"),
        ("bad-type", lambda s: s["media"]["fog"].update(type="vdb"), "media.fog.type"),
        ("medium-not-object", lambda s: s["media"].update(fog=[1]), "media.fog"),
        ("media-array", lambda s: s.update(media=[1]), "media"),
        ("long-name", lambda s: s["media"].update({"n" * 200: {"type": "homogeneous"}}), "media.nnnn"),
        ("albedo-over-one", lambda s: s["media"]["smoke"].update(albedo=1.5), "media.smoke.albedo"),
        ("density-scale-negative", lambda s: s["media"]["smoke"].update(density_scale=-1),
         "media.smoke.density_scale"),
        ("grid-no-file", lambda s: s["media"]["smoke"].pop("file"), "media.smoke.file"),
        ("grid-empty-file", lambda s: s["media"]["smoke"].update(file=""), "media.smoke.file"),
        ("grid-missing-file", lambda s: s["media"]["smoke"].update(file="nowhere.vol"), "media.smoke.file"),
        ("grid-folder", lambda s: s["media"]["smoke"].update(file="."), "media.smoke.file"),
        ("grid-name-absent", lambda s: s["media"]["smoke"].update(grid="temperature"), "media.smoke.grid"),
        ("grid-name-number", lambda s: s["media"]["smoke"].update(grid=3), "media.smoke.grid"),
        ("grid-singular", lambda s: s["media"]["smoke"].update(transform=[{"scale": [1, 0, 1]}]),
         "media.smoke.transform"),
        ("grid-obj-as-vol", lambda s: s["media"]["smoke"].update(file="cube.obj"), "media.smoke.file"),
        ("world-unknown", lambda s: s.update(medium="vacuum"), "medium"),
        ("world-number", lambda s: s.update(medium=1), "medium"),
        ("camera-unknown", lambda s: s["camera"].update(medium="vacuum"), "camera.medium"),
        ("interior-unknown", lambda s: s["objects"][0].update(interior="vacuum"), "objects[0].interior"),
        ("exterior-array", lambda s: s["objects"][1].update(exterior=["fog"]), "objects[1].exterior"),
        ("interior-open-mesh", lambda s: s["objects"][0].update(obj="open.obj"), "not closed"),
        ("subsurface-open-mesh", lambda s: s["objects"][2].update(obj="open.obj"), "not closed"),
        ("interior-and-subsurface", lambda s: s["objects"][2].update(interior="fog"), "objects[2].interior"),
        ("interface-emits", lambda s: s["materials"]["box"].update(emission=1), "materials.box.emission"),
        ("interface-in-mix", lambda s: s["materials"].update(m={"type": "mix", "a": "skin", "b": "box"}),
         "materials.m.b"),
        ("subsurface-over-one", lambda s: s["materials"]["skin"].update(subsurface=2),
         "materials.skin.subsurface"),
        ("subsurface-radius-zero", lambda s: s["materials"]["skin"].update(subsurface_radius=0),
         "materials.skin.subsurface_radius"),
        ("black-hole", lambda s: s.update(black_holes=[{"position": [5, 5, 5], "mass": 0.05}]),
         "black_holes"),
    ]
    for name, change, needle in hostile:
        media_case(name, changed(change), "error", needle=needle)
    many = {"m%d" % i: {"type": "homogeneous"} for i in range(65536)}
    media_case("too-many", changed(lambda s: s.update(media=many)), "error", needle="media")
    # Corrupt and lying .vol files, named by the key that asked for them.
    for name, data in [("empty", b""), ("magic", vol(magic=b"VOX\x03")),
                       ("version", vol(magic=b"VOL\x02")), ("float16", vol(encoding=2)),
                       ("channels", vol(channels=3)), ("zero-res", vol(res=(0, 4, 4), values=[])),
                       ("negative-res", vol(res=(-4, 4, 4), values=[])),
                       ("huge-res", vol(res=(1 << 20, 1 << 20, 1 << 20), values=[1.0])),
                       ("truncated-header", vol(truncate=20)), ("truncated-values", vol(truncate=100)),
                       ("negative-density", vol(values=[-1.0] * 64)),
                       ("nan-density", vol(values=[float("nan")] * 64)),
                       ("inf-density", vol(values=[float("inf")] * 64))]:
        media_case("vol-" + name, scene, "error", needle="media.smoke.file",
                   files={"smoke.vol": data})


MI_FOG = ('<medium type="homogeneous" id="fog"><rgb name="sigma_t" value="1, 2, 3"/>'
          '<float name="albedo" value="0.8"/><phase type="hg"><float name="g" value="0.5"/></phase></medium>')
MI_SMOKE = ('<medium type="heterogeneous" id="smoke"><volume type="gridvolume" name="sigma_t">'
            '<string name="filename" value="smoke.vol"/>%s</volume><float name="scale" value="4"/></medium>')


def mi_cube(inside, bsdf='<bsdf type="null"/>', extra=""):
    return '<shape type="cube">%s<ref name="interior" id="%s"/>%s</shape>' % (bsdf, inside, extra)


def mitsuba_media_cases():
    vol_file = {"smoke.vol": vol()}
    valid = {
        "fog-cube": MI_FOG + mi_cube("fog"),
        "fog-glass-sphere": MI_FOG + '<shape type="sphere"><bsdf type="dielectric"/>'
                                     '<ref name="interior" id="fog"/></shape>',
        "smoke-unit-cube": (MI_SMOKE % "") + mi_cube("smoke"),
        "smoke-grid-bbox": (MI_SMOKE % '<boolean name="use_grid_bbox" value="true"/>') + mi_cube("smoke"),
        "nested-medium": '<shape type="cube"><bsdf type="null"/><medium type="homogeneous" '
                         'name="interior"/></shape>',
    }
    for name, body in valid.items():
        mitsuba_case("media-" + name, mitsuba_scene(body), "ok", extra=vol_file)
    hostile = [
        ("g-one", MI_FOG.replace('value="0.5"', 'value="1"') + mi_cube("fog"), "(-1, 1)"),
        ("albedo-two", MI_FOG.replace('value="0.8"', 'value="2"') + mi_cube("fog"), "albedo"),
        ("type", '<medium type="vdb" id="v"/>' + mi_cube("v"), "medium type"),
        ("ref-bsdf", '<bsdf type="diffuse" id="d"/>' + mi_cube("d"), "not a <medium>"),
        ("ref-missing", mi_cube("nowhere"), "nowhere"),
        ("vol-missing", MI_SMOKE.replace("smoke.vol", "none.vol") % "" + mi_cube("smoke"), "none.vol"),
        ("vol-outside", MI_SMOKE.replace("smoke.vol", "../../etc/passwd") % "" + mi_cube("smoke"),
         "leaves the scene's folder"),
        ("volume-type", MI_SMOKE.replace("gridvolume", "bitmap") % "" + mi_cube("smoke"), "volume type"),
        ("open-rectangle", MI_FOG + '<shape type="rectangle"><bsdf type="null"/>'
                                    '<ref name="interior" id="fog"/></shape>', "not closed"),
    ]
    for name, body, needle in hostile:
        mitsuba_case("media-" + name, mitsuba_scene(body), "error", needle=needle, extra=vol_file)
    for name, data in [("empty", b""), ("flat-box", vol()[:24] + struct.pack("<6f", 0, 0, 0, 1, 0, 1) + vol()[48:]),
                       ("nan-box", vol()[:24] + struct.pack("<6f", 0, 0, 0, float("nan"), 1, 1) + vol()[48:])]:
        mitsuba_case("media-vol-" + name, mitsuba_scene((MI_SMOKE % "") + mi_cube("smoke")), "error",
                     needle="smoke.vol", extra={"smoke.vol": data})
