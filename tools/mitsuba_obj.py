# SPDX-License-Identifier: MIT
"""The OBJ/MTL reader of tools/mitsuba_reference.py: a small reader following tinyobjloader's rules,
written without looking at the renderer's loader, in plain Python (no third-party package), so
tools/make_test_scenes.py can use it to check the files it writes.

    load_obj(path)       the triangles as MeshGroup, one per (material, has vt, has vn)
    load_mtl(path)       {name: Material}
    read_png_size(path)  (width, height) of an intact PNG

Every problem raises SceneError naming the file and line.
"""
import os
import struct
import sys
import zlib


class SceneError(Exception):
    pass


# ---- MTL -----------------------------------------------------------------------------------------

class Material:
    def __init__(self, name):
        self.name = name
        # tinyobjloader's defaults.
        self.kd = [0.0, 0.0, 0.0]
        self.ks = [0.0, 0.0, 0.0]
        self.ke = [0.0, 0.0, 0.0]
        self.tf = [0.0, 0.0, 0.0]
        self.ni = 1.0
        self.d = 1.0
        self.illum = 0
        self.map_kd = None  # absolute path
        self.has_kd = False
        self.has_d = False

    @property
    def emissive(self):
        return any(c > 0 for c in self.ke)

    @property
    def kind(self):
        if self.illum in (4, 6, 7) or (self.ni > 1 and self.d < 1):
            return "dielectric"
        if self.illum in (3, 5):
            return "mirror"
        return "diffuse"


def _floats(tokens, path, line_no, n=3):
    try:
        values = [float(t) for t in tokens[:n]]
    except ValueError:
        raise SceneError(f"{path}:{line_no}: bad number in '{' '.join(tokens)}'")
    if not values:
        raise SceneError(f"{path}:{line_no}: missing value")
    while len(values) < n:  # 'Kd 0.5' means grey, as in tinyobjloader
        values.append(values[-1])
    return values


def _statements(path):
    """(line number, keyword, arguments, text after the keyword) for each non-blank line of an OBJ
    or MTL file, comments removed."""
    with open(path, "r", encoding="utf-8", errors="replace") as f:
        for line_no, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if line:
                key, *rest = line.split()
                yield line_no, key, rest, line[len(key):].strip()


def load_mtl(path):
    materials = {}
    m = None
    for line_no, key, rest, tail in _statements(path):
        if key == "newmtl":
            m = Material(tail)
            materials[m.name] = m
            continue
        if m is None:
            continue
        if key == "Kd":
            m.kd = _floats(rest, path, line_no)
            m.has_kd = True
        elif key == "Ks":
            m.ks = _floats(rest, path, line_no)
        elif key == "Ke":
            m.ke = _floats(rest, path, line_no)
        elif key == "Tf":
            m.tf = _floats(rest, path, line_no)
        elif key == "Ni":
            m.ni = _floats(rest, path, line_no, 1)[0]
        elif key == "d":
            m.d = _floats(rest, path, line_no, 1)[0]
            m.has_d = True
        elif key == "Tr":
            if not m.has_d:  # 'd' wins over 'Tr' (tinyobjloader)
                m.d = 1.0 - _floats(rest, path, line_no, 1)[0]
        elif key == "illum":
            try:
                m.illum = int(rest[0])
            except (ValueError, IndexError):
                raise SceneError(f"{path}:{line_no}: bad illum")
        elif key == "map_Kd":
            if not rest:
                raise SceneError(f"{path}:{line_no}: map_Kd without a file")
            # Options (-mm a b, -o u v w, ...) come first; the file name is the last token.
            m.map_kd = os.path.join(os.path.dirname(path), rest[-1])
            if not m.has_kd:  # tinyobjloader: map_Kd without Kd gets Kd 0.6
                m.kd = [0.6, 0.6, 0.6]
    return materials


# ---- OBJ -----------------------------------------------------------------------------------------

