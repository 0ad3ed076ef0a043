# SPDX-License-Identifier: MIT
"""Scene format v2 (issue 42): one scene that uses every v2 block at once (textures, every
material type and mix, lights of each type, an environment map, objects' transforms with motion,
the camera's shutter, a black hole with a disk) renders; then every number in it is replaced in
turn by one of infinity, -infinity, a negative, a huge value, a NaN-like string and null (in
rotation; the black hole's, the environment's and the shutter's by each of the first four),
each ending in exit 0 or one "pt: ..." line; and mix-material cycles and chains.
"""
import json

from corpus_cases import TINY, TRIANGLE, case
from corpus_images import hdr, png
from corpus_materials import UV_TRIANGLE, material_scene

BAD = [("inf", "1e999"), ("-inf", "-1e999"), ("neg", "-1"), ("huge", "1e300")]
ODD = [("nan", '"NaN"'), ("null", "null")]


def every_block_scene():
    scene = material_scene()
    scene["lights"] = [
        {"type": "point", "position": [0, 1, 0], "intensity": [1, 1, 1]},
        {"type": "spot", "position": [0, 1, 0], "intensity": 2, "direction": [0, -1, 0],
         "cone_angle": 40, "falloff_angle": 20},
        {"type": "directional", "direction": [1, -1, 0], "irradiance": [1, 1, 1]},
        {"type": "sun", "direction": [0, -1, 0], "irradiance": 3, "angle": 0.5}]
    scene["environment"] = {"file": "sky.hdr", "scale": 0.5}
    scene["camera"]["shutter"] = [0, 1]
    scene["objects"][1]["transform"] = [{"scale": 0.5}, {"rotate": {"axis": [0, 1, 0], "angle": 30}},
                                        {"translate": [0.3, 0, 0]}]
    scene["objects"][1]["transform_end"] = [{"translate": [0.4, 0, 0]}]
    scene["black_holes"] = [{"position": [0.3, 0.3, -1], "mass": 0.05, "disk": {
        "normal": [0, 1, 0.2], "inner_radius": 0.3, "outer_radius": 1.0, "emission": [2, 1, 0.5],
        "temperature": 6000, "opacity": 0.7, "noise": {"frequency": 2, "octaves": 3, "swirl": 4}}}]
    return scene


def leaves(node, path=()):
    """Every number in the tree with its path (list indices as ints)."""
    if isinstance(node, bool):
        return
    if isinstance(node, (int, float)):
        yield path
    elif isinstance(node, dict):
        for k, v in node.items():
            yield from leaves(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaves(v, path + (i,))


MARK = 987654.321  # stands for the substituted JSON text (json.dumps cannot write 1e999)


def with_text_at(scene, path, text):
    s = json.loads(json.dumps(scene))
    target = s
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = MARK
    return json.dumps(s).replace(repr(MARK), text)


def scene_v2_case(name, text, expect="any", needle=None):
    files = {"tri.obj": TRIANGLE, "uv.obj": UV_TRIANGLE, "t.png": png(4, 4), "t.hdr": hdr(8, 4),
             "sky.hdr": hdr(16, 8), "scene.json": text}
    case("json-v2-" + name, files, ["render", "scene.json"] + TINY, expect, needle=needle, timeout=900)


def scene_v2_cases():
    scene = every_block_scene()
    scene_v2_case("every-block", json.dumps(scene), "ok")
    skip = ("film", "render")  # v1 keys, covered by corpus_scene.py
    paths = [p for p in leaves(scene) if p[0] not in skip]
    for n, path in enumerate(paths):
        name = ".".join(str(k) for k in path)
        every = path[0] in ("black_holes", "environment") or path[-2:-1] == ("shutter",)
        for label, text in BAD if every else [(BAD + ODD)[n % 6]]:
            scene_v2_case("%s=%s" % (name, label), with_text_at(scene, path, text))
    # Mix materials: cycles, self-reference, a long chain, a missing part.
    for name, materials, needle in [
            ("self", {"m": {"type": "mix", "a": "m", "b": "m", "weight": 0.5}}, "materials.m"),
            ("cycle-2", {"m": {"type": "mix", "a": "n", "b": "n", "weight": 0.5},
                         "n": {"type": "mix", "a": "m", "b": "m", "weight": 0.5}}, "materials."),
            ("missing", {"m": {"type": "mix", "a": "nowhere", "b": "nowhere", "weight": 0.5}}, "nowhere"),
            ("weight-texture-missing", {"d": {"type": "diffuse"},
                                        "m": {"type": "mix", "a": "d", "b": "d", "weight": "nope"}}, "nope")]:
        s = material_scene(materials=materials, objects=[{"obj": "tri.obj", "material": "m"}])
        scene_v2_case("mix-" + name, json.dumps(s), "error", needle=needle)
    chain = {"m0": {"type": "diffuse"}}
    for i in range(1, 200):
        chain["m%d" % i] = {"type": "mix", "a": "m%d" % (i - 1), "b": "m0", "weight": 0.5}
    s = material_scene(materials=chain, objects=[{"obj": "tri.obj", "material": "m199"}])
    scene_v2_case("mix-chain-200", json.dumps(s))
