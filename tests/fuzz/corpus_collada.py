# SPDX-License-Identifier: MIT
"""Cases for the importers of issue 37: COLLADA (host/io/collada_reader.c, scene/import_collada.c),
the Assimp formats (io/assimp_reader.c: STL, OFF, FBX) and Draco-compressed glTF (io/gltf_draco.cc):
a valid CS184-style scene, then broken XML, dangling references, bad counts and indices, hostile
nesting and entity tricks, paths leaving the folder, and mangled copies of the valid file; each
ends in an image or one "pt: ..." line naming the file.
"""
import struct

from corpus_cases import TINY, case

HEAD = ('<?xml version="1.0" encoding="utf-8"?>\n'
        '<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">\n'
        '<asset><up_axis>Z_UP</up_axis></asset>\n')
GEOMETRY = ('<geometry id="g"><mesh><source id="p"><float_array id="pa" count="12">'
            '0 0 0 1 0 0 1 1 0 0 1 0</float_array><technique_common><accessor source="#pa" count="4" '
            'stride="3"/></technique_common></source><vertices id="v"><input semantic="POSITION" '
            'source="#p"/></vertices><polylist material="m" count="1"><input semantic="VERTEX" '
            'source="#v" offset="0"/><vcount>4</vcount><p>0 1 2 3</p></polylist></mesh></geometry>')
SPHERE = ('<geometry id="s"><extra><technique profile="CGL"><sphere><radius>0.3</radius></sphere>'
          '</technique></extra></geometry>')
EFFECTS = ('<library_effects><effect id="fx"><profile_COMMON><technique sid="c"><phong><diffuse>'
           '<color>0.5 0.5 0.5 1</color></diffuse></phong></technique></profile_COMMON><extra>'
           '<technique profile="CGL"><microfacet><alpha>0.1</alpha><eta>0.2 0.9 1.1</eta><k>3 2 2</k>'
           '</microfacet></technique></extra></effect></library_effects>'
           '<library_materials><material id="mat"><instance_effect url="#fx"/></material></library_materials>')
LIGHTS = ('<library_lights><light id="l"><technique_common><point><color>1 1 1</color></point>'
          '</technique_common><extra><technique profile="CGL"><area><color>5 5 5</color></area>'
          '</technique></extra></light></library_lights>')
CAMERA = ('<library_cameras><camera id="c"><optics><technique_common><perspective><xfov>50</xfov>'
          '<aspect_ratio>1.3</aspect_ratio></perspective></technique_common></optics></camera>'
          '</library_cameras>')
BIND = ('<bind_material><technique_common><instance_material symbol="m" target="#mat"/>'
        '</technique_common></bind_material>')
NODES = ('<node id="a"><translate>0 0 0</translate><instance_geometry url="#g">' + BIND +
         '</instance_geometry></node><node id="b"><rotate>0 0 1 30</rotate><scale>1 2 1</scale>'
         '<instance_geometry url="#s">' + BIND + '</instance_geometry></node>'
         '<node id="lamp"><matrix>0.5 0 0 0 0 0.5 0 0 0 0 1 2 0 0 0 1</matrix>'
         '<instance_light url="#l"/></node><node id="cam"><lookat>0 -4 1 0 0 0 0 0 1</lookat>'
         '<instance_camera url="#c"/></node>')


def dae(geometries=GEOMETRY + SPHERE, nodes=NODES, extra=""):
    return (HEAD + LIGHTS + CAMERA + EFFECTS + extra + "<library_geometries>" + geometries +
            "</library_geometries><library_visual_scenes><visual_scene id=\"vs\">" + nodes +
            "</visual_scene></library_visual_scenes><scene><instance_visual_scene url=\"#vs\"/>"
            "</scene></COLLADA>\n")


def dae_case(name, content, expect="any", needle=None):
    case("dae-" + name, {"x.dae": content}, ["render", "x.dae"] + TINY, expect, needle=needle)


