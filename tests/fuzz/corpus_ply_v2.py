# SPDX-License-Identifier: MIT
"""Hostile PLY cases (issue 42), beside corpus_ply.py's: the three formats truncated at many
points, element counts that lie both ways, list lengths 0, 2 and 255 for every count type,
unknown elements and header lines of other writers, tristrips, point clouds.
"""
import struct

from corpus_cases import TINY, case
from corpus_ply import QUAD, ascii_ply, binary_ply

HEAD = "ply\nformat %s 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"


def ply_v2_case(name, content, expect="any", needle=None):
    case("ply-v2-" + name, {"x.ply": content}, ["render", "x.ply"] + TINY, expect, needle=needle)


def strips(fmt, n_vertices, strip, index_type="int"):
    head = (HEAD % (fmt, n_vertices) + "element tristrips 1\nproperty list int %s vertex_indices\n"
            "end_header\n" % index_type)
    vertices = [(i % 3, i // 3, 0) for i in range(n_vertices)]
    if fmt == "ascii":
        return head + "".join("%d %d %d\n" % v for v in vertices) + "%d %s\n" % (
            len(strip), " ".join(str(i) for i in strip))
    order = "<" if fmt == "binary_little_endian" else ">"
    code = {"int": "i", "short": "h", "uint": "I"}[index_type]
    return (head.encode() + b"".join(struct.pack(order + "3f", *v) for v in vertices) +
            struct.pack(order + "i", len(strip)) + b"".join(struct.pack(order + code, i) for i in strip))


def ply_v2_cases():
    faces = [[0, 1, 2], [0, 2, 3]]
    files = {"ascii": ascii_ply(QUAD, faces), "le": binary_ply(QUAD, faces),
             "be": binary_ply(QUAD, faces, big=True)}
    # Truncated at ten points of the body (and inside the header).
    for fmt, content in files.items():
        data = content.encode() if isinstance(content, str) else content
        body = data.index(b"end_header\n") + len(b"end_header\n")
        for k in range(10):
            cut = body - 20 + (len(data) - body + 20) * k // 10
            ply_v2_case("truncated-%s-%d" % (fmt, k), data[:cut], "error")
    # Counts that lie: more or fewer vertices and faces than the data holds.
    for fmt, big in (("ascii", None), ("le", False), ("be", True)):
        for what, delta in (("vertex", 1), ("vertex", -1), ("vertex", -4), ("face", 1), ("face", -1),
                            ("face", -2), ("vertex", 10 ** 6)):
            content = ascii_ply(QUAD, faces) if big is None else binary_ply(QUAD, faces, big=big)
            data = content.encode() if isinstance(content, str) else content
            old = ("element %s %d" % (what, 4 if what == "vertex" else 2)).encode()
            new = ("element %s %d" % (what, (4 if what == "vertex" else 2) + delta)).encode()
            ply_v2_case("count-%s-%s%+d" % (fmt, what, delta), data.replace(old, new, 1))
    # List lengths 0, 2 and 255 with each count type.
    for count_type, code in (("uchar", "B"), ("ushort", "H"), ("uint", "I"), ("char", "b"), ("int", "i")):
        for n in (0, 2, 255):
            head = (HEAD % ("binary_little_endian", 4) + "element face 1\nproperty list %s int "
                    "vertex_indices\nend_header\n" % count_type).encode()
            body = b"".join(struct.pack("<3f", *v) for v in QUAD)
            if count_type == "char" and n == 255:
                body += struct.pack("<b", -1)
            else:
                body += struct.pack("<" + code, n)
            body += b"".join(struct.pack("<i", i % 4) for i in range(n))
            ply_v2_case("list-%s-%d" % (count_type, n), head + body)
        ply_v2_case("list-%s-ascii-0-2" % count_type,
                    ascii_ply(QUAD, [[], [0, 1], [0, 1, 2]]).replace("uchar int", count_type + " int"))
    # Unknown elements and header lines.
    extra = [("element-scalar", "element edge 2\nproperty int a\nproperty int b\n", "0 1\n1 2\n"),
             ("element-list", "element material 1\nproperty list uchar float c\n", "3 1 2 3\n"),
             ("element-empty", "element nothing 0\n", ""),
             ("element-no-properties", "element bare 3\n", "")]
    for name, header, body in extra:
        ply_v2_case("unknown-" + name, ascii_ply(QUAD, faces, header) + body, "ok")
    for name, line in [("created-by", "Created by Blender3D 247 - www.blender.org, source file: 'a.blend'"),
                       ("long", "x" * 1000), ("one-word", "vertices"), ("many-words", "a b c d e f g h"),
                       ("tab", "\tweird\tline"), ("binary", "\x01\x02\x7f"),
                       ("keyword-long", "property float " + "x" * 300)]:
        content = ascii_ply(QUAD, faces).replace("format ascii 1.0\n", "format ascii 1.0\n" + line + "\n")
        ply_v2_case("header-" + name, content, "error" if name == "keyword-long" else "ok",
                    needle="longer than" if name == "keyword-long" else None)
    ply_v2_case("header-nul", ascii_ply(QUAD, faces).replace("format ascii 1.0\n", "format ascii 1.0\nab\0c\n"),
                "error", needle="NUL")
    # tristrips, in the three formats.
    for fmt in ("ascii", "binary_little_endian", "binary_big_endian"):
        short = fmt.split("_")[1] if "_" in fmt else fmt
        ply_v2_case("strips-%s" % short, strips(fmt, 6, [0, 1, 2, 3, 4, -1, 5, 1, 2]), "ok")
        ply_v2_case("strips-%s-restarts-only" % short, strips(fmt, 3, [-1, -1, -1]), "error",
                    needle="no triangles")
        ply_v2_case("strips-%s-range" % short, strips(fmt, 3, [0, 1, 7]), "error", needle="tristrips 0")
        ply_v2_case("strips-%s-negative" % short, strips(fmt, 3, [0, 1, -2]), "error", needle="tristrips 0")
        ply_v2_case("strips-%s-degenerate" % short, strips(fmt, 3, [0, 0, 1, 1, 2, 2]), "error",
                    needle="no triangles")
    ply_v2_case("strips-uint--1", strips("binary_little_endian", 3, [0, 1, 2, 2 ** 32 - 1], "uint"), "error",
                needle="tristrips 0")
    ply_v2_case("strips-and-faces", ascii_ply(QUAD, faces, "element tristrips 1\nproperty list int int "
                                              "vertex_indices\n") + "4 0 1 2 3\n", "ok")
    ply_v2_case("strips-float", strips("ascii", 3, [0, 1, 2]).replace("int int", "int float"), "error",
                needle="float index type")
    # Point clouds: said in PLY's words.
    ply_v2_case("point-cloud", "ply\nformat ascii 1.0\n" + "element vertex 3\nproperty float x\n"
                "property float y\nproperty float z\nend_header\n0 0 0\n1 0 0\n0 1 0\n", "error",
                needle="a point cloud: 3 vertices")
    ply_v2_case("point-cloud-empty", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                "property float y\nproperty float z\nend_header\n", "error", needle="no vertices and no faces")
