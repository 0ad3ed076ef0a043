# SPDX-License-Identifier: MIT
"""gltf_bad_cases.py: broken variants of make_gltf_tests.py's features scene, each with the text
its one-line error must contain (tests/test_io_gltf.c reads bad/cases.txt; tests/fuzz/corpus_gltf.py
replays them)."""
import json
import os
import struct

from gltf_hostile_cases import hostile_variants
from gltf_writer import glb, with_buffer, write


def bad_variants(doc, binary):
    """Broken variants of the features scene: [(file name, {file: bytes or text}, text the error
    must contain)], each beside features.bin."""
    def variant(change):
        d = with_buffer(doc, "features.bin", len(binary))
        change(d)
        return json.dumps(d)
    cases = [
        ("truncated.glb", glb(with_buffer(doc, None, len(binary)), binary)[:-40], "truncated GLB"),
        ("missing_bin.gltf", variant(lambda d: d["buffers"][0].update(uri="nowhere.bin")),
         "buffers[0].uri"),
        ("accessor_range.gltf", variant(lambda d: d["accessors"][0].update(count=1000)),
         "meshes[0].primitives[0].attributes.POSITION: accessors[0]"),
        ("view_range.gltf", variant(lambda d: d["bufferViews"][0].update(byteLength=100000)),
         "bufferViews[0]"),
        ("index_range.gltf",  # the quad's 4 vertices indexed by the strip's indices (up to 5)
         variant(lambda d: d["meshes"][1]["primitives"][0].update(indices=d["meshes"][2]["primitives"][0]["indices"])),
         "meshes[1].primitives[0].indices: index 5"),
        ("inf_matrix.gltf",  # JSON has no infinity: scales of 1e300 under 1e300 overflow
         variant(lambda d: (d["nodes"][0].update(scale=[1e300] * 3), d["nodes"][2].update(scale=[1e300] * 3))),
         "nodes[1]: its world matrix"),  # nodes[1] (1e300 x 0.5) is met first
        ("lines.gltf",  # every primitive LINES (one of several is skipped with a warning)
         variant(lambda d: [p.update(mode=1) for m in d["meshes"] for p in m["primitives"]]),
         "meshes[0].primitives[0].mode: LINES"),
        ("required_ext.gltf", variant(lambda d: d["extensionsRequired"].append("EXT_meshopt_compression")),
         "EXT_meshopt_compression"),
        ("cycle.gltf", variant(lambda d: d["nodes"][4].update(children=[2])), "nodes[2]"),
        ("bad_material.gltf", variant(lambda d: d["meshes"][0]["primitives"][0].update(material=9)),
         "meshes[0].primitives[0].material"),
        ("sparse_range.gltf", variant(lambda d: next(a for a in d["accessors"] if "sparse" in a)
                                      ["sparse"]["indices"].update(byteOffset=400)), "sparse"),
        ("no_position.gltf", variant(lambda d: d["meshes"][5]["primitives"][0]["attributes"].pop("POSITION")),
         "meshes[5].primitives[0].attributes.POSITION"),
        ("not_json.gltf", "{\"asset\": ", "not_json.gltf"),
    ]
    out = [(name, {name: data, "features.bin": binary}, expect) for name, data, expect in cases]
    # A NaN vertex: the lamp's first position.
    nan_bin = bytearray(binary)
    lamp_pos = doc["accessors"][doc["meshes"][5]["primitives"][0]["attributes"]["POSITION"]]
    struct.pack_into("<f", nan_bin, doc["bufferViews"][lamp_pos["bufferView"]]["byteOffset"], float("nan"))
    out.append(("nan_vertex.gltf", {"nan_vertex.gltf": json.dumps(with_buffer(doc, "nan.bin", len(binary))),
                                    "nan.bin": bytes(nan_bin)},
                "meshes[5].primitives[0].attributes.POSITION"))
    return out + hostile_variants(doc, binary)


def write_bad_cases(out, doc, binary):
    os.makedirs(os.path.join(out, "bad"), exist_ok=True)
    with open(os.path.join(out, "bad", "cases.txt"), "w") as f:
        for name, files, expect in bad_variants(doc, binary):
            for fname, data in files.items():
                write(os.path.join(out, "bad", fname), data)
            f.write("%s\t%s\n" % (name, expect))
