# SPDX-License-Identifier: MIT
"""Cases for the checkpoint reader (host/dist/checkpoint.c, read by `pt render --resume`): a
well-formed checkpoint of another scene, then truncated, damaged, other-version, out-of-range and
missing ones, each a one-line error naming the file and the reason; and the seeds of the libFuzzer
target (fuzz_checkpoint.c), made for its fixed identity. The format is checkpoint.h's; hash64 is
scene/scene_hash.c's.
"""
import struct

from corpus_cases import TINY, TRIANGLE, case

M = (1 << 64) - 1
K1, K2 = 0xbf58476d1ce4e5b9, 0x9e3779b97f4a7c15
FILM_WORDS = 4


def hash64(data):
    h = 0x243f6a8885a308d3
    padded = data + b"\0" * (-len(data) % 8)
    for i in range(0, len(padded), 8):
        w = (struct.unpack_from("<Q", padded, i)[0] * K1) & M
        w ^= w >> 31
        h = ((h ^ w) * K2) & M
    z = h ^ len(data)
    z = ((z ^ (z >> 30)) * K1) & M
    z = ((z ^ (z >> 27)) * 0x94d049bb133111eb) & M
    return z ^ (z >> 31)


def checkpoint(width, height, spp, unit_spp, unit_rows, count, done, scene=0x0123456789abcdef,
               max_depth=8, seed=7, version=1, header_bytes=80, sums=None, fix_checksum=True,
               bitmap_bytes=None, flags=2):
    """done: the finished units (a list of unit numbers); bitmap_bytes: a shorter bitmap than count
    needs (a file that claims more than it holds); flags: 2 is the Sobol sampler, pt's default (a
    checkpoint of other settings is refused for that before anything else is compared)."""
    if bitmap_bytes is None:
        bitmap_bytes = (count + 7) // 8 + (-((count + 7) // 8) % 8)
    bitmap = bytearray(bitmap_bytes)
    for u in done:
        bitmap[u // 8] |= 1 << (u % 8)
    header = b"PTCKPT\r\n" + struct.pack("<IIQIIIIfIIIIIIIII", version, header_bytes, scene,
                                         max_depth, seed, 0, flags, 0.0, width, height, spp, unit_spp,
                                         unit_rows, count, len(done), FILM_WORDS, 0)
    words = width * height * FILM_WORDS
    body = header + bytes(bitmap) + (sums if sums is not None else
                                     b"".join(struct.pack("<Q", (i * 2654435761) & M)
                                              for i in range(words)))
    return body + struct.pack("<Q", hash64(body) if fix_checksum else 0)


def with_checksum(body):
    return body + struct.pack("<Q", hash64(body))


# The libFuzzer target's identity (fuzz_checkpoint.c): a 5x6 film, 4 spp, units of 1 spp x 2 rows.
FUZZ_GRID = dict(width=5, height=6, spp=4, unit_spp=1, unit_rows=2, count=12)


def checkpoint_seeds():
    good = checkpoint(done=[0, 3, 4, 11], **FUZZ_GRID)
    seeds = [good, checkpoint(done=list(range(12)), **FUZZ_GRID), checkpoint(done=[], **FUZZ_GRID),
             good[:len(good) // 2], good[:80], checkpoint(done=[1], version=2, **FUZZ_GRID),
             checkpoint(done=[1], seed=8, **FUZZ_GRID)]
    bad = bytearray(good)
    bad[100] ^= 4
    seeds.append(bytes(bad))
    return seeds


def checkpoint_case(name, content, expect, needle, setup=None):
    files = {"tri.obj": TRIANGLE}
    if content is not None:
        files["out.png.ptckpt"] = content
    case("ckpt-" + name, files, ["render", "tri.obj"] + TINY + ["--resume"], expect, needle=needle,
         setup=setup)


def checkpoint_cases():
    # TINY's render: an 8x8 film, 1 spp, max depth 2, seed 0: one unit (1 spp x 8 rows).
    tiny = dict(width=8, height=8, spp=1, unit_spp=1, unit_rows=8, count=1, max_depth=2, seed=0)
    good = checkpoint(done=[0], **tiny)
    checkpoint_case("other-scene", good, "error", "made for another scene")
    checkpoint_case("other-sampler", checkpoint(done=[0], flags=0, **tiny), "error",
                    "--sampler independent in it")
    checkpoint_case("other-spp", checkpoint(done=[0], **dict(tiny, spp=2, count=2)), "error",
                    "spp 2 in it, 1 here")
    checkpoint_case("other-units", checkpoint(done=[0], **dict(tiny, unit_rows=4, count=2)),
                    "error", "unit size differs")
    checkpoint_case("missing", None, "error", "start without --resume")
    checkpoint_case("empty", b"", "error", "not a pt checkpoint")
    checkpoint_case("magic", b"GIF89a\0\0" + good[8:], "error", "wrong magic")
    checkpoint_case("header-only", good[:80], "error", "truncated checkpoint")
    checkpoint_case("truncated", good[:-9], "error", "truncated checkpoint")
    checkpoint_case("trailing", good + b"\0", "error", "damaged checkpoint")
    checkpoint_case("version-2", checkpoint(done=[0], version=2, **tiny), "error",
                    "checkpoint format version 2")
    checkpoint_case("version-max", checkpoint(done=[0], version=0xffffffff, **tiny), "error",
                    "checkpoint format version 4294967295")
    flipped = bytearray(good)
    flipped[120] ^= 1
    checkpoint_case("checksum", bytes(flipped), "error", "checksum mismatch")
    checkpoint_case("checksum-zero", checkpoint(done=[0], fix_checksum=False, **tiny), "error",
                    "checksum mismatch")
    checkpoint_case("header-size", checkpoint(done=[0], header_bytes=81, **tiny), "error",
                    "header fields out of range")
    huge = dict(tiny, width=65536, height=65536)
    checkpoint_case("film-huge", checkpoint(done=[0], sums=b"", **huge), "error",
                    "truncated checkpoint")
    checkpoint_case("film-too-wide", checkpoint(done=[0], sums=b"", **dict(tiny, width=0xffffffff)),
                    "error", "header fields out of range")
    many = dict(tiny, count=0xffffffff)
    checkpoint_case("count-huge", checkpoint(done=[0], bitmap_bytes=8, **many), "error",
                    "truncated checkpoint")
    # A valid checksum over an inconsistent bitmap (a unit beyond the grid): refused all the same.
    body = bytearray(good[:-8])
    body[80] |= 2
    checkpoint_case("bitmap-stray", with_checksum(bytes(body)), "error", "made for another scene")
    # Special files where the checkpoint is read: refused by name before any read (a FIFO hung).
    checkpoint_case("folder", None, "error", "is a directory", setup="mkdir out.png.ptckpt")
    checkpoint_case("fifo", None, "error", "is a FIFO", setup="mkfifo out.png.ptckpt")
    checkpoint_case("device", None, "error", "is a character device",
                    setup="ln -s /dev/zero out.png.ptckpt")
    checkpoint_case("dangling-link", None, "error", "start without --resume",
                    setup="ln -s absent out.png.ptckpt")
    # One flipped bit anywhere (header, bitmap, sums, checksum): refused, never read as a film.
    for offset in (9, 17, 30, 45, 70, 80, len(good) - 9, len(good) - 1):
        flipped = bytearray(good)
        flipped[offset] ^= 0x10
        checkpoint_case("bit-%d" % offset, bytes(flipped), "error", None)
    for cut in (1, 7, 79, 81, 88, len(good) - 1):
        checkpoint_case("cut-%d" % cut, good[:cut], "error", None)
