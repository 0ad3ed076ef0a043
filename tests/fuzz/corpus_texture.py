# SPDX-License-Identifier: MIT
"""Cases for the texture loader (PNG, JPEG, HDR and what stb may guess): truncations, flips,
declared sizes, the libFuzzer findings, special files.
"""
import struct

from corpus_cases import TEXTURED, TINY, case
from corpus_images import hdr, jpeg, jpeg_big_dht, jpeg_declared, png


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


def environment_map_cases():
    """The environment map (scene.json "environment"): the same image loaders behind another key,
    and its own checks (zero power, scale). Uses its own random numbers: the cases before keep
    their bytes."""
    import json
    import random
    from corpus_cases import BASE_SCENE, TRIANGLE

    rng = random.Random(17)

    def env_case(name, data, expect="any", env_file="sky.hdr", extra=None, needle=None):
        scene = dict(BASE_SCENE, environment=dict({"file": env_file}, **(extra or {})))
        files = {"tri.obj": TRIANGLE, "scene.json": json.dumps(scene)}
        if data is not None:
            files[env_file] = data
        case("envmap-" + name, files, ["render", "scene.json"] + TINY, expect, needle=needle)

    good = hdr(16, 8)
    env_case("hdr-valid", good, "ok")
    env_case("hdr-rotated-scaled", good, "ok", extra={"rotation": -725.5, "scale": 3})
    for cut in (1, 8, 30, len(good) // 2, len(good) - 12):
        env_case("hdr-truncated-%d" % cut, good[:len(good) - cut], "error")
    for i in range(4):
        b = bytearray(good)
        for _ in range(3):
            b[rng.randrange(40, len(b))] = rng.randrange(256)
        env_case("hdr-flipped-%02d" % i, bytes(b))
    env_case("hdr-huge-declared", hdr(16, 1, declared=(16000000, 16000000)), "error")
    env_case("scale-zero", good, "error", extra={"scale": 0}, needle="zero total power")
    env_case("scale-negative", good, "error", extra={"scale": -1}, needle="environment.scale")
    env_case("exr-garbage", b"v/1\x01" + bytes(40), "error", env_file="sky.exr")
    env_case("missing", None, "error", needle="sky.hdr")
    env_case("png", png(4, 4), "error", env_file="sky.png")
