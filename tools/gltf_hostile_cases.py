# SPDX-License-Identifier: MIT
"""gltf_hostile_cases.py: hostile variants of make_gltf_tests.py's features scene (issue 42): each
once made the sanitizers report, hung, or was accepted silently. Like gltf_bad_cases.py: [(file
name, {file: bytes or text}, text the one-line error must contain)], each beside features.bin;
tests/test_io_gltf.c loads them through bad/cases.txt and tests/fuzz/corpus_gltf.py replays them
on the ASan build."""
import json
import struct

from gltf_writer import UBYTE, UINT, glb, with_buffer

DEEP = 100000  # levels of nested arrays: a recursive JSON walk overflows the stack


def hostile_variants(doc, binary):
    def variant(change):
        d = with_buffer(doc, "features.bin", len(binary))
        change(d)
        return json.dumps(d)

    def image_in_view(offset, length):
        def change(d):
            d["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": length})
            d["images"] = [{"bufferView": len(d["bufferViews"]) - 1, "mimeType": "image/png"}]
            d["textures"] = [{"source": 0}]
            d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        return change

    def texture(index, where):
        def change(d):
            d["images"] = [{"uri": "none.png"}]
            d["textures"] = [{"source": 0}]
            m = d["materials"][0]
            if where == "base":
                m["pbrMetallicRoughness"]["baseColorTexture"] = {"index": index}
            else:
                d["extensionsUsed"].append("KHR_materials_specular")
                m.setdefault("extensions", {})["KHR_materials_specular"] = {"specularTexture": {"index": index}}
        return change

    def first_accessor_count(count):
        return lambda d: d["accessors"][d["meshes"][0]["primitives"][0]["indices"]].update(count=count)

    def sparse_index(d):
        a = next(a for a in d["accessors"] if "sparse" in a)
        # the sparse index view (one UNSIGNED_BYTE) re-pointed at 4 bytes of 0xff as UNSIGNED_INT
        d["bufferViews"].append({"buffer": 0, "byteOffset": len(binary), "byteLength": 4})
        a["sparse"]["indices"] = {"bufferView": len(d["bufferViews"]) - 1, "componentType": UINT}
    big = bytes(binary) + b"\xff\xff\xff\xff\0"

    deep = json.dumps(with_buffer(doc, "features.bin", len(binary)))
    deep = deep.replace('"asset": {', '"asset": {"extras": ' + "[" * DEEP + "]" * DEEP + ", ", 1)
    cases = [
        ("deep_extras.gltf", deep, "nested more than 1000"),
        ("image_view_beyond.gltf", variant(image_in_view(len(binary) - 4, 4096)), "images[0].bufferView"),
        ("image_view_offset.gltf", variant(image_in_view(1 << 30, 16)), "images[0].bufferView"),
        ("count_zero.gltf", variant(first_accessor_count(0)), "meshes[0].primitives[0].indices"),
        ("texture_index_max.gltf", variant(texture(2 ** 31 - 1, "base")), "baseColorTexture"),
        ("texture_index_ext.gltf", variant(texture(2 ** 31, "ext")), "specularTexture.index"),
        ("texture_index_huge.gltf", variant(texture(2 ** 40, "base")),
         "baseColorTexture.index = 1099511627776"),
        ("buffer_folder.gltf", variant(lambda d: d["buffers"][0].update(uri=".")), "is a directory"),
        ("buffer_escapes.gltf", variant(lambda d: d["buffers"][0].update(uri="../../../../../../etc/hostname")),
         "buffers[0].uri"),
        ("image_absolute.gltf", variant(lambda d: d.update(images=[{"uri": "/etc/hostname"}])), "images[0].uri"),
        ("image_escapes.gltf", variant(lambda d: d.update(images=[{"uri": "a/%2E%2E/../../x.png"}])),
         "images[0].uri"),
        ("empty.glb", b"", "empty file"),
        ("huge_matrix.gltf", variant(lambda d: d["nodes"][5].update(matrix=[1e308, 0, 0, 0, 0, 1e308, 0, 0,
                                                                         0, 0, 1e308, 0, 0, 0, 0, 1])),
         "nodes[5]: its world matrix has an entry of 1e+308"),
        ("huge_scale.gltf", variant(lambda d: d["nodes"][6].update(scale=[1e300] * 3)),
         "nodes[6]: its world matrix has an entry of"),
    ]
    out = [(name, {name: data, "features.bin": binary}, expect) for name, data, expect in cases]
    d = with_buffer(doc, "big.bin", len(big))
    sparse_index(d)
    out.append(("sparse_index_max.gltf", {"sparse_index_max.gltf": json.dumps(d), "big.bin": big},
                "sparse.indices"))
    # The strip's UNSIGNED_INT indices with a sparse value of 2^32 - 1 (as a float it was 2^32,
    # converted to index 0: a silently wrong triangle).
    d = with_buffer(doc, "big.bin", len(big))
    strip = d["meshes"][2]["primitives"][0]["indices"]
    d["bufferViews"].append({"buffer": 0, "byteOffset": len(binary), "byteLength": 4})  # 2^32 - 1
    d["bufferViews"].append({"buffer": 0, "byteOffset": len(binary) + 4, "byteLength": 1})  # index 0
    d["accessors"][strip]["sparse"] = {"count": 1, "indices": {"bufferView": len(d["bufferViews"]) - 1,
                                                               "componentType": UBYTE},
                                       "values": {"bufferView": len(d["bufferViews"]) - 2}}
    out.append(("sparse_value_max.gltf", {"sparse_value_max.gltf": json.dumps(d), "big.bin": big},
                "meshes[2].primitives[0].indices: index 4294967295"))
    return out


def many(kind, n):
    """A GLB of one triangle in one mesh placed n times ("nodes"), or of one mesh of n primitives
    sharing the triangle's accessor ("primitives"): 10^5 of either took minutes to load (a
    realloc per object copied O(n^2) bytes)."""
    pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    doc = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(pos)}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 1, 0]}]}
    prims = n if kind == "primitives" else 1
    doc["meshes"] = [{"primitives": [{"attributes": {"POSITION": 0}}] * prims}]
    doc["nodes"] = ([{"mesh": 0, "translation": [i % 1000, i // 1000, 0]} for i in range(n)]
                    if kind == "nodes" else [{"mesh": 0}])
    doc["scenes"] = [{"nodes": list(range(len(doc["nodes"])))}]
    return glb(doc, pos)


if __name__ == "__main__":  # gltf_hostile_cases.py nodes|primitives N OUT.glb
    import sys
    with open(sys.argv[3], "wb") as f:
        f.write(many(sys.argv[1], int(sys.argv[2])))
