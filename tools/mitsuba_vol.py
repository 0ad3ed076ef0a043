# SPDX-License-Identifier: MIT
"""Mitsuba 3's `.vol` grid format, written with plain Python (tools/make_media_scenes.py makes the
test scenes' grids with it; tools/mitsuba_media_conventions.py its probes).

  bytes 0-2   'VOL', byte 3 the version (3)
  int32       encoding (1 = float32)
  int32 x3    resolution x, y, z
  int32       channels
  float32 x6  bounding box: x, y, z min, then x, y, z max (Mitsuba's use_grid_bbox; DESIGN's box)
  float32     values, x fastest, then y, then z, channels interleaved: ((z * ny + y) * nx + x) * c + k
All little-endian.
"""
import struct


def write_vol(path, resolution, bbox_min, bbox_max, values, channels=1):
    """values: a flat sequence in the file's order (x fastest)."""
    nx, ny, nz = resolution
    if len(values) != nx * ny * nz * channels:
        raise ValueError(f"{path}: {len(values)} values for a {nx}x{ny}x{nz}x{channels} grid")
    with open(path, "wb") as f:
        f.write(b"VOL" + bytes([3]))
        f.write(struct.pack("<5i", 1, nx, ny, nz, channels))
        f.write(struct.pack("<6f", *bbox_min, *bbox_max))
        f.write(struct.pack(f"<{len(values)}f", *values))


def read_vol(path):
    """(resolution, bbox_min, bbox_max, channels, values) of a float32 .vol file."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:3] != b"VOL" or data[3] != 3:
        raise ValueError(f"{path}: not a version 3 .vol file")
    encoding, nx, ny, nz, channels = struct.unpack_from("<5i", data, 4)
    if encoding != 1:
        raise ValueError(f"{path}: encoding {encoding} is not float32")
    box = struct.unpack_from("<6f", data, 24)
    n = nx * ny * nz * channels
    values = struct.unpack_from(f"<{n}f", data, 48)
    return (nx, ny, nz), box[:3], box[3:], channels, values
