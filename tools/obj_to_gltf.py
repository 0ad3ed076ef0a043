#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""obj_to_gltf.py IN.obj OUT.gltf|OUT.glb [--camera EX,EY,EZ,FOVY_DEG]: an OBJ and its MTL as a
glTF 2.0 file (standard library only), for glTF versions of pt's scenes.

One mesh, one primitive per material (usemtl), positions (and normals, uvs when every face
corner has them); polygons fan-triangulated (pt's scenes use convex ones). MTL to glTF: Kd ->
baseColorFactor, metallic 0, roughness 1, KHR_materials_specular specularFactor 0 where Ks is
black (pure Lambert, as pt reads such an MTL material), Ke -> emissiveFactor (divided by its
largest component, which becomes KHR_materials_emissive_strength when above 1). uv v is flipped
(glTF's v = 0 is the image's top row). --camera adds a perspective camera node at E looking
along -z with that vertical field of view. A .gltf embeds its buffer as a base64 data URI.
"""
import base64
import json
import math
import os
import struct
import sys


def read_mtl(path):
    mats, cur = {}, None
    if not os.path.exists(path):
        return mats
    for line in open(path):
        words = line.split("#")[0].split()
        if not words:
            continue
        if words[0] == "newmtl":
            cur = mats.setdefault(words[1], {"Kd": [0.8] * 3, "Ks": [0] * 3, "Ke": [0] * 3})
        elif cur is not None and words[0] in ("Kd", "Ks", "Ke"):
            cur[words[0]] = [float(x) for x in words[1:4]]
    return mats


def read_obj(path):
    v, vt, vn, groups, mtllibs, mat = [], [], [], {}, [], None
    for line in open(path):
        words = line.split("#")[0].split()
        if not words:
            continue
        k = words[0]
        if k == "v":
            v.append([float(x) for x in words[1:4]])
        elif k == "vt":
            vt.append([float(x) for x in words[1:3]])
        elif k == "vn":
            vn.append([float(x) for x in words[1:4]])
        elif k == "mtllib":
            mtllibs += words[1:]
        elif k == "usemtl":
            mat = words[1]
        elif k == "f":
            corners = []
            for w in words[1:]:
                parts = (w.split("/") + ["", ""])[:3]
                idx = [int(p) if p else 0 for p in parts]
                sizes = (len(v), len(vt), len(vn))
                corners.append(tuple(i - 1 if i > 0 else (sizes[j] + i if i < 0 else -1)
                                     for j, i in enumerate(idx)))
            for i in range(1, len(corners) - 1):
                groups.setdefault(mat, []).append((corners[0], corners[i], corners[i + 1]))
    return v, vt, vn, groups, mtllibs


def convert(obj_path, camera):
    v, vt, vn, groups, mtllibs = read_obj(obj_path)
    mtl = {}
    for lib in mtllibs:
        mtl.update(read_mtl(os.path.join(os.path.dirname(obj_path), lib)))
    binary, views, accessors, prims, materials = bytearray(), [], [], [], []

    def add(data, ctype, count, type_, extra=None):
        while len(binary) % 4:
            binary.append(0)
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(data)})
        binary.extend(data)
        a = {"bufferView": len(views) - 1, "componentType": ctype, "count": count, "type": type_}
        a.update(extra or {})
        accessors.append(a)
        return len(accessors) - 1

    for name, tris in groups.items():
        corners = [c for t in tris for c in t]
        has_t = all(c[1] >= 0 for c in corners)
        has_n = all(c[2] >= 0 for c in corners)
        pos = [v[c[0]] for c in corners]
        attrs = {"POSITION": add(b"".join(struct.pack("<3f", *p) for p in pos), 5126, len(pos), "VEC3",
                                 {"min": [min(p[i] for p in pos) for i in range(3)],
                                  "max": [max(p[i] for p in pos) for i in range(3)]})}
        if has_n:
            attrs["NORMAL"] = add(b"".join(struct.pack("<3f", *vn[c[2]]) for c in corners), 5126,
                                  len(corners), "VEC3")
        if has_t:
            attrs["TEXCOORD_0"] = add(b"".join(struct.pack("<2f", vt[c[1]][0], 1 - vt[c[1]][1])
                                               for c in corners), 5126, len(corners), "VEC2")
        m = mtl.get(name, {"Kd": [0.8] * 3, "Ks": [0] * 3, "Ke": [0] * 3})
        material = {"name": name or "default",
                    "pbrMetallicRoughness": {"baseColorFactor": m["Kd"] + [1], "metallicFactor": 0,
                                             "roughnessFactor": 1}}
        ext = {}
        if max(m["Ks"]) == 0:
            ext["KHR_materials_specular"] = {"specularFactor": 0}
        strength = max(m["Ke"])
        if strength > 0:
            material["emissiveFactor"] = [x / max(strength, 1) for x in m["Ke"]]
            if strength > 1:
                ext["KHR_materials_emissive_strength"] = {"emissiveStrength": strength}
        if ext:
            material["extensions"] = ext
        materials.append(material)
        prims.append({"attributes": attrs, "material": len(materials) - 1})
    nodes = [{"mesh": 0, "name": os.path.basename(obj_path)}]
    doc = {"asset": {"version": "2.0", "generator": "pt tools/obj_to_gltf.py"},
           "extensionsUsed": ["KHR_materials_specular", "KHR_materials_emissive_strength"],
           "scene": 0, "scenes": [{"nodes": [0]}], "nodes": nodes,
           "meshes": [{"primitives": prims}], "materials": materials,
           "accessors": accessors, "bufferViews": views}
    if camera:
        ex, ey, ez, fov = camera
        nodes.append({"camera": 0, "translation": [ex, ey, ez]})
        doc["scenes"][0]["nodes"].append(1)
        doc["cameras"] = [{"type": "perspective",
                           "perspective": {"yfov": math.radians(fov), "znear": 0.01}}]
    return doc, bytes(binary)


def main():
    args = sys.argv[1:]
    camera = None
    if "--camera" in args:
        i = args.index("--camera")
        camera = [float(x) for x in args[i + 1].split(",")]
        del args[i:i + 2]
    if len(args) != 2:
        sys.exit(__doc__)
    doc, binary = convert(args[0], camera)
    if args[1].endswith(".glb"):
        doc["buffers"] = [{"byteLength": len(binary)}]
        text = json.dumps(doc).encode()
        text += b" " * (-len(text) % 4)
        binary += b"\0" * (-len(binary) % 4)
        chunks = (struct.pack("<II", len(text), 0x4E4F534A) + text +
                  struct.pack("<II", len(binary), 0x004E4942) + binary)
        with open(args[1], "wb") as f:
            f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks)
    else:
        doc["buffers"] = [{"byteLength": len(binary), "uri": "data:application/octet-stream;base64,"
                           + base64.b64encode(binary).decode()}]
        with open(args[1], "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")


if __name__ == "__main__":
    main()
