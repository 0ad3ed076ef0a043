# SPDX-License-Identifier: MIT
"""Grid files (issue 40: host/io/volume_vol.c, volume_nvdb.cc), each read by a scene whose world
medium is a grid medium (shared/DESIGN.md "Media"): Mitsuba 3 .vol files and NanoVDB .nvdb files
written here byte by byte (NanoVDB 32.x's layout: file header, grid metadata, grid, tree, root,
root tiles, lower internal nodes, leaves), valid small ones and hostile mutations: truncations,
bad magic, versions, codecs, encodings and channels, counts and offsets that do not fit or are
misaligned, huge and empty boxes, NaN and negative densities, overlapping tiles, random bytes.
The hostile ones must fail with one line naming the grid file, the valid ones render (both need
the scene parser of branch media40); random mutations do either.
"""
import json
import random
import struct

from corpus_cases import BASE_SCENE, TINY, TRIANGLE, case

NVDB_MAGIC = 0x304244566F6E614E  # "NanoVDB0"
NVDB_VERSION = (32 << 21) | (4 << 10) | 2
GRID_BYTES, TREE_BYTES, ROOT_BYTES, TILE_BYTES = 672, 64, 64, 32
LOWER_BYTES, LEAF_BYTES = 33856, 2144


def scene(grid_file, grid_name=None):
    medium = {"type": "grid", "file": grid_file, "density_scale": 2.0}
    if grid_name is not None:
        medium["grid"] = grid_name
    s = dict(BASE_SCENE, media={"smoke": medium}, medium="smoke")
    return json.dumps(s)


def volume_case(name, grid_file, content, expect, grid_name=None):
    case(name, {"scene.json": scene(grid_file, grid_name), "tri.obj": TRIANGLE, grid_file: content},
         ["render", "scene.json"] + TINY, expect, needle=grid_file if expect == "error" else None)


# --- Mitsuba 3 .vol ---------------------------------------------------------------------------

def vol(res=(4, 3, 2), values=None, magic=b"VOL", version=3, encoding=1, channels=1,
        bbox=(0.0, 0.0, 0.0, 1.0, 1.0, 1.0)):
    if values is None:
        values = [0.125 * (i % 9) for i in range(res[0] * res[1] * res[2] * max(channels, 0))]
    return (magic + bytes([version]) + struct.pack("<i3ii6f", encoding, *res, channels, *bbox) +
            struct.pack("<%df" % len(values), *values))


