# SPDX-License-Identifier: MIT
"""Cases for materials v2: the JSON "textures" and "materials" blocks, objects' "material" and
"smooth", and the MTL statements the mapping reads (Pr, Pm, Ns, Ke/map_Ke, norm, map_Bump, map_d).
One valid scene and one valid MTL use every key; every bad value is a one-line error naming the
key.
"""
import json

from corpus_cases import BASE_SCENE, TEXTURED, TINY, TRIANGLE, case
from corpus_images import hdr, jpeg, png

UV_TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n"
TEXTURES = {"bricks": {"file": "t.png"}, "lin": {"file": "t.png", "encoding": "linear"},
            "sky": {"file": "t.hdr"},
            "marble": {"type": "noise", "color0": [0.9, 0.9, 0.9], "color1": [0.2, 0.2, 0.3],
                       "frequency": 4.0, "octaves": 5, "seed": 1}}
MATERIALS = {
    "wall": {"type": "diffuse", "albedo": "bricks", "normal_map": "lin", "bump_map": "lin",
             "bump_scale": 0.5, "opacity": "lin"},
    "gold": {"type": "conductor", "eta": [0.143, 0.374, 1.442], "k": [3.983, 2.385, 1.603],
             "roughness": 0.3, "anisotropy": 0.5, "reflectance": 0.9},
    "mirror": {"type": "conductor"},
    "glass": {"type": "dielectric", "ior": 1.5, "roughness": 0.1, "tint": [1, 0.9, 0.9],
              "absorption": [0, 0.5, 1]},
    "plastic": {"type": "principled", "base_color": "marble", "metallic": "lin", "roughness": 0.4,
                "specular": 0.5, "specular_color": [1, 1, 1], "ior": 1.45},
    "lamp": {"type": "diffuse", "emission": "sky", "emission_strength": 2},
    "blend": {"type": "mix", "a": "gold", "b": "wall", "weight": "marble"},
}


def material_scene(textures=None, materials=None, objects=None):
    scene = json.loads(json.dumps(BASE_SCENE))
    scene["textures"] = json.loads(json.dumps(TEXTURES if textures is None else textures))
    scene["materials"] = json.loads(json.dumps(MATERIALS if materials is None else materials))
    scene["objects"] = objects or [{"obj": "tri.obj", "material": "blend", "smooth": True},
                                   {"obj": "uv.obj"}]
    return scene


def scene_case(name, scene, expect="any", needle=None, extra=None):
    files = {"tri.obj": TRIANGLE, "uv.obj": UV_TRIANGLE, "t.png": png(4, 4), "t.hdr": hdr(8, 4),
             "scene.json": scene if isinstance(scene, str) else json.dumps(scene)}
    files.update(extra or {})
    case("json-mat-" + name, files, ["render", "scene.json"] + TINY, expect, needle=needle)


def with_key(material, key, value):
    materials = json.loads(json.dumps(MATERIALS))
    materials[material][key] = value
    return material_scene(materials=materials)


