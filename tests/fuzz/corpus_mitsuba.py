# SPDX-License-Identifier: MIT
"""Cases for the Mitsuba 3 XML importer (host/io/xml_tree.c, host/scene/import_mitsuba.c,
mitsuba_*.c): valid scenes using each element, then malformed XML, bad values, escaping paths,
missing refs and include cycles, each a one-line error naming file:line and the element; and a
few random mutations of a valid scene (expect "any": never a crash).
"""
from corpus_cases import TINY, TRIANGLE, case

SENSOR = """<sensor type="perspective"><float name="fov" value="40"/>
  <transform name="to_world"><lookat origin="0.3, 0.3, 2" target="0.3, 0.3, 0" up="0, 1, 0"/></transform>
  <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
  <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/>
  <rfilter type="box"/></film></sensor>"""
TRI = '<shape type="obj"><string name="filename" value="tri.obj"/>%s</shape>'

VALID = {
    "diffuse": TRI % '<bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf>',
    "conductor-preset": TRI % '<bsdf type="roughconductor"><string name="material" value="Au"/>'
                              '<float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.05"/></bsdf>',
    "dielectric-named": TRI % '<bsdf type="roughdielectric"><string name="int_ior" value="diamond"/></bsdf>',
    "plastic": TRI % '<bsdf type="plastic"><spectrum name="diffuse_reflectance" value="400:0.1, 700:0.9"/></bsdf>',
    "blend-mask": TRI % '<bsdf type="mask"><float name="opacity" value="0.5"/><bsdf type="blendbsdf">'
                        '<bsdf type="diffuse"/><bsdf type="conductor"/></bsdf></bsdf>',
    "principled": TRI % '<bsdf type="principled"><float name="specular" value="0"/></bsdf>',
    "thin": TRI % '<bsdf type="thindielectric"/>',
    "checkerboard": TRI % '<bsdf type="diffuse"><texture name="reflectance" type="checkerboard"/></bsdf>',
    "area": TRI % '<emitter type="area"><rgb name="radiance" value="2"/></emitter>',
    "shapes": '<shape type="sphere"><float name="radius" value="0.2"/></shape><shape type="cube">'
              '<boolean name="flip_normals" value="true"/></shape><shape type="disk"/>'
              '<shape type="rectangle"><boolean name="face_normals" value="true"/></shape>',
    "flip-obj": TRI % '<boolean name="flip_normals" value="true"/><boolean name="face_normals" value="true"/>',
    "instances": '<shape type="shapegroup" id="g">' + TRI % '' + '</shape>'
                 '<shape type="instance"><ref id="g"/></shape><shape type="instance"><ref id="g"/>'
                 '<transform name="to_world"><translate x="1"/></transform></shape>',
    "lights": TRI % '' + '<emitter type="point"><point name="position" value="0, 1, 1"/></emitter>'
              '<emitter type="spot"><transform name="to_world"><lookat origin="0,1,1" target="0,0,0"/>'
              '</transform></emitter><emitter type="directional"/><emitter type="constant"/>',
    "include": '<include filename="part.xml"/>' + TRI % '<ref id="inc"/>',
    "unknown-plugins": TRI % '<bsdf type="hair"/>' + '<shape type="cylinder"/><medium type="x"/>'
                       '<integrator type="aov"/>',
    "integrator": TRI % '' + '<integrator type="volpath"><integer name="max_depth" value="3"/></integrator>',
}