def vol_cases(rng):
    good = vol()
    volume_case("vol-valid", "x.vol", good, "ok")
    volume_case("vol-valid-named", "x.vol", good, "ok", grid_name="density")
    volume_case("vol-valid-trailing-bytes", "x.vol", good + b"\0" * 13, "ok")
    volume_case("vol-valid-negative-zero", "x.vol", vol(values=[-0.0] * 24), "ok")
    volume_case("vol-name-absent", "x.vol", good, "error", grid_name="temperature")
    for k in range(10):
        volume_case("vol-truncated-%d" % k, "x.vol", good[:len(good) * k // 10], "error")
    volume_case("vol-magic", "x.vol", vol(magic=b"VOX"), "error")
    for version in (0, 2, 4, 255):
        volume_case("vol-version-%d" % version, "x.vol", vol(version=version), "error")
    for encoding in (0, 2, 3, 4, -1, 1 << 30):
        volume_case("vol-encoding-%d" % encoding, "x.vol", vol(encoding=encoding), "error")
    for channels in (0, 3, -1, 1 << 30):
        volume_case("vol-channels-%d" % channels, "x.vol", vol(channels=channels, values=[0.5] * 24), "error")
    for res in ((0, 3, 2), (4, -3, 2), (2 ** 31 - 1, 2, 1), (65536, 65536, 1), (-1, -1, -1),
                (1, 1, 2 ** 30)):
        volume_case("vol-res-%d-%d-%d" % res, "x.vol", vol(res=res, values=[0.5] * 24), "error")
    for label, bbox in (("nan", (float("nan"), 0, 0, 1, 1, 1)), ("inf", (0, 0, 0, float("inf"), 1, 1)),
                        ("empty", (0, 0, 0, 1, 0, 1)), ("inverted", (1, 0, 0, 0, 1, 1))):
        volume_case("vol-bbox-" + label, "x.vol", vol(bbox=bbox), "error")
    for label, value in (("nan", float("nan")), ("negative", -1.0), ("inf", float("inf"))):
        values = [0.25] * 24
        values[13] = value
        volume_case("vol-voxel-" + label, "x.vol", vol(values=values), "error")
    for k in range(12):
        data = bytearray(good)
        for _ in range(rng.randint(1, 6)):
            data[rng.randrange(len(data))] = rng.randrange(256)
        volume_case("vol-random-%d" % k, "x.vol", bytes(data), "any")


# --- NanoVDB .nvdb ----------------------------------------------------------------------------

def root_key(x, y, z):
    return ((z & 0xFFFFFFFF) >> 12) | (((y & 0xFFFFFFFF) >> 12) << 21) | (((x & 0xFFFFFFFF) >> 12) << 42)


def leaf(origin, values, active=True):
    head = struct.pack("<3i3BB", *origin, 7, 7, 7, 2)
    mask = struct.pack("<8Q", *([0xFFFFFFFFFFFFFFFF if active else 0] * 8))
    return head + mask + struct.pack("<4f", min(values), max(values), 0, 0) + struct.pack("<512f", *values)


def lower(origin, tiles):
    """A lower internal node of only tiles: tiles maps offset n (z fastest) to an active value."""
    value_mask, table = [0] * 64, bytearray(4096 * 8)
    for n, v in tiles.items():
        value_mask[n >> 6] |= 1 << (n & 63)
        struct.pack_into("<f", table, 8 * n, v)
    head = struct.pack("<6iQ", *origin, *(c + 127 for c in origin), 0)
    return (head + struct.pack("<64Q", *value_mask) + bytes(512) + struct.pack("<4f", 0, 1, 0, 0) +
            bytes(16) + bytes(table))


def nvdb(leaves=(), lowers=(), root_tiles=(), bbox=((0, 0, 0), (7, 7, 7)), name=b"density",
         grid_type=1, voxel=0.5, translation=(1.0, -2.0, 0.5), codec=0):
    tiles = b"".join(struct.pack("<QqIf", root_key(*o), 0, state, v) + bytes(8) for o, state, v in root_tiles)
    root = struct.pack("<6iI5f", *bbox[0], *bbox[1], len(root_tiles), 0, 0, 1, 0, 0) + bytes(16)
    lower_at = TREE_BYTES + ROOT_BYTES + len(tiles)
    leaf_at = lower_at + LOWER_BYTES * len(lowers)
    tree = struct.pack("<4Q3I3IQ", leaf_at if leaves else 0, lower_at if lowers else 0, 0, TREE_BYTES,
                       len(leaves), len(lowers), 0, 0, 0, len(root_tiles), 512 * len(leaves))
    body = tree + root + tiles + b"".join(lowers) + b"".join(leaves)
    size = GRID_BYTES + len(body)
    mat = [voxel, 0, 0, 0, voxel, 0, 0, 0, voxel]
    inv = [1 / voxel if m else 0 for m in mat]
    grid_map = struct.pack("<9f9f3ff9d9d3dd", *mat, *inv, *translation, 1, *mat, *inv, *translation, 1)
    grid = (struct.pack("<QQIIIIQ", NVDB_MAGIC, 0, NVDB_VERSION, 0x20, 0, 1, size) +
            struct.pack("<256s", name) + grid_map + struct.pack("<6d3d", *([0.0] * 6), voxel, voxel, voxel) +
            struct.pack("<IIqIIQQ", 2, grid_type, 0, 0, 0, 0, 0))
    assert len(grid) == GRID_BYTES, len(grid)
    meta = struct.pack("<QQQQII6d6i3dI4I3IHHI", size, size, 0, 512 * len(leaves), grid_type, 2,
                       *([0.0] * 6), *bbox[0], *bbox[1], voxel, voxel, voxel, len(name) + 1,
                       len(leaves), len(lowers), 0, 1, 0, 0, len(root_tiles), codec, 0, NVDB_VERSION)
    header = struct.pack("<QIHH", NVDB_MAGIC, NVDB_VERSION, 1, codec)
    return header + meta + name + b"\0" + grid + body


def patched(data, offset, fmt, *values):
    out = bytearray(data)
    struct.pack_into(fmt, out, offset, *values)
    return bytes(out)


def nvdb_cases(rng):
    ramp = [0.001 * n for n in range(512)]
    good = nvdb(leaves=[leaf((0, 0, 0), ramp)])
    grid_at = 16 + 176 + len(b"density") + 1
    tree_at = grid_at + GRID_BYTES
    root_at = tree_at + TREE_BYTES
    leaf_at = tree_at + struct.unpack_from("<Q", good, tree_at)[0]
    volume_case("nvdb-valid-leaf", "x.nvdb", good, "ok")
    volume_case("nvdb-valid-named", "x.nvdb", good, "ok", grid_name="density")
    volume_case("nvdb-valid-empty-tree", "x.nvdb", nvdb(bbox=((0, 0, 0), (3, 3, 3))), "ok")
    # No nodes at a level: its offset is never used (fuzz_volume found it added to a pointer).
    empty = nvdb(bbox=((0, 0, 0), (3, 3, 3)))
    volume_case("nvdb-valid-unused-offsets", "x.nvdb",
                patched(empty, 16 + 176 + 8 + GRID_BYTES, "<3Q", 2 ** 63, 2 ** 63 + 32, 2 ** 64 - 32), "ok")
    volume_case("nvdb-valid-lower-tiles", "x.nvdb",
                nvdb(lowers=[lower((0, 0, 0), {0: 1.0, 17: 0.5, 4095: 2.0})], bbox=((0, 0, 0), (127, 127, 127))),
                "ok")
    volume_case("nvdb-valid-root-tile", "x.nvdb",
                nvdb(root_tiles=[((0, 0, 0), 1, 0.25)], bbox=((0, 0, 0), (15, 15, 15))), "ok")
    volume_case("nvdb-valid-far-leaf", "x.nvdb", nvdb(leaves=[leaf((-2 ** 31, 2 ** 31 - 8, 0), ramp)]), "ok")
    volume_case("nvdb-name-absent", "x.nvdb", good, "error", grid_name="smoke")
    volume_case("nvdb-double-grid", "x.nvdb", nvdb(leaves=[leaf((0, 0, 0), ramp)], grid_type=2), "error")
    volume_case("nvdb-empty-file", "x.nvdb", b"", "error")
    for k in range(16):
        volume_case("nvdb-truncated-%d" % k, "x.nvdb", good[:len(good) * k // 16], "error")
    header_patches = [("magic", 0, "<Q", NVDB_MAGIC ^ 1), ("magic-swapped", 0, ">Q", NVDB_MAGIC),
                      ("version", 8, "<I", 31 << 21), ("codec-zip", 14, "<H", 1), ("codec-blosc", 14, "<H", 2),
                      ("codec-7", 14, "<H", 7), ("grid-count-0", 12, "<H", 0), ("grid-count-max", 12, "<H", 65535),
                      ("meta-grid-size", 16, "<Q", 2 ** 63), ("meta-file-size", 24, "<Q", 7),
                      ("meta-name-size-0", 16 + 136, "<I", 0), ("meta-name-size-huge", 16 + 136, "<I", 2 ** 32 - 1),
                      ("grid-magic", grid_at, "<Q", 0), ("grid-version", grid_at + 16, "<I", 33 << 21),
                      ("grid-size", grid_at + 32, "<Q", 1), ("grid-type-vec3f", grid_at + 636, "<I", 6),
                      ("grid-type-huge", grid_at + 636, "<I", 2 ** 32 - 1),
                      ("map-zero", grid_at + 296 + 88, "<9d", *([0.0] * 9)),
                      ("map-nan", grid_at + 296 + 88, "<d", float("nan")),
                      ("map-huge", grid_at + 296 + 88, "<9d", 1e300, 0, 0, 0, 1e300, 0, 0, 0, 1e300),
                      ("translation-inf", grid_at + 296 + 88 + 144, "<d", float("inf")),
                      ("leaf-count-huge", tree_at + 32, "<I", 2 ** 32 - 1), ("leaf-count-2", tree_at + 32, "<I", 2),
                      ("leaf-offset-misaligned", tree_at, "<Q", struct.unpack_from("<Q", good, tree_at)[0] + 4),
                      ("leaf-offset-huge", tree_at, "<Q", 2 ** 64 - 32), ("leaf-offset-0", tree_at, "<Q", 0),
                      ("lower-count", tree_at + 36, "<I", 1), ("upper-count", tree_at + 40, "<I", 3),
                      ("root-offset-huge", tree_at + 24, "<Q", 2 ** 63), ("root-offset-misaligned", tree_at + 24, "<Q", 65),
                      ("root-table-huge", root_at + 24, "<I", 2 ** 32 - 1), ("root-table-1", root_at + 24, "<I", 1),
                      ("bbox-huge", root_at, "<6i", -2 ** 31, -2 ** 31, -2 ** 31, 2 ** 31 - 1, 2 ** 31 - 1, 2 ** 31 - 1),
                      ("bbox-empty", root_at, "<6i", 5, 5, 5, 4, 4, 4),
                      ("bbox-thin", root_at, "<6i", 0, 0, 0, 0, 0, 2 ** 30),
                      ("bbox-2-31", root_at, "<6i", 0, 0, 0, 2 ** 16, 2 ** 15, 0),
                      ("leaf-value-nan", leaf_at + 96 + 4 * 77, "<f", float("nan")),
                      ("leaf-value-negative", leaf_at + 96 + 4 * 77, "<f", -1.0),
                      ("leaf-value-inf", leaf_at + 96 + 4 * 511, "<f", float("inf")),
                      ("leaf-origin-min", leaf_at, "<3i", -2 ** 31, -2 ** 31, -2 ** 31)]
    for label, offset, fmt, *values in header_patches:
        volume_case("nvdb-" + label, "x.nvdb", patched(good, offset, fmt, *values),
                    "any" if label in ("leaf-offset-0", "root-table-1", "leaf-origin-min") else "error")
    # A grid of 100 bytes that the file holds exactly: too small for its own headers.
    small = patched(patched(good, 16, "<Q", 100), 24, "<Q", 100)[:grid_at + 100]
    volume_case("nvdb-grid-too-small", "x.nvdb", small, "error")
    # Two lower nodes at one origin, every tile active: the tiles overlap (refused, not filled twice).
    every = {n: 0.5 for n in range(4096)}
    volume_case("nvdb-overlapping-tiles", "x.nvdb",
                nvdb(lowers=[lower((0, 0, 0), every), lower((0, 0, 0), every)], bbox=((0, 0, 0), (127, 127, 127))),
                "error")
    # The same active root tile 64 times: overlapping.
    volume_case("nvdb-root-tiles-many", "x.nvdb",
                nvdb(root_tiles=[((0, 0, 0), 1, 1.0)] * 64, bbox=((0, 0, 0), (63, 63, 63))), "error")
    # A finite map whose translation overflows at the box's far minimum.
    far = patched(good, root_at, "<6i", 2 ** 30, 0, 0, 2 ** 30 + 7, 7, 7)
    volume_case("nvdb-map-overflow", "x.nvdb", patched(far, grid_at + 296 + 88, "<d", 1e300), "error")
    for k in range(24):
        data = bytearray(good)
        for _ in range(rng.randint(1, 8)):
            data[rng.randrange(min(len(data), leaf_at + 96))] = rng.randrange(256)
        volume_case("nvdb-random-%d" % k, "x.nvdb", bytes(data), "any")


def volume_cases(rng=None):
    rng = rng or random.Random(20261240)
    vol_cases(rng)
    nvdb_cases(rng)
