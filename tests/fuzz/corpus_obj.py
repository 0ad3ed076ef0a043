# SPDX-License-Identifier: MIT
"""Cases for the OBJ loader and the MTL files it reads: indices, values, junk, special files.
"""
from corpus_cases import TEXTURED, TINY, TRIANGLE, case
from corpus_images import png


def obj_case(name, text, expect="any", needle=None, extra=None, setup=None, path="x.obj"):
    files = {path: text} if text is not None else {}
    files.update(extra or {})
    case("obj-" + name, files, ["render", path] + TINY, expect, needle=needle, setup=setup)


def obj_cases(rng):
    v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
    obj_case("valid", TRIANGLE, "ok")
    for name, face in [("zero", "f 0 1 2"), ("too-big", "f 1 2 4"), ("neg-too-far", "f -4 -2 -1"),
                       ("huge", "f 1 2 99999999999999999999"), ("int-max", "f 1 2 2147483647"),
                       ("int-min", "f 1 2 -2147483648"), ("texcoord-missing", "f 1/1 2/2 3/3"),
                       ("normal-missing", "f 1//1 2//1 3//1"), ("letters", "f a b c"),
                       ("slashes", "f 1/// 2 3"), ("empty-parts", "f / / /"), ("two-corners", "f 1 2"),
                       ("one-corner", "f 1"), ("no-corners", "f"), ("repeated", "f 1 1 1"),
                       ("mixed-format", "f 1 2/1 3//1"), ("plus-sign", "f +1 +2 +3"),
                       ("float-index", "f 1.5 2 3"), ("hex-index", "f 0x1 2 3")]:
        obj_case("index-" + name, v3 + face + "\n", "any" if name in ("repeated", "plus-sign",
                 "two-corners", "one-corner", "no-corners") else "error")
    obj_case("corners-255", "".join("v %d %d 0\n" % (i % 16, i // 16) for i in range(255)) +
             "f " + " ".join(str(i + 1) for i in range(255)) + "\n")
    obj_case("corners-256", v3 + "f " + " ".join(["1", "2", "3"] * 86) + "\n", "error")
    obj_case("collinear-ngon", "".join("v %d 0 0\n" % i for i in range(50)) +
             "f " + " ".join(str(i + 1) for i in range(50)) + "\n", "error")
    obj_case("all-same-vertex", v3 + "f 1 1 1 1 1 1\n", "error")
    obj_case("bowtie", "v 0 0 0\nv 1 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n")
    obj_case("nonplanar", "v 0 0 0\nv 1 0 0\nv 1 1 1\nv 0 1 -1\nf 1 2 3 4\n")
    for name, v in [("nan", "v nan 0 0"), ("inf", "v inf 0 0"), ("overflow", "v 1e39 0 0"),
                    ("underflow", "v 1e-50 0 0"), ("text", "v a b c"), ("short", "v 1 2"),
                    ("long", "v 1 2 3 4 5 6 7 8"), ("huge-exponent", "v 1e999999999 0 0"),
                    ("hex-float", "v 0x1p3 0 0"), ("vn-nan", "vn nan 0 0"), ("vt-nan", "vt nan 0"),
                    ("vt-empty", "vt"), ("vn-zero", "vn 0 0 0")]:
        obj_case("value-" + name, v + "\n" + TRIANGLE)
    for i in range(12):
        junk = bytes(rng.randrange(256) for _ in range(rng.choice([16, 300, 5000])))
        obj_case("junk-%02d" % i, junk, "error")
    for i in range(10):
        text = bytearray((TRIANGLE * 3).encode())
        for _ in range(rng.randint(1, 3)):
            text[rng.randrange(len(text))] = rng.choice(b"0123456789 /-.ef\n\t\r")
        obj_case("mutated-%02d" % i, bytes(text))
    obj_case("png-bytes", png(2, 2), "error", needle="not an OBJ text file")
    obj_case("empty", "", "error", needle="no faces")
    obj_case("only-comments", "# nothing\n\n", "error", needle="no faces")
    obj_case("only-vertices", v3, "error", needle="no faces")
    obj_case("crlf", TRIANGLE.replace("\n", "\r\n"), "ok")
    obj_case("lone-cr", TRIANGLE.replace("\n", "\r"), "ok")
    obj_case("tabs", TRIANGLE.replace(" ", "\t"), "ok")
    obj_case("utf8-comment", "# \u00e9\u00e8 \u2603\n" + TRIANGLE, "ok")
    obj_case("long-line", TRIANGLE + "#" + "x" * (2 << 20) + "\n", "error", needle="line of")
    obj_case("many-groups", "".join("g g%d\no o%d\ns %d\n" % (i, i, i) for i in range(500)) + TRIANGLE)
    obj_case("usemtl-unknown", "usemtl nowhere\n" + TRIANGLE)
    obj_case("mtllib-missing", "mtllib nowhere.mtl\nusemtl a\n" + TRIANGLE)
    obj_case("mtllib-empty-name", "mtllib\n" + TRIANGLE)
    obj_case("faces-before-vertices", "f 1 2 3\n" + "v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    obj_case("dev-zero-symlink", None, "error", setup="ln -s /dev/zero x.obj",
             needle="character device")
    obj_case("dev-null-symlink", None, "error", setup="ln -s /dev/null x.obj")
    obj_case("fifo", None, "error", setup="mkfifo x.obj", needle="FIFO")
    obj_case("directory", None, "error", setup="mkdir x.obj")
    obj_case("dangling-symlink", None, "error", setup="ln -s nowhere.obj x.obj")
    obj_case("no-read-permission", TRIANGLE, "any", setup="chmod 000 x.obj")
    case("obj-dev-zero-direct", {}, ["render", "/dev/zero"] + TINY, "error", needle="/dev/zero")
    case("obj-proc-self-mem", {}, ["render", "/proc/self/mem"] + TINY, "error")
    obj_case("uppercase-extension", TRIANGLE, "ok", path="X.OBJ")
    obj_case("huge-vertex-count", "".join("v %d 0 0\n" % i for i in range(20000)) + TRIANGLE, "ok")


def mtl_case(name, mtl, expect="any", needle=None, setup=None, extra=None, obj=None):
    files = {"x.obj": obj or "mtllib m.mtl\nusemtl a\n" + TRIANGLE}
    if mtl is not None:
        files["m.mtl"] = mtl
    files.update(extra or {})
    case("mtl-" + name, files, ["render", "x.obj"] + TINY, expect, needle=needle, setup=setup)


def mtl_cases(rng):
    mtl_case("valid", "newmtl a\nKd 0.5 0.5 0.5\n", "ok")
    mtl_case("directory", None, "error", setup="mkdir m.mtl", needle="directory")
    mtl_case("dev-zero", None, "error", obj="mtllib /dev/zero\nusemtl a\n" + TRIANGLE,
             needle="/dev/zero")
    mtl_case("fifo", None, "error", setup="mkfifo m.mtl", needle="FIFO")
    mtl_case("missing", None, "ok")
    mtl_case("empty", "", "ok")
    mtl_case("png-bytes", png(2, 2))
    mtl_case("huge", None, "error", setup="truncate -s 65M m.mtl", needle="limit")
    for i in range(6):
        mtl_case("junk-%02d" % i, bytes(rng.randrange(256) for _ in range(500)))
    for name, line in [("kd-negative", "Kd -1 -1 -1"), ("kd-nan", "Kd nan nan nan"),
                       ("kd-huge", "Kd 1e30 1e30 1e30"), ("kd-text", "Kd a b c"), ("kd-short", "Kd 1"),
                       ("ke-huge", "Ke 1e38 1e38 1e38"), ("ke-inf", "Ke inf inf inf"),
                       ("ke-negative", "Ke -5 -5 -5"), ("ks-nan", "Ks nan 0 0"), ("ni-zero", "Ni 0"),
                       ("ni-negative", "Ni -1"), ("ni-nan", "Ni nan"), ("d-two", "d 2"),
                       ("d-negative", "d -1"), ("illum-99", "illum 99"), ("illum-negative", "illum -5"),
                       ("illum-huge", "illum 99999999999"), ("tf-nan", "Tf nan nan nan"),
                       ("ns-huge", "Ns 1e30"), ("map-missing", "map_Kd nowhere.png"),
                       ("map-empty", "map_Kd"), ("map-long", "map_Kd " + "p" * 3000 + ".png"),
                       ("map-dev-zero", "map_Kd /dev/zero"), ("map-directory", "map_Kd /"),
                       ("map-options", "map_Kd -bm 1 -o 0 0 0 -s 1 1 1 -clamp on t.png")]:
        mtl_case("value-" + name, "newmtl a\n" + line + "\n",
                 obj=TEXTURED.replace("usemtl t", "usemtl a") if name.startswith("map") else None)
    mtl_case("newmtl-no-name", "newmtl\nKd 1 0 0\n")
    mtl_case("duplicate-newmtl", "newmtl a\nKd 1 0 0\nnewmtl a\nKd 0 1 0\n", "ok")
    mtl_case("long-line", "newmtl a\n#" + "x" * (2 << 20) + "\n")
