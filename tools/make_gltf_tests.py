#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""make_gltf_tests.py OUT_DIR: the glTF files of tests/test_io_gltf.c, written with the standard
library only (json, struct, base64: CI has no pip), and their equivalent JSON + OBJ scene.

features.gltf + features.bin, features.glb and features_embedded.gltf (base64 data URIs) hold one
scene covering: nested node transforms (TRS and column-major matrices, a mirroring scale), a mesh
placed by 3 nodes, every accessor component type (BYTE..FLOAT, normalized and not, with
KHR_mesh_quantization), an interleaved buffer view (byteStride), sparse accessors (on a buffer
view and on none), strips and fans, a mesh of two primitives, a primitive without material, an
emissive material, a perspective camera and a KHR_lights_punctual point light.
reference.json + reference_<material>.obj: the same triangles in world space, decoded and
transformed here, one OBJ per material. bad/: broken files, listed in bad/cases.txt as
"file<TAB>text the error must contain". big.glb (--big N): N triangles, for tools/gltf_import_time.
"""
import base64
import json
import math
import os
import struct
import sys

from gltf_bad_cases import bad_variants, write_bad_cases  # noqa: F401 (corpus_gltf uses them)
from gltf_writer import (FLOAT, BYTE, UBYTE, SHORT, USHORT, UINT, Builder, data_uri,  # noqa: F401
                         decoded, glb, png, with_buffer, write)

# ---- The features scene ----------------------------------------------------------------------

BOX = [(x, y, z) for x in (-0.2, 0.2) for y in (0, 0.4) for z in (-0.2, 0.2)]
BOX_TRIS = [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4),
            (2, 6, 7), (2, 7, 3), (0, 4, 6), (0, 6, 2), (1, 3, 7), (1, 7, 5)]
MATERIALS = [
    {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1],
                                             "metallicFactor": 0, "roughnessFactor": 0.5}},
    {"name": "green", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.7, 0.2, 1],
                                               "metallicFactor": 0.25, "roughnessFactor": 0.75}},
    {"name": "lamp", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]},
     "emissiveFactor": [1, 0.9, 0.8], "extensions": {"KHR_materials_emissive_strength":
                                                     {"emissiveStrength": 6}}},
]
# (base colour, metallic, roughness, emission) as pt's JSON writes them; "default" is glTF's.
REF_MATERIALS = {"red": ([0.8, 0.1, 0.1], 0, 0.5, [0, 0, 0]),
                 "green": ([0.1, 0.7, 0.2], 0.25, 0.75, [0, 0, 0]),
                 "lamp": ([0, 0, 0], 1, 1, [6, 5.4, 4.8]),
                 "default": ([1, 1, 1], 1, 1, [0, 0, 0])}


def quat_matrix(q):
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def local_matrix(node):
    """4x4 row-major (column vectors) of a node."""
    if "matrix" in node:
        m = node["matrix"]
        return [[m[4 * c + r] for c in range(4)] for r in range(4)]
    t = node.get("translation", [0, 0, 0])
    r = quat_matrix(node.get("rotation", [0, 0, 0, 1]))
    s = node.get("scale", [1, 1, 1])
    return [[r[i][0] * s[0], r[i][1] * s[1], r[i][2] * s[2], t[i]] for i in range(3)] + [[0, 0, 0, 1]]


def mul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def det3(m):
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))


def rot_y(degrees):
    a = math.radians(degrees) / 2
    return [0, math.sin(a), 0, math.cos(a)]


def features():
    """(glTF JSON without buffers, binary buffer, {mesh: [(material name, positions, triangles)]})."""
    b = Builder()
    meshes, shapes = [], []

    def add_mesh(prims):
        meshes.append({"primitives": [p for p, _ in prims]})
        shapes.append([s for _, s in prims])

    # mesh 0: the box, FLOAT positions, UNSIGNED_BYTE indices; placed by 3 nodes.
    pos = [c for v in BOX for c in v]
    idx = [i for t in BOX_TRIS for i in t]
    add_mesh([({"attributes": {"POSITION": b.accessor(pos, 3, FLOAT)},
                "indices": b.accessor(idx, 1, UBYTE), "material": 0},
               ("red", pos, BOX_TRIS))])
    # mesh 1: a quad of normalized SHORT positions, BYTE normals, UNSIGNED_BYTE uvs, USHORT indices.
    quad = [-0.5, 0, -0.5, 0.5, 0, -0.5, 0.5, 0, 0.5, -0.5, 0, 0.5]
    add_mesh([({"attributes": {"POSITION": b.accessor(quad, 3, SHORT, True),
                               "NORMAL": b.accessor([0, 1, 0] * 4, 3, BYTE, True),
                               "TEXCOORD_0": b.accessor([0, 0, 1, 0, 1, 1, 0, 1], 2, UBYTE, True)},
                "indices": b.accessor([0, 2, 1, 0, 3, 2], 1, USHORT), "material": 1},
               ("green", decoded(quad, SHORT, True), [(0, 2, 1), (0, 3, 2)]))])
    # mesh 2: a strip, positions and normals interleaved (byteStride 24), UNSIGNED_INT indices.
    strip = [0, 0, 0, 0, 0.3, 0, 0.3, 0, 0, 0.3, 0.3, 0, 0.6, 0, 0, 0.6, 0.3, 0]
    inter = b"".join(struct.pack("<6f", *strip[3 * i:3 * i + 3], 0, 0, 1) for i in range(6))
    view = b.view(inter, stride=24)
    p_acc = b.accessor(strip, 3, FLOAT, view=view, offset=0, count=6)
    n_acc = b.accessor([], 3, FLOAT, view=view, offset=12, count=6)
    strip_order = [5, 4, 3, 2, 1, 0]
    tris = [(strip_order[i], strip_order[i + 1 + i % 2], strip_order[i + 2 - i % 2]) for i in range(4)]
    add_mesh([({"attributes": {"POSITION": p_acc, "NORMAL": n_acc},
                "indices": b.accessor(strip_order, 1, UINT), "mode": 5, "material": 1},
               ("green", strip, tris))])
    # mesh 3: a fan without indices, UNSIGNED_BYTE positions (KHR_mesh_quantization), USHORT uvs;
    # no material (the glTF default).
    fan = [0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 2, 0, 0, 1, 0]
    add_mesh([({"attributes": {"POSITION": b.accessor(fan, 3, UBYTE),
                               "TEXCOORD_0": b.accessor([0.5] * 10, 2, USHORT, True)}, "mode": 6},
               ("default", fan, [(1, 2, 0), (2, 3, 0), (3, 4, 0)]))])
    # mesh 4: two primitives: BYTE positions with a sparse substitution (UNSIGNED_BYTE indices,
    # FLOAT... no: values share the accessor's type), and a sparse accessor on no buffer view.
    base = [0, 0, 0, 10, 0, 0, 0, 10, 0, 10, 10, 0]
    a = b.accessor(base, 3, BYTE)
    sparse_vals = [20, 20, 5]
    b.accessors[a]["sparse"] = {"count": 1,
                                "indices": {"bufferView": b.view(struct.pack("<B", 3)), "componentType": UBYTE},
                                "values": {"bufferView": b.view(struct.pack("<3b", *sparse_vals))}}
    substituted = base[:9] + sparse_vals
    b.accessors.append({"componentType": FLOAT, "count": 3, "type": "VEC3"})  # no buffer view
    z = len(b.accessors) - 1
    vals = [0, 0, 1, 1, 0, 1, 0, 1, 1]
    b.accessors[z]["sparse"] = {"count": 3,
                                "indices": {"bufferView": b.view(struct.pack("<3H", 0, 1, 2)),
                                            "componentType": USHORT},
                                "values": {"bufferView": b.view(struct.pack("<9f", *vals))}}
    add_mesh([({"attributes": {"POSITION": a}, "indices": b.accessor([0, 1, 2, 2, 1, 3], 1, UBYTE),
                "material": 0}, ("red", substituted, [(0, 1, 2), (2, 1, 3)])),
              ({"attributes": {"POSITION": z}, "material": 1}, ("green", vals, [(0, 1, 2)]))])
    # mesh 5: the lamp, facing down.
    lamp = [-0.3, 0, -0.3, 0.3, 0, -0.3, 0.3, 0, 0.3, -0.3, 0, 0.3]
    add_mesh([({"attributes": {"POSITION": b.accessor(lamp, 3, FLOAT)},
                "indices": b.accessor([0, 1, 2, 0, 2, 3], 1, USHORT), "material": 2},
               ("lamp", lamp, [(0, 1, 2), (0, 2, 3)]))])
    s = math.sqrt(0.5)
    nodes = [
        {"name": "root", "translation": [0, 0.5, 0], "rotation": rot_y(30), "children": [1, 2, 3]},
        {"mesh": 0, "matrix": [0.5, 0, 0, 0, 0, 0.5, 0, 0, 0, 0, 0.5, 0, -1, 0, 0.2, 1]},
        {"mesh": 0, "translation": [1, 0, 0], "scale": [1, 2, 1], "children": [4]},
        {"mesh": 1, "translation": [0, -0.5, 0], "scale": [4, 1, 4]},
        {"mesh": 0, "translation": [0, 0.5, 0.5], "scale": [-1, 1, 1], "rotation": [s, 0, 0, s]},
        {"mesh": 2, "translation": [-1, 0, -1]},
        {"mesh": 3, "translation": [0.5, 0, -1.5], "scale": [0.25, 0.25, 0.25]},
        {"mesh": 4, "translation": [-1.5, 0, 0.5], "scale": [0.05, 0.05, 0.05]},
        {"mesh": 5, "translation": [0, 2.5, 0], "rotation": [1, 0, 0, 0]},
        {"camera": 0, "translation": [0, 1.5, 5]},
        {"translation": [0, 2, 2], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"translation": [1, 2, 0], "rotation": [-s, 0, 0, s], "extensions": {"KHR_lights_punctual": {"light": 1}}},
        {"rotation": rot_y(60), "children": [13]},
        {"rotation": [-0.5, 0, 0, math.sqrt(0.75)], "extensions": {"KHR_lights_punctual": {"light": 2}}},
    ]
    doc = {
        "asset": {"version": "2.0", "generator": "pt tools/make_gltf_tests.py"},
        "extensionsUsed": ["KHR_mesh_quantization", "KHR_materials_emissive_strength",
                           "KHR_lights_punctual"],
        "extensionsRequired": ["KHR_mesh_quantization"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 1, 1], "intensity": 683},
            {"type": "spot", "color": [1, 0.5, 0.25], "intensity": 1366, "range": 10,
             "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
            {"type": "directional", "color": [0.5, 0.5, 1], "intensity": 341.5}]}},
        "scene": 0, "scenes": [{"nodes": [0, 5, 6, 7, 8, 9, 10, 11, 12]}],
        "nodes": nodes, "meshes": meshes, "materials": MATERIALS,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}}],
        "accessors": b.accessors, "bufferViews": b.views,
    }
    return doc, bytes(b.bin), shapes


def world_triangles(doc, shapes):
    """{material: [triangle of 3 world points]} by walking the scene as a reader must."""
    out = {}

    def walk(n, parent):
        node = doc["nodes"][n]
        world = mul(parent, local_matrix(node))
        if "mesh" in node:
            for material, pos, tris in shapes[node["mesh"]]:
                pts = [[sum(world[i][k] * pos[3 * v + k] for k in range(3)) + world[i][3]
                        for i in range(3)] for v in range(len(pos) // 3)]
                for t in tris:
                    t = (t[0], t[2], t[1]) if det3(world) < 0 else t  # pt keeps fronts
                    out.setdefault(material, []).append([pts[v] for v in t])
        for c in node.get("children", []):
            walk(c, world)
    ident = [[float(i == j) for j in range(4)] for i in range(4)]
    for root in doc["scenes"][doc["scene"]]["nodes"]:
        walk(root, ident)
    return out


def write_reference(out, doc, shapes):
    tris = world_triangles(doc, shapes)
    objects, materials = [], {}
    for name, faces in sorted(tris.items()):
        lines = []
        for k, t in enumerate(faces):
            lines += ["v %.9g %.9g %.9g" % tuple(p) for p in t]
            lines.append("f %d %d %d" % (3 * k + 1, 3 * k + 2, 3 * k + 3))
        write(os.path.join(out, "reference_%s.obj" % name), "\n".join(lines) + "\n")
        base, metallic, roughness, emission = REF_MATERIALS[name]
        materials[name] = {"type": "principled", "base_color": base, "metallic": metallic,
                           "roughness": roughness, "emission": emission}
        objects.append({"obj": "reference_%s.obj" % name, "material": name})
    def minus_z(*quats):  # a node's -Z after its rotations (outermost first)
        v = [0, 0, -1]
        for q in reversed(quats):
            m = quat_matrix(q)
            v = [sum(m[i][k] * v[k] for k in range(3)) for i in range(3)]
        return v
    s = math.sqrt(0.5)
    lights = [{"type": "point", "position": [0, 2, 2], "intensity": [1, 1, 1]},
              {"type": "spot", "position": [1, 2, 0], "intensity": [2, 1, 0.5],
               "direction": minus_z([-s, 0, 0, s]), "cone_angle": math.degrees(0.5),
               "falloff_angle": math.degrees(0.2)},
              {"type": "directional", "irradiance": [0.25, 0.25, 0.5],
               "direction": minus_z(rot_y(60), [-0.5, 0, 0, math.sqrt(0.75)])}]
    scene = {"camera": {"eye": [0, 1.5, 5], "target": [0, 1.5, 4], "fov_y": math.degrees(0.7)},
             "lights": lights,
             "materials": materials, "objects": objects}
    write(os.path.join(out, "reference.json"), json.dumps(scene, indent=1))


def textured():
    """(GLB bytes, external PNG bytes): one quad whose material uses every field of
    scene/gltf_material.h: images in the GLB's buffer, as a data URI and as a file beside it."""
    b = Builder()
    quad = [-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1]
    image = png(2, 2, [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128])
    prim = {"attributes": {"POSITION": b.accessor(quad, 3, FLOAT),
                           "TEXCOORD_0": b.accessor([0, 0, 1, 0, 1, 1, 0, 1], 2, FLOAT)},
            "indices": b.accessor([0, 2, 1, 0, 3, 2], 1, UBYTE), "material": 0}
    view = b.view(image)
    transform = {"KHR_texture_transform": {"offset": [0.5, 0.25], "rotation": 0.75, "scale": [2, 3]}}
    material = {
        "name": "everything",
        "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.8, 0.7, 0.6], "metallicFactor": 0.4,
                                 "roughnessFactor": 0.3,
                                 "baseColorTexture": {"index": 0, "extensions": transform},
                                 "metallicRoughnessTexture": {"index": 1}},
        "normalTexture": {"index": 2, "scale": 0.5}, "occlusionTexture": {"index": 1, "strength": 0.25},
        "emissiveTexture": {"index": 1}, "emissiveFactor": [0.1, 0.2, 0.3],
        "alphaMode": "MASK", "alphaCutoff": 0.375, "doubleSided": True,
        "extensions": {
            "KHR_materials_emissive_strength": {"emissiveStrength": 4},
            "KHR_materials_specular": {"specularFactor": 0.625, "specularColorFactor": [0.5, 0.75, 1],
                                       "specularTexture": {"index": 0},
                                       "specularColorTexture": {"index": 1}},
            "KHR_materials_transmission": {"transmissionFactor": 0.875, "transmissionTexture": {"index": 2}},
            "KHR_materials_ior": {"ior": 1.25},
            "KHR_materials_volume": {"thicknessFactor": 0.125, "attenuationDistance": 2.5,
                                     "attenuationColor": [0.25, 0.5, 0.75]}}}
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "extensionsUsed": ["KHR_texture_transform", "KHR_materials_emissive_strength",
                              "KHR_materials_specular", "KHR_materials_transmission",
                              "KHR_materials_ior", "KHR_materials_volume"],
           "meshes": [{"primitives": [prim]}], "materials": [material],
           "images": [{"bufferView": view, "mimeType": "image/png"},
                      {"uri": "data:image/png;base64," + base64.b64encode(image).decode()},
                      {"uri": "tex%20file.png"}],
           "samplers": [{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728}],
           "textures": [{"source": 0, "sampler": 0}, {"source": 1}, {"source": 2}],
           "accessors": b.accessors, "bufferViews": b.views}
    return glb(with_buffer(doc, None, len(b.bin)), bytes(b.bin)), image