BAD = [
    ("malformed", "<scene version='3.0.0'><shape type='obj'></scene>", "scene.xml:1: malformed XML"),
    ("doctype", "<!DOCTYPE scene [<!ENTITY a 'aaaa'>]><scene version='3.0.0'/>", "DOCTYPE"),
    ("not-scene", "<shape type='obj'/>", "root element must be <scene"),
    ("no-version", "<scene><shape type='sphere'/></scene>", "missing version"),
    ("no-shape", "<scene version='3.0.0'><emitter type='constant'/></scene>", "no shape"),
    ("bad-float", "<scene version='3.0.0'>\n<shape type='sphere'><float name='radius' value='x'/></shape></scene>",
     "scene.xml:2: <float name=\"radius\">"),
    ("undefined-parameter", "<scene version='3.0.0'>\n<shape type='sphere'><float name='radius' value='$r'/>"
     "</shape></scene>", "undefined parameter $r"),
    ("missing-ref", "<scene version='3.0.0'><shape type='sphere'>\n<ref id='nope'/></shape></scene>",
     "scene.xml:2: <ref id=\"nope\">"),
    ("escaping-file", "<scene version='3.0.0'><shape type='obj'><string name='filename' value='../x.obj'/>"
     "</shape></scene>", "leaves the scene's folder"),
    ("absolute-file", "<scene version='3.0.0'><shape type='ply'><string name='filename' value='/etc/passwd'/>"
     "</shape></scene>", "leaves the scene's folder"),
    ("missing-obj", "<scene version='3.0.0'><shape type='obj'><string name='filename' value='none.obj'/>"
     "</shape></scene>", "none.obj"),
    ("include-cycle", "<scene version='3.0.0'><include filename='scene.xml'/></scene>", "nested more than"),
    ("bad-rotate", "<scene version='3.0.0'><shape type='sphere'><transform name='to_world'>\n"
     "<rotate angle='30'/></transform></shape></scene>", "scene.xml:2: <rotate>"),
    ("projective-matrix", "<scene version='3.0.0'><shape type='sphere'><transform name='to_world'>"
     "<matrix value='1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1'/></transform></shape></scene>", "projective"),
    ("bad-ior", "<scene version='3.0.0'><shape type='sphere'><bsdf type='dielectric'>"
     "<string name='int_ior' value='mithril'/></bsdf></shape></scene>", "named indices"),
    ("bad-sensor", "<scene version='3.0.0'><sensor type='orthographic'/><shape type='sphere'/></scene>",
     "not perspective or thinlens"),
    ("zero-depth", "<scene version='3.0.0'><integrator type='path'><integer name='max_depth' value='0'/>"
     "</integrator><shape type='sphere'/></scene>", "max_depth 0"),
    ("duplicate-id", "<scene version='3.0.0'><bsdf type='diffuse' id='a'/><bsdf type='diffuse' id='a'/>"
     "<shape type='sphere'/></scene>", "a second element with id"),
    ("deep", "<scene version='3.0.0'>" + "<bsdf type='twosided'>" * 80 + "</bsdf>" * 80 + "</scene>",
     "nested too deeply"),
    ("blend-one", "<scene version='3.0.0'><shape type='sphere'><bsdf type='blendbsdf'><bsdf type='diffuse'/>"
     "</bsdf></shape></scene>", "needs 2 nested bsdfs"),
    ("ref-wrong-kind", "<scene version='3.0.0'><texture type='bitmap' id='t'/><shape type='sphere'>"
     "<ref id='t'/></shape></scene>", "not a <bsdf>"),
]


def scene(body, spp=1):
    return ('<scene version="3.0.0"><default name="spp" value="%d"/>' % spp) + SENSOR + body + "</scene>"


def mitsuba_case(name, xml, expect, needle=None, args=None, extra=None):
    files = {"scene.xml": xml, "tri.obj": TRIANGLE,
             "part.xml": '<scene version="3.0.0"><bsdf type="diffuse" id="inc"/></scene>'}
    files.update(extra or {})
    case("mitsuba-" + name, files, (args or []) + ["render", "scene.xml"] + TINY, expect, needle=needle)


def mitsuba_cases(rng):
    for name, body in VALID.items():
        mitsuba_case(name, scene(body), "ok")
    old = scene(TRI % '<bsdf type="dielectric"><float name="intIOR" value="1.3"/></bsdf>').replace(
        'version="3.0.0"', 'version="0.6.0"').replace("sample_count", "sampleCount")
    mitsuba_case("old-version-camelcase", old, "ok")
    case("mitsuba-cli-define", {"scene.xml": scene(TRI % ""), "tri.obj": TRIANGLE},
         ["render", "scene.xml", "-D", "spp=2"] + TINY, "ok")
    case("mitsuba-cli-define-bad", {"scene.xml": scene(TRI % ""), "tri.obj": TRIANGLE},
         ["render", "scene.xml", "-D", "2=x"] + TINY, "error", needle="NAME=VALUE")
    for name, xml, needle in BAD:
        mitsuba_case(name, xml, "error", needle)
    # Random damage to a valid scene: cut, duplicated or swapped bytes; never a crash.
    base = scene(VALID["lights"] + VALID["blend-mask"] + VALID["instances"]).encode()
    for i in range(12):
        data = bytearray(base)
        for _ in range(1 + i % 4):
            k = rng.randrange(len(data))
            op = rng.randrange(3)
            if op == 0:
                data[k] = rng.choice(b"<>/\"'=$ 0-9x")
            elif op == 1:
                del data[k:k + rng.randrange(1, 40)]
            else:
                data[k:k] = data[rng.randrange(len(data)):][:20]
        mitsuba_case("mutation-%02d" % i, bytes(data), "any")