def json_material_cases():
    scene_case("valid", material_scene(), "ok")
    bad = [("roughness-over-1", "gold", "roughness", 1.5, "materials.gold.roughness"),
           ("roughness-negative", "plastic", "roughness", -0.1, "materials.plastic.roughness"),
           ("ior-negative", "glass", "ior", -1.5, "materials.glass.ior"),
           ("ior-huge", "glass", "ior", 1e308, "materials.glass.ior"),
           ("eta-negative", "gold", "eta", [0.1, -1, 1], "materials.gold.eta"),
           ("k-negative", "gold", "k", -2, "materials.gold.k"),
           ("absorption-negative", "glass", "absorption", [0, -0.5, 1], "materials.glass.absorption"),
           ("anisotropy-1", "gold", "anisotropy", 1, "materials.gold.anisotropy"),
           ("albedo-over-1", "wall", "albedo", [2, 0, 0], "materials.wall.albedo"),
           ("opacity-over-1", "wall", "opacity", 1.5, "materials.wall.opacity"),
           ("emission-negative", "lamp", "emission", -1, "materials.lamp.emission"),
           ("weight-negative", "blend", "weight", -1, "materials.blend.weight"),
           ("unknown-texture", "wall", "albedo", "nowhere", "nowhere"),
           ("unknown-scalar-texture", "gold", "roughness", "nowhere", "materials.gold.roughness"),
           ("unknown-normal-map", "wall", "normal_map", "nowhere", "materials.wall.normal_map"),
           ("mix-unknown", "blend", "a", "silver", "silver"),
           ("mix-self", "blend", "b", "blend", "materials.blend.b"),
           ("unknown-key", "gold", "albedo", 0.5, "materials.gold.albedo"),
           ("unknown-type", "gold", "type", "metal", "materials.gold.type"),
           ("eta-texture", "gold", "eta", "bricks", "materials.gold.eta")]
    for name, material, key, value, needle in bad:
        scene_case(name, with_key(material, key, value), "error", needle=needle)
    materials = json.loads(json.dumps(MATERIALS))
    materials["ring"] = {"type": "mix", "a": "blend2", "b": "gold"}
    materials["blend2"] = {"type": "mix", "a": "ring", "b": "gold"}
    scene_case("mix-cycle", material_scene(materials=materials), "error", needle="cycle")
    materials = {"leaf": {"type": "diffuse"}}
    for i in range(12):
        materials["m%d" % i] = {"type": "mix", "a": "m%d" % (i + 1) if i < 11 else "leaf", "b": "leaf"}
    scene_case("mix-too-deep", material_scene(materials=materials,
                                              objects=[{"obj": "tri.obj", "material": "m0"}]),
               "error", needle="deep")
    for name, texture, needle, extra in [
            ("texture-undecodable", {"file": "junk.png"}, "textures.bad.file", {"junk.png": "not an image"}),
            ("texture-missing", {"file": "nowhere.png"}, "nowhere.png", None),
            ("texture-truncated-hdr", {"file": "cut.hdr"}, "cut.hdr", {"cut.hdr": hdr(8, 4)[:-10]}),
            ("texture-bad-encoding", {"file": "t.png", "encoding": "gamma"}, "textures.bad.encoding", None),
            ("texture-no-file", {"encoding": "linear"}, "textures.bad.file", None),
            ("texture-exr-junk", {"file": "x.exr"}, "x.exr", {"x.exr": "v/1\x01\x00\x00\x00junk"}),
            ("noise-octaves-0", {"type": "noise", "octaves": 0}, "textures.bad.octaves", None),
            ("noise-frequency-negative", {"type": "noise", "frequency": -1}, "textures.bad.frequency", None),
            ("noise-seed-negative", {"type": "noise", "seed": -1}, "textures.bad.seed", None),
            ("noise-with-file", {"type": "noise", "file": "t.png"}, "textures.bad.file", None),
            ("texture-type-unknown", {"type": "voronoi"}, "textures.bad.type", None)]:
        textures = json.loads(json.dumps(TEXTURES))
        textures["bad"] = texture
        scene_case(name, material_scene(textures=textures), "error", needle=needle, extra=extra)
    textures = json.loads(json.dumps(TEXTURES))
    textures["grey"] = {"file": "g.jpg", "encoding": "linear"}
    materials = json.loads(json.dumps(MATERIALS))
    materials["wall"]["normal_map"] = "grey"
    scene_case("normal-map-grey", material_scene(textures=textures, materials=materials), "error",
               needle="materials.wall.normal_map", extra={"g.jpg": jpeg(8, 8)})
    for name, obj, needle in [("object-material-unknown", {"obj": "tri.obj", "material": "brass"}, "brass"),
                              ("object-material-number", {"obj": "tri.obj", "material": 3}, "objects[0].material"),
                              ("object-smooth-number", {"obj": "tri.obj", "smooth": 1}, "objects[0].smooth")]:
        scene_case(name, material_scene(objects=[obj]), "error", needle=needle)
    for block in ("textures", "materials"):
        for vname, value in [("array", []), ("number", 1), ("null", None)]:
            scene = material_scene()
            scene[block] = value
            scene_case("%s-%s" % (block, vname), scene, "error", needle=block)
        scene = material_scene()
        scene[block]["x"] = 7
        scene_case("%s-entry-number" % block, scene, "error", needle="%s.x" % block)
    # Every key of every material with values of the wrong kind.
    for material, keys in MATERIALS.items():
        for key in keys:
            if key == "type":
                continue
            for vname, value in [("null", None), ("true", True), ("object", {}), ("four", [1, 2, 3, 4]),
                                 ("huge", 1e308), ("long-string", "s" * 5000)]:
                scene_case("type-%s-%s-%s" % (material, key, vname), with_key(material, key, value),
                           "error", needle="materials.%s.%s" % (material, key))


def mtl_case(name, mtl, expect="any", needle=None, extra=None):
    files = {"x.obj": TEXTURED, "m.mtl": "newmtl t\n" + mtl + "\n", "t.png": png(4, 4)}
    files.update(extra or {})
    case("mtl-v2-" + name, files, ["render", "x.obj"] + TINY, expect, needle=needle)


def mtl_material_cases():
    mtl_case("valid", "Kd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs 250\nillum 2\nPr 0.3\nPm 1\n"
             "map_Pr t.png\nmap_Pm t.png\nKe 1 1 1\nmap_Ke t.png\nnorm -bm 0.5 t.png\n"
             "map_Bump t.png\nmap_d t.png\nd 0.5\nKa 1 1 1\nmap_Kd -s 2 2 1 -clamp on t.png", "ok")
    mtl_case("grey-bump", "Kd 1 1 1\nbump -bm 2 g.jpg", "ok", extra={"g.jpg": jpeg(8, 8)})
    for name, line in [("pr-nan", "Pr nan"), ("pr-negative", "Pr -1"), ("pr-huge", "Pr 1e39"),
                       ("pm-nan", "Pm nan"), ("pm-two", "Pm 2"), ("ns-negative", "Ns -5\nKs 1 1 1\nillum 2"),
                       ("ns-nan", "Ns nan\nKs 1 1 1\nillum 2"), ("bm-nan", "norm -bm nan t.png"),
                       ("bm-huge", "norm -bm 1e39 t.png"), ("ke-map-only", "map_Ke t.png"),
                       ("conductor-pr", "Ks 1 1 1\nillum 3\nPr 2"), ("glass-pr", "illum 7\nNi 1.5\nPr nan")]:
        mtl_case("value-" + name, line)
    for statement in ("map_Ke", "map_Pr", "map_Pm", "map_d", "norm", "map_Bump"):
        mtl_case("corrupt-" + statement, "%s junk.png" % statement, "error", needle=statement,
                 extra={"junk.png": "not an image"})
        mtl_case("missing-" + statement, "%s nowhere.png" % statement)
        mtl_case("dev-zero-" + statement, "%s /dev/zero" % statement, "error")


def material_cases():
    json_material_cases()
    mtl_material_cases()
