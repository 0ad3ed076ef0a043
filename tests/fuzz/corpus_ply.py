# SPDX-License-Identifier: MIT
"""Cases for the PLY reader (host/io/ply_reader.c, ply_header.c): valid files in the three formats,
then bad headers, absurd counts, truncated and malformed data, each a one-line error naming the
file; and scenes naming PLY files with "ply".
"""
import json
import struct

from corpus_cases import BASE_SCENE, TINY, case

VERTEX_HEADER = "element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
FACE_HEADER = "element face %d\nproperty list uchar int vertex_indices\n"
QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]


def ascii_ply(vertices, faces, extra_header=""):
    head = "ply\nformat ascii 1.0\n" + VERTEX_HEADER % len(vertices) + FACE_HEADER % len(faces)
    body = "".join("%s %s %s\n" % v for v in vertices)
    body += "".join("%d %s\n" % (len(f), " ".join(str(i) for i in f)) for f in faces)
    return head + extra_header + "end_header\n" + body


def binary_ply(vertices, faces, big=False, truncate=None):
    order = ">" if big else "<"
    head = ("ply\nformat binary_%s_endian 1.0\n" % ("big" if big else "little") +
            VERTEX_HEADER % len(vertices) + FACE_HEADER % len(faces) + "end_header\n").encode()
    body = b"".join(struct.pack(order + "3f", *v) for v in vertices)
    body += b"".join(struct.pack(order + "B%di" % len(f), len(f), *f) for f in faces)
    return head + (body if truncate is None else body[:truncate])


def ply_case(name, content, expect="any", needle=None):
    case("ply-" + name, {"x.ply": content}, ["render", "x.ply"] + TINY, expect, needle=needle)


def ply_cases():
    ply_case("ascii", ascii_ply(QUAD, [[0, 1, 2, 3]]), "ok")
    ply_case("binary-le", binary_ply(QUAD, [[0, 1, 2], [0, 2, 3]]), "ok")
    ply_case("binary-be", binary_ply(QUAD, [[0, 1, 2, 3]], big=True), "ok")
    ply_case("concave", ascii_ply(QUAD + [(0.5, 0.5, 0)], [[0, 1, 4, 2, 3]]), "ok")
    ply_case("short-face", ascii_ply(QUAD, [[0, 1], [0, 1, 2]]), "ok")
    ply_case("skipped-element", ascii_ply(QUAD, [[0, 1, 2]], "element edge 1\nproperty list int uint v\n") +
             "2 0 1\n", "ok")
    ply_case("empty-faces-only", ascii_ply(QUAD, [[], []]), "error", "no triangles")
    ply_case("no-faces", "ply\nformat ascii 1.0\n" + VERTEX_HEADER % 1 + "end_header\n0 0 0\n", "error",
             "no triangles")
    bad = [("not-ply", "PLX\nformat ascii 1.0\nend_header\n", "not a PLY file"),
           ("float16", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float16 x\nend_header\n",
            "unknown property type 'float16'"),
           ("no-end-header", "ply\nformat ascii 1.0\n" + VERTEX_HEADER % 3, "missing end_header"),
           ("version", "ply\nformat ascii 1.1\nend_header\n", "unsupported format version"),
           ("format", "ply\nformat binary 1.0\nend_header\n", "unknown format"),
           ("count-negative", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "element count"),
           ("count-overflow", "ply\nformat ascii 1.0\nelement vertex 123456789012345678901\nend_header\n",
            "element count"),
           ("count-absurd", "ply\nformat ascii 1.0\n" + VERTEX_HEADER % 10**12 + "end_header\n0 0 0\n",
            "claims 1000000000000 'vertex' elements"),
           ("index-range", ascii_ply(QUAD, [[0, 1, 99]]), "vertex index 99 out of range (4 vertices)"),
           ("index-negative", ascii_ply(QUAD, [[0, -1, 2]]), "vertex index -1 out of range"),
           ("nan", ascii_ply([(0, 0, 0), (1, "nan", 0), (0, 1, 0)], [[0, 1, 2]]), "not finite"),
           ("overflow", ascii_ply([(0, 0, 0), (1, "1e39", 0), (0, 1, 0)], [[0, 1, 2]]), "not finite"),
           ("letters", ascii_ply([(0, 0, 0), (1, "a", 0), (0, 1, 0)], [[0, 1, 2]]), "bad number 'a'"),
           ("no-x", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\nend_header\n0\n",
            "lacks property x"),
           ("no-index-list", "ply\nformat ascii 1.0\n" + VERTEX_HEADER % 1 +
            "element face 1\nproperty int vertex_indices\nend_header\n0 0 0\n0\n", "lacks a vertex_indices list"),
           ("list-too-long", ascii_ply(QUAD, [[0, 1, 2]]).replace("\n3 0 1 2", "\n250 0 1 2"),
            "has a bad length 250"),
           ("face-256", ascii_ply(QUAD, [[0, 1, 2] * 86]).replace(
               "uchar int vertex_indices", "ushort int vertex_indices"), "the limit is 255"),
           ("binary-truncated", binary_ply(QUAD, [[0, 1, 2]]).replace(
               b"end_header", b"property int flags\nend_header"), "truncated binary data (face 0 of 1)"),
           ("ascii-truncated", ascii_ply(QUAD, [[0, 1, 2], [0, 2, 3]])[:-8], "unexpected end of data"),
           ("binary-absurd", binary_ply(QUAD, [[0, 1, 2]], truncate=20), "claims"),
           ("binary-be-index", binary_ply(QUAD, [[0, 1, 5]], big=True), "vertex index 5 out of range"),
           ("binary-be-nan", binary_ply([(0, 0, 0), (1, float("nan"), 0), (0, 1, 0)], [[0, 1, 2]], big=True),
            "not finite")]
    for name, content, needle in bad:
        ply_case(name, content, "error", needle)
    scene = json.loads(json.dumps(BASE_SCENE))
    tri = ascii_ply([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [[0, 1, 2]])
    for name, obj, expect, needle in [
            ("valid", {"ply": "tri.ply", "transform": [{"scale": 0.5}]}, "ok", None),
            ("other-extension", {"ply": "tri.data"}, "ok", None),
            ("both", {"ply": "tri.ply", "obj": "tri.obj"}, "error", "objects[0]"),
            ("neither", {"smooth": True}, "error", "objects[0]"),
            ("ply-of-obj", {"ply": "tri.obj"}, "error", "not a PLY file")]:
        scene["objects"] = [obj]
        case("json-ply-" + name, {"tri.ply": tri, "tri.data": tri, "tri.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                                  "scene.json": json.dumps(scene)},
             ["render", "scene.json"] + TINY, expect, needle=needle)
