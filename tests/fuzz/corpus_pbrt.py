# SPDX-License-Identifier: MIT
"""Cases for the pbrt-v4 importer (host/io/pbrt_parser.c, host/scene/import_pbrt*.c): a valid scene
with each element, then malformed tokens, parameter lists, directives and paths, each a one-line
error naming the file and line; and random mutations of the valid scene (expect "any": an error
line or a render, never a crash). The seeds of the "pbrt" libFuzzer target are these files.
"""
from corpus_cases import TINY, case

HEAD = ('LookAt 0 0 -5  0 0 0  0 1 0\nCamera "perspective" "float fov" [40]\n'
        'Film "rgb" "integer xresolution" [8] "integer yresolution" [8]\n'
        'Sampler "halton" "integer pixelsamples" 1\nIntegrator "volpath" "integer maxdepth" [2]\n'
        'WorldBegin\n')
TRI = 'Shape "trianglemesh" "point3 P" [-1 -1 0 1 -1 0 0 1 0] "integer indices" [0 1 2]\n'
FULL = HEAD + (
    'LightSource "point" "rgb I" [5 5 5] "point3 from" [0 2 -2]\n'
    'LightSource "spot" "blackbody I" 3000 "float coneangle" 40 "float power" 10\n'
    'LightSource "distant" "rgb L" [1 1 1] "point3 to" [0 -1 0]\n'
    'LightSource "infinite" "rgb L" [0.1 0.1 0.1]\n'
    'Texture "k" "spectrum" "checkerboard" "rgb tex1" [1 0 0]\n'
    'Texture "c" "float" "constant" "float value" 0.3\n'
    'MakeNamedMaterial "gold" "string type" "conductor" "spectrum eta" "metal-Au-eta" '
    '"spectrum k" "metal-Au-k" "float uroughness" 0.2 "float vroughness" 0.05\n'
    'MakeNamedMaterial "red" "string type" "diffuse" "texture reflectance" "k"\n'
    'MakeNamedMaterial "m" "string type" "mix" "string materials" ["gold" "red"] "texture amount" "c"\n'
    'AttributeBegin NamedMaterial "m" ' + TRI + 'AttributeEnd\n'
    'AttributeBegin Material "coateddiffuse" "float roughness" 0.1 Translate 1 0 0 Rotate 30 0 1 0\n'
    '  Shape "sphere" "float radius" 0.3\nAttributeEnd\n'
    'AttributeBegin AreaLightSource "diffuse" "blackbody L" [6500] "bool twosided" true "float power" 5\n'
    '  ReverseOrientation Shape "disk" "float radius" 0.2 "float alpha" 0.5\nAttributeEnd\n'
    'ObjectBegin "o" Material "dielectric" "spectrum eta" "glass-BK7"\n'
    '  Shape "bilinearmesh" "point3 P" [0 0 0 1 0 0 0 1 0 1 1 0]\nObjectEnd\n'
    'ObjectInstance "o" Translate 0 -1 0 ObjectInstance "o"\n'
    'CoordinateSystem "here" Identity CoordSysTransform "here"\n'
    'Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]\n')

