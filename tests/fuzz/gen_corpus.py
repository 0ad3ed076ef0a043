#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""gen_corpus.py OUT [--seeds DIR]: writes the malformed-input corpus into OUT/cases/ (one folder
per case); with --seeds, also the seed inputs of the libFuzzer targets (DIR/scene, DIR/obj,
DIR/texture: the corpus's scene files, OBJ+MTL pairs and images).

Each case folder holds its input files and case.json:
  args    the pt command line (after the binary); run with the case folder as working directory.
          "{repo}" is replaced by the repository root at replay time.
  env     variables set for the run (on top of the replay's own); a value of null unsets one.
  expect  "ok" (exit 0), "error" (non-zero exit and one "pt: ..." line last on stderr) or "any"
          (either of those); never a signal, a sanitizer report, a hang or a silent failure.
  needle  optional text the error line must contain (the file or value it names).
  setup   optional shell run in the case folder before pt ($PT_FUZZ_CACHE: a warm kernel cache).
  known   a known failure owned elsewhere (reported, not counted as failed): remove once fixed.
  timeout seconds instead of the replay's default (more for a cold kernel compile, less for a
          known hang).
Deterministic: the same corpus every run (seeded), so a failure names a case that stays put.
"""
import json
import os
import random
import shutil
import struct
import sys
import zlib

TINY = ["--width", "8", "--height", "8", "--spp", "1", "--max-depth", "2", "--device", "cpu",
        "--quiet", "-o", "out.png"]
TRIANGLE = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
TEXTURED = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl t\nf 1/1 2/2 3/3\n"
BASE_SCENE = {
    "camera": {"eye": [0.3, 0.3, 2], "target": [0.3, 0.3, 0], "up": [0, 1, 0], "fov_y": 40},
    "film": {"width": 8, "height": 8},
    "render": {"spp": 1, "max_depth": 2},
    "objects": [{"obj": "tri.obj"}],
    "background": [1, 1, 1],
}

cases = []


def case(name, files, args, expect="any", env=None, needle=None, setup=None, known=None,
         timeout=None):
    cases.append(dict(name=name, files=files, args=args, expect=expect, env=env or {},
                      needle=needle, setup=setup, known=known, timeout=timeout))


# ---- Images, written here so the corpus needs no committed binaries --------------------------

def png(width, height, declared=None):
    """A valid RGBA PNG; `declared` overrides the IHDR size (the data stays width x height)."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    w, h = declared or (width, height)
    rows = []
    for y in range(height):
        row = b"\0"
        for x in range(width):
            row += bytes((x * 40 % 256, y * 40 % 256, 128, 255))
        rows.append(row)
    raw = b"".join(rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def jpeg(width=8, height=8):
    """A baseline greyscale JPEG whose every 8x8 block is flat grey: one DC and one AC Huffman
    code, both "0", so each block is the two bits 00 (DC difference 0, end of block)."""
    def segment(marker, data):
        return b"\xff" + bytes((marker,)) + struct.pack(">H", len(data) + 2) + data
    blocks = ((width + 7) // 8) * ((height + 7) // 8)
    bits = "00" * blocks
    bits += "1" * (-len(bits) % 8)
    scan = bytes(int(bits[i:i + 8], 2) for i in range(0, len(bits), 8))
    scan = scan.replace(b"\xff", b"\xff\x00")
    one_code = bytes([1] + [0] * 15)  # one code of length 1
    return (b"\xff\xd8" +
            segment(0xDB, b"\x00" + bytes([1] * 64)) +
            segment(0xC0, b"\x08" + struct.pack(">HH", height, width) + b"\x01\x01\x11\x00") +
            segment(0xC4, b"\x00" + one_code + b"\x00") +
            segment(0xC4, b"\x10" + one_code + b"\x00") +
            segment(0xDA, b"\x01\x01\x00\x00\x3f\x00") + scan + b"\xff\xd9")


def hdr(width, height, rle=True, declared=None):
    w, h = declared or (width, height)
    out = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w)
    for _ in range(height):
        if rle:
            out += bytes((2, 2, width >> 8, width & 255))
            for channel in range(4):
                left = width
                while left:
                    run = min(left, 127)
                    out += bytes((128 + run, 128 if channel == 3 else 90))
                    left -= run
        else:
            out += bytes((200, 100, 50, 128)) * width
    return out


# ---- JSON scenes ---------------------------------------------------------------------------------

def scene_case(name, text, expect="any", needle=None, extra_files=None, args_extra=None):
    files = {"tri.obj": TRIANGLE, "scene.json": text}
    files.update(extra_files or {})
    case("json-" + name, files, ["render", "scene.json"] + TINY + (args_extra or []), expect,
         needle=needle)


def json_cases(rng):
    base = json.dumps(BASE_SCENE, indent=1)
    scene_case("valid", base, "ok")
    for i, cut in enumerate(range(1, len(base), max(1, len(base) // 20))):
        scene_case("truncated-%02d" % i, base[:cut], "error", needle="scene.json")
    for i in range(15):
        b = bytearray(base.encode())
        for _ in range(rng.randint(1, 4)):
            b[rng.randrange(len(b))] = rng.randrange(256)
        scene_case("byteflip-%02d" % i, bytes(b))
    for name, text in [("empty", ""), ("blank", "  \n\t\n"), ("null", "null"), ("array", "[]"),
                       ("number", "42"), ("string", '"scene"'), ("nul-byte", base[:20] + "\0" + base[20:]),
                       ("bom", "\ufeff" + base), ("trailing-garbage", base + "}}"),
                       ("trailing-comma", base[:-2] + ",\n}"), ("comment", "// c\n" + base),
                       ("single-quotes", base.replace('"', "'")), ("two-objects", base + base),
                       ("unclosed-string", '{"objects": [{"obj": "tri.obj}]}'),
                       ("nan-literal", base.replace('"fov_y": 40', '"fov_y": NaN')),
                       ("inf-literal", base.replace('"fov_y": 40', '"fov_y": Infinity')),
                       ("binary", bytes(range(256)) * 4)]:
        scene_case(name, text)
    values = {"null": None, "true": True, "string": "x", "empty-array": [], "object": {},
              "four": [1, 2, 3, 4], "zero": 0, "minus-one": -1, "huge": 1e308,
              "int-overflow": 2147483648, "tiny": 5e-324, "huge-string": "s" * 100000}
    paths = ["camera", "camera.eye", "camera.target", "camera.up", "camera.fov_y", "camera.aperture",
             "camera.focus_distance", "film", "film.width", "film.height", "render", "render.spp",
             "render.max_depth", "background", "objects", "objects.0", "objects.0.obj"]
    for path in paths:
        for vname, value in values.items():
            scene = json.loads(json.dumps(BASE_SCENE))
            node, keys = scene, path.split(".")
            for k in keys[:-1]:
                node = node[int(k)] if k.isdigit() else node[k]
            last = keys[-1]
            if last.isdigit():
                node[int(last)] = value
            else:
                node[last] = value
            scene_case("type-%s-%s" % (path, vname), json.dumps(scene))
    for where in ["", "camera", "film", "render", "objects.0"]:
        scene = json.loads(json.dumps(BASE_SCENE))
        node = scene
        for k in filter(None, where.split(".")):
            node = node[int(k)] if k.isdigit() else node[k]
        node["bogus_key"] = 1
        scene_case("unknown-key-%s" % (where or "root"), json.dumps(scene), "error",
                   needle="bogus_key")
    scene_case("deep-array", '{"objects": ' + "[" * 20000 + "]" * 20000 + "}", "error")
    scene_case("deep-object", '{"camera": ' + '{"a":' * 5000 + "1" + "}" * 5000 + "}", "error")
    long_name = "d" * 5000 + ".obj"
    scene = json.loads(json.dumps(BASE_SCENE))
    scene["objects"] = [{"obj": long_name}]
    scene_case("long-obj-path", json.dumps(scene), "error")
    scene["objects"] = [{"obj": "tri.obj"}] * 2000
    scene_case("many-objects", json.dumps(scene), "ok")
    scene["objects"] = []
    scene_case("no-objects", json.dumps(scene), "error")
    for special in ["/dev/zero", "/dev/null", "/", ".", "fifo.obj", "/proc/self/mem", "tri.obj/x"]:
        scene = json.loads(json.dumps(BASE_SCENE))
        scene["objects"] = [{"obj": special}]
        setup = "mkfifo fifo.obj" if special == "fifo.obj" else None
        cases.append(dict(name="json-object-%s" % special.strip("/").replace("/", "-") or "root",
                          files={"tri.obj": TRIANGLE, "scene.json": json.dumps(scene)},
                          args=["render", "scene.json"] + TINY, expect="error", env={},
                          needle=None, setup=setup, known=None, timeout=None))
    case("json-scene-is-fifo", {}, ["render", "scene.json"] + TINY, "error", setup="mkfifo scene.json",
         timeout=5)
    case("json-scene-is-dev-zero", {}, ["render", "/dev/zero"] + TINY, "error")
    case("json-huge-file", {"tri.obj": TRIANGLE}, ["render", "scene.json"] + TINY, "error",
         setup="truncate -s 70M scene.json")


# ---- OBJ -----------------------------------------------------------------------------------------

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


# ---- MTL -----------------------------------------------------------------------------------------

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


# ---- Textures ------------------------------------------------------------------------------------

def texture_case(name, data, expect="any", needle=None, setup=None, tex="t.png"):
    files = {"x.obj": TEXTURED, "m.mtl": "newmtl t\nKd 1 1 1\nmap_Kd %s\n" % tex}
    if data is not None:
        files[tex] = data
    case("tex-" + name, files, ["render", "x.obj"] + TINY, expect, needle=needle, setup=setup)


def texture_cases(rng):
    good_png, good_jpg, good_hdr, flat_hdr = png(4, 4), jpeg(16, 16), hdr(16, 4), hdr(4, 2, rle=False)
    texture_case("png-valid", good_png, "ok")
    texture_case("jpg-valid", good_jpg, "ok", tex="t.jpg")
    texture_case("hdr-valid", good_hdr, "ok", tex="t.hdr")
    texture_case("hdr-flat-valid", flat_hdr, "ok", tex="t.hdr")
    for label, data, ext in [("png", good_png, "png"), ("jpg", good_jpg, "jpg"),
                             ("hdr", good_hdr, "hdr"), ("hdr-flat", flat_hdr, "hdr")]:
        cuts = sorted(set([1, 4, 8, 12, 20, 30, len(data) // 2, len(data) - 8, len(data) - 1]))
        if label == "hdr":  # every byte of the last scanline: the RLE loop that never ended
            cuts = sorted(set(cuts + list(range(1, 40))))
        for cut in cuts:
            if 0 < cut < len(data):
                # The last bytes of a PNG (IEND) or JPEG (EOI) are not needed to decode it.
                expect = "any" if label in ("png", "jpg") and cut <= 12 else "error"
                texture_case("%s-truncated-%d" % (label, cut), data[:len(data) - cut], expect,
                             tex="t." + ext)
    for i in range(10):
        b = bytearray(good_png)
        for _ in range(3):
            b[rng.randrange(8, len(b))] = rng.randrange(256)
        texture_case("png-flipped-%02d" % i, bytes(b))
    for i in range(6):
        b = bytearray(good_hdr)
        for _ in range(3):
            b[rng.randrange(40, len(b))] = rng.randrange(256)
        texture_case("hdr-flipped-%02d" % i, bytes(b), tex="t.hdr")
    texture_case("png-huge-declared", png(2, 2, declared=(100000, 100000)), "error")
    texture_case("png-wide-declared", png(2, 2, declared=(2 ** 31 - 1, 1)), "error")
    texture_case("jpg-huge-declared", jpeg_declared(65500, 65500), "error",
                 tex="t.jpg")
    texture_case("hdr-huge-declared", hdr(16, 1, declared=(16000000, 16000000)), "error",
                 tex="t.hdr")
    texture_case("hdr-zero-size", hdr(16, 1, declared=(0, 0)), "error", tex="t.hdr")
    texture_case("hdr-negative", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y -5 +X 16\n", "error",
                 tex="t.hdr")
    texture_case("hdr-no-resolution", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n", "error",
                 tex="t.hdr")
    texture_case("hdr-zero-run", hdr(16, 1)[:-8 * 2] + b"\x00" * 16, "error", tex="t.hdr")
    # libFuzzer finding: a DHT declaring over 256 codes made stb write past its Huffman tables.
    texture_case("jpg-dht-over-256-codes", jpeg_big_dht(), "error", tex="t.jpg", needle="256 codes")
    # libFuzzer finding: stb allocated a chunk's declared length (2 GiB) before reading it.
    texture_case("png-chunk-past-end", good_png[:33] + struct.pack(">I", 0x7ffffff0) + b"IDAT" +
                 good_png[41:60], "error", needle="chunk")
    # libFuzzer findings: stb ends an .hdr header at the first empty line (a zero-length RLE run
    # past a second resolution line looped forever); a DHT running past the end of the file.
    texture_case("hdr-second-resolution-line", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n-Y 1 +X 16\n\n"
                 b"-Y 1 +X 16\n" + bytes((2, 2, 0, 16, 0)) + b"\1" * 60, "error", tex="t.hdr",
                 needle="zero-length")
    texture_case("jpg-dht-past-end", jpeg(8, 8)[:-30] + b"\xff\xc4\x00\x14\x00\x01" + bytes(10) +
                 b"\x01\x00\xff\x29\xd9", "error", tex="t.jpg", needle="256 codes")
    texture_case("png-named-jpg", good_png, "ok", tex="t.jpg")
    texture_case("hdr-named-png", good_hdr, "ok")
    texture_case("text-named-png", b"this is not an image\n", "error")
    texture_case("empty", b"", "error")
    texture_case("directory", None, "error", setup="mkdir t.png")
    texture_case("fifo", None, "error", setup="mkfifo t.png", needle="FIFO")
    texture_case("dev-zero", None, "error", setup="ln -s /dev/zero t.png")
    texture_case("missing", None, "any")
    texture_case("bmp-truncated", b"BM" + b"\0" * 20, "error", tex="t.bmp")
    texture_case("gif-truncated", b"GIF89a\x10\x00\x10\x00", "error", tex="t.gif")
    texture_case("psd-header", b"8BPS" + b"\0" * 30, "error", tex="t.psd")


def jpeg_big_dht():
    """The flat JPEG with one more DC table (id 1) of 2 x 200 codes: stb 2.27 has room for 256."""
    data = jpeg(8, 8)
    table = b"\x01" + bytes([0] * 14 + [200, 200]) + bytes(400)
    segment = b"\xff\xc4" + struct.pack(">H", len(table) + 2) + table
    at = data.index(b"\xff\xc4")
    return data[:at] + segment + data[at:]


def jpeg_declared(width, height):
    """A JPEG whose frame header declares width x height but whose scan holds one block."""
    data = bytearray(jpeg(8, 8))
    at = data.index(b"\xff\xc0") + 5
    data[at:at + 4] = struct.pack(">HH", height, width)
    return bytes(data)


# ---- Outputs, command line, environment --------------------------------------------------------

def cli_cases():
    scene = {"tri.obj": TRIANGLE}
    base = ["render", "tri.obj", "--width", "8", "--height", "8", "--spp", "1", "--max-depth", "2",
            "--device", "cpu", "--quiet"]
    for name, out, setup, expect in [
            ("png", "o.png", None, "ok"), ("exr", "o.exr", None, "ok"), ("upper", "O.PNG", None, "ok"),
            ("tiff", "o.tiff", None, "error"), ("no-extension", "o", None, "error"),
            ("empty", "", None, "error"), ("dot-png", ".png", None, "ok"),
            ("directory", "d.png", "mkdir d.png", "error"),
            ("missing-folder", "no/such/dir/o.png", None, "error"),
            ("proc", "/proc/o.png", None, "error"),
            ("read-only-file", "ro.png", "touch ro.png && chattr +i ro.png 2>/dev/null || true", "any"),
            ("long-name", "n" * 300 + ".png", None, "error"),
            ("long-path", "/".join(["d" * 200] * 8) + "/o.png", None, "error")]:
        case("out-" + name, scene, base + ["-o", out], expect, setup=setup)
    case("out-dev-full", scene, base + ["-o", "full.png"], "error", setup="ln -s /dev/full full.png")
    case("out-preview-exr", scene, base + ["-o", "o.exr", "--preview"], "ok")
    case("out-default-folder-is-file", scene, base, "error", setup="touch out")
    case("out-aov-albedo", scene, base + ["-o", "a.png", "--aov", "albedo"], "ok")
    case("out-aov-depth-exr", scene, base + ["-o", "a.exr", "--aov", "depth"], "ok")

    opts = {"--spp": ["0", "-1", "abc", "1.5", "", "99999999999", "0x10", "1e3", " 1"],
            "--max-depth": ["0", "1025", "-3", "x", ""], "--width": ["0", "65537", "-8", "w", "1e9"],
            "--height": ["0", "65537", "h"], "--seed": ["-1", "abc", "99999999999999999999", "1.5"],
            "--exposure": ["nan", "inf", "-inf", "1e308", "x", ""],
            "--aov": ["shiny", "", "ALBEDO"], "--device": ["gpu", "9:9", "-1:0", "0:", ":0", "abc",
                                                            "0:0:0", "99999999999:0", ""],
            "--camera": ["{", "[]", '{"eye": "x"}', '{"fov_y": -1}', '{"bogus": 1}', "null", ""],
            "--frames": ["0", "-1", "x"], "--csv": ["", "/proc/x.csv"]}
    for opt, values in opts.items():
        for i, value in enumerate(values):
            args = [a for a in base]
            if opt in args:
                at = args.index(opt)
                args[at + 1] = value
            else:
                args += [opt, value]
            case("arg%s-%d" % (opt, i), scene, args + ["-o", "o.png"], "any")
        case("arg%s-missing-value" % opt, scene, ["render", "tri.obj", opt], "error")
    for name, args in [("none", []), ("unknown-command", ["frobnicate"]), ("help", ["help"]),
                       ("dash-h", ["-h"]), ("render-no-scene", ["render"]),
                       ("unknown-option", base + ["--bogus"]), ("two-scenes", base + ["tri.obj"]),
                       ("option-first", ["--spp", "1", "render", "tri.obj"]),
                       ("devices-extra", ["devices", "extra"]), ("devices", ["devices"]),
                       ("long-arg", ["render", "x" * 100000]),
                       ("non-utf8", ["render", "\udcff\udcfe.obj"]),
                       ("empty-scene-arg", ["render", ""]), ("repeated-spp", base + ["--spp", "1"]),
                       ("view-no-display", ["view", "tri.obj", "--device", "cpu", "--frames", "1"]),
                       ("bench-bad-csv", ["bench", "tri.obj", "--device", "cpu", "--spp", "1",
                                          "--width", "8", "--height", "8", "--csv", "/proc/x"])]:
        env = {"DISPLAY": None, "WAYLAND_DISPLAY": None} if name == "view-no-display" else None
        case("cli-" + name, scene, args, "any", env=env)


def env_cases():
    scene = {"tri.obj": TRIANGLE}
    base = ["render", "tri.obj"] + TINY
    # Valid non-default layouts are left out: each would compile the kernels once more.
    settings = [("PT_BVH_WIDTH", ["0", "1", "3", "16", "abc", "", "-2", "8", "2x"]),
                ("PT_BVH_QUANTIZED", ["2", "x", "", "0", "1"]),
                ("PT_NO_CACHE", ["1", "0", "yes", ""]),
                ("PT_LOCAL_SIZE", ["0", "-1", "abc", "1", "3", "100000", "99999999999"]),
                ("PT_CL_OPTIONS", ["-this-is-not-an-option", "-D"]),
                ("OCL_ICD_VENDORS", ["/nonexistent"])]
    for var, values in settings:
        for i, value in enumerate(values):
            case("env-%s-%d" % (var, i), scene, base, "any", env={var: value})
    cache_env = {"XDG_CACHE_HOME": "cache"}
    for name, xdg, setup in [("file", "f", "touch f"), ("proc", "/proc/cache", None),
                             ("missing-deep", "a/b/c/d", None), ("long", "l" * 3000, None),
                             ("relative-dot", ".", None), ("empty", "", None)]:
        case("env-cache-home-" + name, scene, base, "ok", env={"XDG_CACHE_HOME": xdg}, setup=setup)
    case("env-no-home", scene, base, "ok", env={"XDG_CACHE_HOME": None, "HOME": None})
    # Without POCL_CACHE_DIR, PoCL's cache is in the unusable cache home too (it offered no device).
    case("env-cache-home-file-pocl", scene, base, "ok",
         env={"XDG_CACHE_HOME": "f", "POCL_CACHE_DIR": None}, setup="touch f", timeout=120)
    # A warm cache copied in, then damaged: truncated at several sizes, zeroed, replaced.
    copy = 'mkdir -p cache && cp -r "$PT_FUZZ_CACHE/pt" cache/ && for f in cache/pt/*.bin; do '
    for name, damage in [("empty", ': > "$f"'), ("1-byte", 'truncate -s 1 "$f"'),
                         ("31-bytes", 'truncate -s 31 "$f"'), ("32-bytes", 'truncate -s 32 "$f"'),
                         ("1000-bytes", 'truncate -s 1000 "$f"'),
                         ("half", 'truncate -s $(( $(stat -c %s "$f") / 2 )) "$f"'),
                         ("minus-1", 'truncate -s -1 "$f"'), ("plus-zeros", 'truncate -s +4096 "$f"'),
                         ("flipped", 'printf x | dd of="$f" bs=1 seek=5000 conv=notrunc 2>/dev/null'),
                         ("garbage", 'head -c 100000 /dev/urandom > "$f"'),
                         ("directory", 'rm "$f" && mkdir "$f"'), ("fifo", 'rm "$f" && mkfifo "$f"'),
                         ("dev-zero", 'rm "$f" && ln -s /dev/zero "$f"'),
                         ("read-only-folder", 'chmod 555 cache/pt')]:
        case("cache-" + name, scene, base, "ok", env=cache_env, setup=copy + damage + "; done")


def as_bytes(content):
    return content.encode("utf-8", "surrogateescape") if isinstance(content, str) else content


def write_seeds(folder):
    for target in ("scene", "obj", "texture"):
        os.makedirs(os.path.join(folder, target), exist_ok=True)
    for i, c in enumerate(cases):
        files, seed = c["files"], None
        if c["name"].startswith("json-") and "scene.json" in files:
            target, seed = "scene", as_bytes(files["scene.json"])
        elif c["name"].startswith(("obj-", "mtl-")) and "x.obj" in files:
            target, seed = "obj", as_bytes(files["x.obj"])
            if "m.mtl" in files:
                seed += b"\n#MTL\n" + as_bytes(files["m.mtl"])
        elif c["name"].startswith("tex-"):
            images = [n for n in files if n.startswith("t.")]
            if images:
                target, seed = "texture", as_bytes(files[images[0]])
        if seed is not None and len(seed) < 1 << 20:
            with open(os.path.join(folder, target, "seed-%03d" % i), "wb") as f:
                f.write(seed)


def main():
    out = sys.argv[1]
    rng = random.Random(20261201)
    json_cases(rng)
    obj_cases(rng)
    mtl_cases(rng)
    texture_cases(rng)
    cli_cases()
    env_cases()
    root = os.path.join(out, "cases")
    shutil.rmtree(root, ignore_errors=True)
    os.makedirs(root)
    names = set()
    for i, c in enumerate(cases):
        name = "%03d-%s" % (i, "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in c["name"]))
        assert c["name"] not in names, c["name"]
        names.add(c["name"])
        folder = os.path.join(root, name[:120])
        os.makedirs(folder)
        for fname, content in c["files"].items():
            data = as_bytes(content)
            with open(os.path.join(folder, fname), "wb") as f:
                f.write(data)
        meta = {k: c[k] for k in ("args", "env", "expect", "needle", "setup", "known", "timeout")}
        with open(os.path.join(folder, "case.json"), "w") as f:
            json.dump(meta, f)
    print("gen_corpus: %d cases in %s" % (len(cases), root))
    if len(sys.argv) > 3 and sys.argv[2] == "--seeds":
        write_seeds(sys.argv[3])


if __name__ == "__main__":
    main()
