# SPDX-License-Identifier: MIT
"""Cases for the glTF import (host/io/gltf_loader.cc, gltf_primitives.cc, gltf_scene_graph.cc,
host/scene/gltf_scene.c): the generator's valid files (tools/make_gltf_tests.py: .gltf + .bin,
.glb, data URIs), its broken variants (each a one-line error naming the file and the JSON path),
seeded byte flips of the GLB and value changes of the JSON (any outcome but a crash or hang), and
scenes naming glTF files with "gltf".
"""
import json
import os
import sys

from corpus_cases import BASE_SCENE, TINY, case

# A case that renders may be the first to need the program of a scene with instances and analytic
# lights: a cold kernel compile under ASan on a loaded machine can take minutes.
COLD = 900

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import make_gltf_tests as gen  # noqa: E402


def gltf_cases(rng):
    doc, binary, _ = gen.features()
    gltf = json.dumps(gen.with_buffer(doc, "features.bin", len(binary)))
    glb = gen.glb(gen.with_buffer(doc, None, len(binary)), binary)
    embedded = json.dumps(gen.with_buffer(doc, gen.data_uri(binary), len(binary)))
    for name, files, arg in [("gltf", {"x.gltf": gltf, "features.bin": binary}, "x.gltf"),
                             ("glb", {"x.glb": glb}, "x.glb"),
                             ("embedded", {"x.gltf": embedded}, "x.gltf")]:
        case("gltf-" + name, files, ["render", arg] + TINY, "ok", timeout=COLD)
    for name, files, needle in gen.bad_variants(doc, binary):
        case("gltf-bad-" + name, files, ["render", name] + TINY, "error", needle=needle)
    for i in range(24):  # byte flips of the GLB, its header and JSON chunk most often
        data = bytearray(glb)
        for _ in range(rng.randint(1, 8)):
            at = rng.randrange(min(len(data), 64)) if rng.random() < 0.3 else rng.randrange(len(data))
            data[at] = rng.randrange(256)
        case("gltf-flip-%02d" % i, {"x.glb": bytes(data)}, ["render", "x.glb"] + TINY, "any", timeout=COLD)
    values = [-1, 0, 3, 255, 65536, 2 ** 31, 2 ** 32 + 1, -2 ** 40, 1e300, 0.5, "x", None, [], {}]
    for i in range(24):  # one JSON value somewhere replaced by an odd one
        d = gen.with_buffer(doc, "features.bin", len(binary))
        section = rng.choice(["accessors", "bufferViews", "nodes", "meshes", "materials"])
        item = rng.choice(d[section])
        key = rng.choice(sorted(item))
        item[key] = rng.choice(values)
        case("gltf-value-%02d-%s-%s" % (i, section, key), {"x.gltf": json.dumps(d), "features.bin": binary},
             ["render", "x.gltf"] + TINY, "any", timeout=COLD)
    scene = json.loads(json.dumps(BASE_SCENE))
    for name, obj, expect, needle in [
            ("valid", {"gltf": "x.glb", "transform": [{"scale": 0.5}]}, "ok", None),
            ("material", {"gltf": "x.glb", "material": "nope"}, "error", "objects[0].material"),
            ("both", {"gltf": "x.glb", "obj": "tri.obj"}, "error", "objects[0]"),
            ("not-gltf", {"gltf": "tri.obj"}, "error", "tri.obj"),
            ("missing", {"gltf": "none.glb"}, "error", "none.glb")]:
        scene["objects"] = [obj]
        case("json-gltf-" + name, {"x.glb": glb, "tri.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                                   "scene.json": json.dumps(scene)},
             ["render", "scene.json"] + TINY, expect, needle=needle, timeout=COLD)
