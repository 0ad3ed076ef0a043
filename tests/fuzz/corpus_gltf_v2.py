# SPDX-License-Identifier: MIT
"""Hostile glTF/GLB cases (issue 42), beside corpus_gltf.py's: every accessor field, strides and
sparse fields with odd values, huge counts, int-typed keys out of range, lying GLB containers,
URIs that escape, name special files or lie about their data, cyclic and deep node graphs,
required extensions, primitive modes and the features pt drops with a warning. Each must end in
exit 0 or one "pt: ..." line; those with a needle are one-line errors naming it. Files are GLBs
(x.glb) where they can be, so that they also seed the libFuzzer target.
"""
import json
import os
import sys

from corpus_cases import TINY, case

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
import make_gltf_tests as gen  # noqa: E402
from gltf_hostile_cases import many  # noqa: E402

COLD = 900  # a case that renders may compile kernels cold under ASan
ODD = [0, -1, 2 ** 31, 2 ** 32 - 1, 1.5, None]


def gltf_v2_cases():
    doc, binary, _ = gen.features()

    def glb_case(name, change=None, expect="any", needle=None, d=None, bin_=None, timeout=COLD):
        d = d if d is not None else gen.with_buffer(doc, None, len(binary))
        if change:
            change(d)
        data = gen.glb(d, binary if bin_ is None else bin_)
        case("gltf-v2-" + name, {"x.glb": data}, ["render", "x.glb"] + TINY, expect, needle=needle,
             timeout=timeout)

    def gltf_case(name, change, expect="any", needle=None, extra=None, setup=None):
        d = gen.with_buffer(doc, "features.bin", len(binary))
        change(d)
        files = {"x.gltf": json.dumps(d), "features.bin": binary}
        files.update(extra or {})
        case("gltf-v2-" + name, files, ["render", "x.gltf"] + TINY, expect, needle=needle,
             setup=setup, timeout=COLD)

    def setter(path, value):
        def change(d):
            target = d
            for key in path[:-1]:
                target = target[key]
            target[path[-1]] = value
        return change

    # Accessors: every field of accessors[0] (POSITION of the box) and [1] (its indices).
    for acc in (0, 1):
        for key in ("count", "byteOffset", "componentType", "bufferView"):
            for i, value in enumerate(ODD):
                glb_case("accessor%d-%s-%d" % (acc, key, i), setter(["accessors", acc, key], value))
        for value in ("SCALAR", "VEC2", "VEC4", "MAT4", "VEC5", 3):
            glb_case("accessor%d-type-%s" % (acc, value), setter(["accessors", acc, "type"], value))
        glb_case("accessor%d-normalized" % acc, setter(["accessors", acc, "normalized"], True))
    # Strides: the interleaved view (bufferViews of mesh 2) and a plain one.
    strided = next(i for i, v in enumerate(doc["bufferViews"]) if "byteStride" in v)
    for view in (strided, 0):
        for value in (1, 4, 256, 2 ** 31, -4):
            glb_case("stride-view%d-%s" % (view, value), setter(["bufferViews", view, "byteStride"], value))
        for key in ("byteOffset", "byteLength", "buffer"):
            for i, value in enumerate([-1, 2 ** 32 + 4, len(binary) + 1]):
                glb_case("view%d-%s-%d" % (view, key, i), setter(["bufferViews", view, key], value))
    # Sparse: the BYTE accessor with a sparse substitution.
    sparse = next(i for i, a in enumerate(doc["accessors"]) if "sparse" in a)
    for key, values in [("count", [0, -1, 2, 2 ** 31, 1000]),
                        (("indices", "componentType"), [5120, 5122, 5126, 5125, 0]),
                        (("indices", "byteOffset"), [-1, 2 ** 31 - 1, 1]),
                        (("values", "byteOffset"), [-1, 2 ** 31 - 1]),
                        (("indices", "bufferView"), [-1, 99]), (("values", "bufferView"), [-1, 99])]:
        path = ["accessors", sparse, "sparse"] + ([key] if isinstance(key, str) else list(key))
        for value in values:
            glb_case("sparse-%s-%s" % ("-".join(path[3:]), value), setter(path, value))
    # Huge counts: on no buffer view (zeros cost memory, not file bytes) and on a view.
    for count in (2 ** 24, 2 ** 24 + 1, 2 ** 28, 2 ** 28 + 1, 2 ** 32, 2 ** 62):
        glb_case("huge-count-%d" % count, lambda d, c=count: d["accessors"][0].update(count=c) or
                 d["accessors"][0].pop("bufferView"))
        glb_case("huge-count-view-%d" % count, setter(["accessors", 0, "count"], count))
    # Int-typed keys out of range (tinygltf converts them unchecked).
    for name, path in [("node-mesh", ["nodes", 1, "mesh"]), ("node-camera", ["nodes", 9, "camera"]),
                       ("node-child", ["nodes", 0, "children", 0]), ("scene", ["scene"]),
                       ("scene-node", ["scenes", 0, "nodes", 0]),
                       ("material", ["meshes", 0, "primitives", 0, "material"]),
                       ("indices", ["meshes", 0, "primitives", 0, "indices"]),
                       ("position", ["meshes", 0, "primitives", 0, "attributes", "POSITION"]),
                       ("mode", ["meshes", 0, "primitives", 0, "mode"])]:
        for value in (-2, 2 ** 31, 2 ** 40, 0.5):
            glb_case("int-%s-%s" % (name, value), setter(path, value), "error", needle="is not an index"
                     if value != -2 or name in ("node-child", "scene-node") else None)
    # Primitive modes: POINTS and LINES are skipped (the others of the file render), 7+ refused.
    for mode in range(9):
        glb_case("mode-%d" % mode, setter(["meshes", 0, "primitives", 0, "mode"], mode),
                 "error" if mode > 6 else "ok", needle="mode" if mode > 6 else None)
    glb_case("mode-all-points", lambda d: [p.update(mode=0) for m in d["meshes"] for p in m["primitives"]],
             "error", needle="pt renders triangles")
    # Node graphs: cycles, shared children, deep chains.
    glb_case("cycle-self", lambda d: d["nodes"][5].update(children=[5]), "error", needle="nodes[5]")
    glb_case("cycle-two", lambda d: (d["nodes"][5].update(children=[6]), d["nodes"][6].update(children=[5])),
             "error", needle="reached twice")
    glb_case("shared-child", lambda d: d["nodes"][5].update(children=[1]), "error", needle="reached twice")
    glb_case("scene-twice", lambda d: d["scenes"][0]["nodes"].append(5), "error", needle="reached twice")
    glb_case("no-scenes", lambda d: (d.pop("scenes"), d.pop("scene")), "ok")
    glb_case("scene-missing", setter(["scene"], 7), "error", needle="scenes[7]")

    def chain(n):
        def change(d):
            first = len(d["nodes"])
            d["nodes"] += [{"children": [first + i + 1]} for i in range(n - 1)] + [{"mesh": 0}]
            d["scenes"][0]["nodes"].append(first)
        return change
    glb_case("chain-900", chain(900), "ok")
    glb_case("chain-1100", chain(1100), "error", needle="nested more than 1000")
    # Required and used extensions.
    # KHR_draco_mesh_compression is read (io/gltf_draco.cc): required, it refuses nothing.
    glb_case("required-KHR_draco_mesh_compression",
             lambda d: d["extensionsRequired"].append("KHR_draco_mesh_compression"), "ok")
    for ext in ("EXT_meshopt_compression", "KHR_texture_basisu",
                "KHR_materials_clearcoat", "", "x" * 300):
        glb_case("required-%s" % ext[:40], lambda d, e=ext: d["extensionsRequired"].append(e),
                 "error", needle="extensionsRequired")
        glb_case("used-%s" % ext[:40], lambda d, e=ext: d["extensionsUsed"].append(e), "ok")
    glb_case("required-not-array", setter(["extensionsRequired"], "KHR_mesh_quantization"))
    glb_case("required-numbers", setter(["extensionsRequired"], [1, 2]))
    # Dropped features: one warning each, the rest renders.
    glb_case("skins", setter(["skins"], [{"joints": [1, 2]}]), "ok")
    glb_case("animations", setter(["animations"], [{"channels": [], "samplers": []}]), "ok")
    glb_case("morph", lambda d: d["meshes"][0].update(weights=[0.5]), "ok")
    glb_case("orthographic", lambda d: d["cameras"].append(
        {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 9}}), "ok")
    # Lying GLB containers.
    good = gen.glb(gen.with_buffer(doc, None, len(binary)), binary)
    import struct
    for name, data, needle in [
            ("glb-empty", b"", "empty file"), ("glb-magic-only", b"glTF", "truncated GLB"),
            ("glb-header-only", struct.pack("<4sII", b"glTF", 2, 12), "truncated GLB"),
            ("glb-header-only-padded", struct.pack("<4sII", b"glTF", 2, 12) + bytes(8), "JSON chunk"),
            ("glb-version-1", good[:4] + struct.pack("<I", 1) + good[8:], "version 1"),
            ("glb-length-short", good[:8] + struct.pack("<I", 19) + good[12:], None),
            ("glb-length-huge", good[:8] + struct.pack("<I", 2 ** 32 - 1) + good[12:], "truncated GLB"),
            ("glb-json-chunk-huge", good[:12] + struct.pack("<I", 2 ** 31) + good[16:], "truncated GLB"),
            ("glb-json-chunk-zero", good[:12] + struct.pack("<I", 0) + good[16:], None),
            ("glb-first-chunk-bin", good[:16] + b"BIN\0" + good[20:], "not JSON"),
            ("glb-no-bin", good[:12 + 8 + struct.unpack("<I", good[12:16])[0]], None),
            ("glb-bin-short", good[:-40], "truncated GLB"),
            ("glb-deep", good[:20] + b"[" * 5000 + good[20 + 5000:], "nested more than 1000"),
            ("glb-nul-json", good[:20] + b"\0" * 8 + good[28:], None)]:
        case("gltf-v2-" + name, {"x.glb": data}, ["render", "x.glb"] + TINY,
             "error" if needle or name != "glb-length-short" else "any", needle=needle)
    # URIs: escaping, special files, lying data URIs.
    for i, uri in enumerate(["../features.bin", "/etc/hostname", "a/../../features.bin",
                             "%2E%2E/features.bin", "/dev/zero", "//etc/passwd"]):
        gltf_case("uri-escapes-%d" % i, setter(["buffers", 0, "uri"], uri), "error", needle="buffers[0].uri")
        gltf_case("image-uri-escapes-%d" % i, setter(["images"], [{"uri": uri}]), "error",
                  needle="images[0].uri")
    for name, uri, needle in [("folder", ".", "buffers[0].uri"), ("sub-folder", "sub", "buffers[0].uri"),
                              ("empty", "", None), ("missing", "none.bin", "buffers[0].uri"),
                              ("nul", "features.bin%00x", "NUL byte"), ("long", "a" * 5000, None),
                              ("data-bad-base64", "data:application/octet-stream;base64,!!!!", None),
                              ("data-short", gen.data_uri(binary[:100]), None),
                              ("data-no-comma", "data:application/octet-stream;base64", None)]:
        gltf_case("uri-" + name, setter(["buffers", 0, "uri"], uri), "error", needle=needle,
                  setup="mkdir sub" if name == "sub-folder" else None)
    gltf_case("uri-fifo", setter(["buffers", 0, "uri"], "pipe.bin"), "error", needle="buffers[0].uri",
              setup="mkfifo pipe.bin")
    gltf_case("uri-dev-link", setter(["buffers", 0, "uri"], "zero.bin"), "error", needle="buffers[0].uri",
              setup="ln -s /dev/zero zero.bin")

    def textured_by(uri):
        def change(d):
            d["images"] = [{"uri": uri}]
            d["textures"] = [{"source": 0}]
            d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        return change
    gltf_case("image-fifo", textured_by("pipe.png"), "error", needle="pipe.png", setup="mkfifo pipe.png")
    gltf_case("image-folder", textured_by("sub"), "error", needle="sub", setup="mkdir sub")
    gltf_case("image-missing", textured_by("none.png"), "error", needle="none.png")
    gltf_case("image-not-image", textured_by("features.bin"), "error", needle="images[0]")
    # Images in buffer views that lie.
    for i, (offset, length) in enumerate([(len(binary) - 4, 4096), (2 ** 30, 16), (0, 0),
                                          (len(binary), 1), (0, 2 ** 32 - 1)]):
        def image_view(d, o=offset, n=length):
            d["bufferViews"].append({"buffer": 0, "byteOffset": o, "byteLength": n})
            d["images"] = [{"bufferView": len(d["bufferViews"]) - 1, "mimeType": "image/png"}]
            d["textures"] = [{"source": 0}]
            d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        glb_case("image-view-%d" % i, image_view, "error")
    # Large but legal: 10^4 nodes and primitives (the 10^5 files are the unit test's).
    case("gltf-v2-many-nodes", {"x.glb": many("nodes", 10000)}, ["render", "x.glb"] + TINY, "ok",
         timeout=COLD)
    case("gltf-v2-many-primitives", {"x.glb": many("primitives", 10000)}, ["render", "x.glb"] + TINY,
         "ok", timeout=COLD)