class MeshGroup:
    """The triangles of one material (and one normal mode) with their own vertex arrays; corner
    indices are 0-based into positions/texcoords/normals of this group."""

    def __init__(self, material, has_uv, has_normals):
        self.material = material
        self.has_uv = has_uv
        self.has_normals = has_normals
        self.positions, self.texcoords, self.normals = [], [], []
        self.triangles, self.tri_uv, self.tri_normals = [], [], []
        self._remap = ({}, {}, {})

    def _local(self, which, index, source, target):
        remap = self._remap[which]
        if index not in remap:
            remap[index] = len(target)
            target.append(source[index])
        return remap[index]

    def add(self, corners, v, vt, vn):
        self.triangles.append(tuple(self._local(0, c[0], v, self.positions) for c in corners))
        if self.has_uv:
            self.tri_uv.append(tuple(self._local(1, c[1], vt, self.texcoords) for c in corners))
        if self.has_normals:
            self.tri_normals.append(tuple(self._local(2, c[2], vn, self.normals) for c in corners))


def _resolve(token, count, path, line_no, what):
    try:
        i = int(token)
    except ValueError:
        raise SceneError(f"{path}:{line_no}: bad {what} index '{token}'")
    i = i - 1 if i > 0 else count + i  # 1-based, or negative = relative to the end
    if not 0 <= i < count:
        raise SceneError(f"{path}:{line_no}: {what} index {token} out of range")
    return i


def load_obj(path):
    """Returns a list of MeshGroup, one per (material, has vt, has vn) in first-use order."""
    v, vt, vn = [], [], []
    materials = {}
    current = None
    groups = {}
    for line_no, key, rest, tail in _statements(path):
        if key == "v":
            v.append(_floats(rest, path, line_no))
        elif key == "vt":
            vt.append(_floats(rest, path, line_no, 2))
        elif key == "vn":
            vn.append(_floats(rest, path, line_no))
        elif key == "mtllib":
            for name in rest:
                mtl = os.path.join(os.path.dirname(path), name)
                if not os.path.exists(mtl):  # tinyobjloader warns and goes on (the dragon's)
                    print(f"mitsuba_obj: {path}:{line_no}: mtllib {name} not found", file=sys.stderr)
                    continue
                materials.update(load_mtl(mtl))
        elif key == "usemtl":
            name = tail
            if name not in materials:
                raise SceneError(f"{path}:{line_no}: material '{name}' not defined")
            current = materials[name]
        elif key == "f":
            if len(rest) < 3:
                raise SceneError(f"{path}:{line_no}: face with fewer than 3 corners")
            corners = []
            for tok in rest:
                parts = tok.split("/")
                c = [_resolve(parts[0], len(v), path, line_no, "v"), None, None]
                if len(parts) > 1 and parts[1]:
                    c[1] = _resolve(parts[1], len(vt), path, line_no, "vt")
                if len(parts) > 2 and parts[2]:
                    c[2] = _resolve(parts[2], len(vn), path, line_no, "vn")
                corners.append(c)
            has_uv = all(c[1] is not None for c in corners)
            has_n = all(c[2] is not None for c in corners)
            if current is None:
                current = materials.setdefault("", Material(""))  # tinyobjloader's default
            group = groups.setdefault((current.name, has_uv, has_n),
                                      MeshGroup(current, has_uv, has_n))
            for k in range(1, len(corners) - 1):  # fan: the faces here are convex
                group.add((corners[0], corners[k], corners[k + 1]), v, vt, vn)
        # g, o, s, l, p and anything else: no effect on the image
    return list(groups.values())


def read_png_size(path):
    """Checks that path is a PNG whose chunks are intact and whose image data inflates to the
    right size; returns (width, height)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SceneError(f"{path}: not a PNG")
    pos, idat, width = 8, b"", None
    while pos < len(data):
        (length,), kind = struct.unpack(">I", data[pos:pos + 4]), data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        (crc,) = struct.unpack(">I", data[pos + 8 + length:pos + 12 + length])
        if zlib.crc32(kind + body) & 0xFFFFFFFF != crc:
            raise SceneError(f"{path}: bad CRC in {kind!r}")
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour]
    if depth != 8 or len(zlib.decompress(idat)) != height * (1 + width * channels):
        raise SceneError(f"{path}: unexpected PNG layout")
    return width, height