BAD = [
    ("string", 'Shape "x" "string a" "open\n', "scene.pbrt:1"),
    ("escape", 'Shape "x" "string a" "\\q"\n', "unknown escape"),
    ("number", "Translate 1 2 3x\n", "malformed number"),
    ("char", "Translate 1 2 3 @\n", "unexpected character"),
    ("type", HEAD + 'Shape "sphere" "flaot radius" 1\n', "unknown parameter type"),
    ("decl", HEAD + 'Shape "sphere" "float" 1\n', '"type name"'),
    ("twice", HEAD + 'Shape "sphere" "float radius" 1 "float radius" 2\n', "given twice"),
    ("bracket", HEAD + 'Shape "sphere" "float radius" [1\n', "unterminated ["),
    ("count", HEAD + 'Shape "trianglemesh" "point3 P" [0 0 0 1]\n', "not a multiple of 3"),
    ("index", HEAD + 'Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 -1]\n',
     "out of range"),
    ("float-index", HEAD + 'Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "integer indices" [0 1 1.5]\n',
     "expected an integer"),
    ("uv-count", HEAD + 'Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 0 1 0] "point2 uv" [0 0]\n',
     "one value per point"),
    ("radius", HEAD + 'Shape "sphere" "float radius" -1\n', "must be > 0"),
    ("lookat", "LookAt 0 0 0 0 0 0 0 1 0\n", "LookAt"),
    ("lookat-up", "LookAt 0 0 0 0 1 0 0 1 0\n", "parallel"),
    ("rotate", "Rotate 10 0 0 0\n", "no direction"),
    ("projective", "Transform [1 0 0 1 0 1 0 0 0 0 1 0 0 0 0 1]\n", "projective"),
    ("attr-end", "AttributeEnd\n", "without a matching begin"),
    ("object-end", "ObjectEnd\n", "ObjectEnd without ObjectBegin"),
    ("object-open", HEAD + 'ObjectBegin "a"\n' + TRI, "without ObjectEnd"),
    ("object-twice", HEAD + 'ObjectBegin "a" ObjectEnd ObjectBegin "a"\n', "defined twice"),
    ("object-nested", HEAD + 'ObjectBegin "a" ObjectBegin "b"\n', "inside the definition"),
    ("instance", HEAD + 'ObjectInstance "none"\n', "no object"),
    ("named", HEAD + 'NamedMaterial "none"\n', "no material"),
    ("mix", HEAD + 'Material "mix" "string materials" ["a" "b"]\n', "no material"),
    ("texture", HEAD + 'Material "diffuse" "texture reflectance" "none"\n', "no texture"),
    ("material-twice", HEAD + 'MakeNamedMaterial "a" "string type" "diffuse"\n'
     'MakeNamedMaterial "a" "string type" "diffuse"\n', "defined twice"),
    ("material-type", HEAD + 'MakeNamedMaterial "a"\n', 'no "string type"'),
    ("eta", HEAD + 'Material "dielectric" "float eta" -2\n', "out of range"),
    ("film", 'Film "rgb" "integer xresolution" [-5]\n', "out of range"),
    ("spp", 'Sampler "halton" "integer pixelsamples" 0\n', "must be >= 1"),
    ("depth", 'Integrator "path" "integer maxdepth" -1\n', "out of range"),
    ("camera", HEAD + 'Camera "perspective"\n', "inside the world block"),
    ("fov", 'Camera "perspective" "float fov" 180\nWorldBegin\n' + TRI, "out of range"),
    ("directive", "Frobnicate\n", "unknown directive"),
    ("value", "42\n", "expected a directive"),
    ("empty", "", "no shapes"),
    ("blackbody", HEAD + 'LightSource "point" "blackbody I" -5\n', "temperature"),
    ("spectrum", HEAD + 'LightSource "point" "spectrum I" [500 1 400 1]\n', "must increase"),
    ("include-escape", 'Include "../x.pbrt"\n', "x.pbrt"),
    ("include-absolute", 'Include "/etc/passwd"\n', "/etc/passwd"),
    ("include-missing", 'Include "missing.pbrt"\n', "missing.pbrt"),
    ("include-cycle", 'Include "scene.pbrt"\n', "deep"),
    ("ply-escape", HEAD + 'Shape "plymesh" "string filename" "../a.ply"\n', "a.ply"),
    ("texture-escape", HEAD + 'Texture "t" "spectrum" "imagemap" "string filename" "/tmp/x.png"\n',
     "x.png"),
    ("ply-missing", HEAD + 'Shape "plymesh" "string filename" "none.ply"\n', "none.ply"),
]


def pbrt_case(name, files, expect="any", needle=None):
    case("pbrt-" + name, files, ["render", "scene.pbrt"] + TINY, expect, needle=needle)


def mutate(rng, text):
    """One random edit: delete, duplicate or swap a span, or insert a token."""
    tokens = ['"', "[", "]", "-1e39", "0", "AttributeEnd", "ObjectBegin", '"float x"', "#", "\\",
              "Include", "nan", '"integer indices"', "\x00", "\xff"]
    i, j = sorted(rng.randrange(len(text) + 1) for _ in range(2))
    kind = rng.randrange(4)
    if kind == 0:
        return text[:i] + text[j:]
    if kind == 1:
        return text[:j] + text[i:j] + text[j:]
    if kind == 2:
        return text[:i] + rng.choice(tokens) + text[i:]
    return text[i:j] + text[:i] + text[j:]


def pbrt_cases(rng):
    pbrt_case("full", {"scene.pbrt": FULL}, "ok")
    pbrt_case("include", {"scene.pbrt": HEAD + 'Include "geometry.pbrt"\n', "geometry.pbrt": TRI}, "ok")
    pbrt_case("import", {"scene.pbrt": HEAD + 'Import "geometry.pbrt"\n', "geometry.pbrt": TRI}, "ok")
    for name, text, needle in BAD:
        pbrt_case(name, {"scene.pbrt": text}, "error", needle)
    for k in range(40):
        text = FULL
        for _ in range(1 + rng.randrange(3)):
            text = mutate(rng, text)
        pbrt_case("mutation-%02d" % k, {"scene.pbrt": text})