def big(path, triangles):
    """A grid of about `triangles` triangles (FLOAT positions and normals, UINT indices)."""
    n = max(1, int(math.sqrt(triangles / 2)))
    pos = bytearray()
    for j in range(n + 1):
        pos += b"".join(struct.pack("<3f", i / n, 0.1 * math.sin(7 * i / n + 3 * j / n), j / n) for i in range(n + 1))
    nrm = struct.pack("<3f", 0, 1, 0) * ((n + 1) * (n + 1))
    idx = bytearray()
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            idx += struct.pack("<6I", a, a + n + 1, a + 1, a + 1, a + n + 1, a + n + 2)
    binary = bytes(pos) + bytes(nrm) + bytes(idx)
    nv = (n + 1) * (n + 1)
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
           "accessors": [{"bufferView": 0, "componentType": FLOAT, "count": nv, "type": "VEC3",
                          "min": [0, -0.1, 0], "max": [1, 0.1, 1]},
                         {"bufferView": 1, "componentType": FLOAT, "count": nv, "type": "VEC3"},
                         {"bufferView": 2, "componentType": UINT, "count": 6 * n * n, "type": "SCALAR"}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                           {"buffer": 0, "byteOffset": len(pos), "byteLength": len(nrm)},
                           {"buffer": 0, "byteOffset": len(pos) + len(nrm), "byteLength": len(idx)}],
           "buffers": [{"byteLength": len(binary)}]}
    write(path, glb(doc, binary))
    return 2 * n * n


def main():
    args = sys.argv[1:]
    if len(args) == 3 and args[0] == "--big":
        print("%s: %d triangles" % (args[2], big(args[2], int(args[1]))))
        return
    if len(args) != 1:
        sys.exit(__doc__)
    out = args[0]
    os.makedirs(out, exist_ok=True)
    doc, binary, shapes = features()
    write(os.path.join(out, "features.bin"), binary)
    write(os.path.join(out, "features.gltf"), json.dumps(with_buffer(doc, "features.bin", len(binary)), indent=1))
    write(os.path.join(out, "features.glb"), glb(with_buffer(doc, None, len(binary)), binary))
    write(os.path.join(out, "features_embedded.gltf"),
          json.dumps(with_buffer(doc, data_uri(binary), len(binary))))
    write_reference(out, doc, shapes)
    data, image = textured()
    write(os.path.join(out, "textured.glb"), data)
    write(os.path.join(out, "tex file.png"), image)
    write_bad_cases(out, doc, binary)


if __name__ == "__main__":
    main()