def collada_cases(rng):
    good = dae()
    dae_case("cs184", good, "ok")
    dae_case("empty", "", "error", "x.dae")
    dae_case("not-xml", "COLLADA but not XML\n", "error", "x.dae")
    dae_case("truncated", good[: len(good) // 2], "error", "x.dae")
    dae_case("other-root", '<?xml version="1.0"?><scene/>', "error", "x.dae")
    dae_case("no-scene", HEAD + "</COLLADA>", "error", "visual_scene")
    dae_case("dangling-geometry", dae(nodes='<node id="n"><instance_geometry url="#nothing"/></node>'),
             "error", "nothing")
    dae_case("dangling-material", dae(nodes='<node id="n"><instance_geometry url="#g"><bind_material>'
             '<technique_common><instance_material symbol="m" target="#none"/></technique_common>'
             '</bind_material></instance_geometry></node>'), "error", "none")
    dae_case("index-range", dae(geometries=GEOMETRY.replace("<p>0 1 2 3</p>", "<p>0 1 2 99</p>")),
             "error", "index 99")
    dae_case("negative-index", dae(geometries=GEOMETRY.replace("<p>0 1 2 3</p>", "<p>0 -1 2 3</p>")),
             "error", "x.dae")
    dae_case("vcount-overrun", dae(geometries=GEOMETRY.replace("<vcount>4</vcount>", "<vcount>4 9</vcount>")),
             "error", "vcount")
    dae_case("vcount-huge", dae(geometries=GEOMETRY.replace("<vcount>4</vcount>", "<vcount>99999999999</vcount>")),
             "error", "x.dae")
    dae_case("count-lies", dae(geometries=GEOMETRY.replace('count="12"', 'count="1200000000"')),
             "error", "x.dae")
    dae_case("count-beyond-text", dae(geometries=GEOMETRY.replace('count="12"', 'count="600000000"')
             .replace('count="4" stride', 'count="200000000" stride')), "error", "count")
    dae_case("stride-zero", dae(geometries=GEOMETRY.replace('stride="3"', 'stride="0"')), "error", "x.dae")
    dae_case("offset-huge", dae(geometries=GEOMETRY.replace('offset="0"', 'offset="4000000000"')),
             "error", "x.dae")
    dae_case("nan-position", dae(geometries=GEOMETRY.replace("1 1 0 0 1 0", "nan 1 0 0 1 0")), "error", "x.dae")
    dae_case("bad-matrix", dae(nodes=NODES.replace("0.5 0 0 0 0 0.5 0 0 0 0 1 2 0 0 0 1", "1 2 3")),
             "error", "matrix")
    dae_case("zero-scale", dae(nodes=NODES.replace("<scale>1 2 1</scale>", "<scale>0 0 0</scale>")), "any")
    dae_case("negative-radius", dae(geometries=GEOMETRY + SPHERE.replace("0.3", "-1")), "error", "radius")
    cycle = '<library_nodes><node id="loop"><instance_node url="#loop"/></node></library_nodes>'
    dae_case("instance-node-cycle", dae(nodes='<node id="n"><instance_node url="#loop"/></node>', extra=cycle),
             "error", "deeper")
    dae_case("deep-nesting", dae(nodes="<node>" * 5000 + "</node>" * 5000), "error", "x.dae")
    dae_case("entity-expansion",
             '<?xml version="1.0"?><!DOCTYPE C [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;'
             '&a;&a;&a;&a;"><!ENTITY c "&b;&b;&b;&b;&b;&b;&b;&b;&b;&b;">]><COLLADA>&c;</COLLADA>',
             "error", "x.dae")
    dae_case("external-entity",
             '<?xml version="1.0"?><!DOCTYPE C [<!ENTITY x SYSTEM "file:///etc/passwd">]><COLLADA>&x;'
             '</COLLADA>', "error", "x.dae")
    image = ('<library_images><image id="i"><init_from>%s</init_from></image></library_images>'
             '<library_effects><effect id="tx"><profile_COMMON><technique sid="c"><lambert><diffuse>'
             '<texture texture="i" texcoord="uv"/></diffuse></lambert></technique></profile_COMMON>'
             '</effect></library_effects><library_materials><material id="tm"><instance_effect url="#tx"/>'
             '</material></library_materials>')
    dae_case("image-escapes", dae(extra=image % "../../../etc/passwd"), "error", "passwd")
    dae_case("image-absolute", dae(extra=image % "file:///etc/passwd"), "error", "passwd")
    dae_case("image-missing", dae(extra=image % "none.png"), "any")
    for i in range(12):  # mangled copies: a run of bytes replaced
        data = bytearray(good.encode())
        at = rng.randrange(len(data))
        for k in range(rng.randrange(1, 16)):
            if at + k < len(data):
                data[at + k] = rng.randrange(256)
        dae_case("mangled-%02d" % i, bytes(data))
    # The Assimp formats.
    tri = struct.pack("<12f", 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0) + b"\0\0"
    case("stl-binary", {"x.stl": b"\0" * 80 + struct.pack("<I", 1) + tri}, ["render", "x.stl"] + TINY, "ok")
    case("stl-count-lies", {"x.stl": b"\0" * 80 + struct.pack("<I", 1 << 30) + tri},
         ["render", "x.stl"] + TINY, "error", needle="x.stl")
    case("stl-ascii-broken", {"x.stl": "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n"},
         ["render", "x.stl"] + TINY, "error", needle="x.stl")
    case("off-ok", {"x.off": "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"},
         ["render", "x.off"] + TINY, "ok")
    case("off-index", {"x.off": "OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 7\n"},
         ["render", "x.off"] + TINY, "any")
    for ext in ("stl", "fbx", "3ds", "x3d", "off"):  # Assimp asserts on an empty buffer
        case(ext + "-empty", {"x." + ext: ""}, ["render", "x." + ext] + TINY, "error", needle="empty")
    case("fbx-garbage", {"x.fbx": b"Kaydara FBX Binary  \0\x1a\0" + bytes(range(256)) * 4},
         ["render", "x.fbx"] + TINY, "error", needle="x.fbx")
    case("fbx-ascii-empty", {"x.fbx": "; FBX 7.5.0 project file\nObjects: {\n}\n"},
         ["render", "x.fbx"] + TINY, "error", needle="x.fbx")
    case("3ds-garbage", {"x.3ds": b"\x4d\x4d" + struct.pack("<I", 1 << 31) + b"\0" * 32},
         ["render", "x.3ds"] + TINY, "error", needle="x.3ds")
