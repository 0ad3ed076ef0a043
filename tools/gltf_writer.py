# SPDX-License-Identifier: MIT
"""gltf_writer.py: the container side of the glTF test files (tools/make_gltf_tests.py), standard
library only: component types and their normalized decoding, a buffer/view/accessor builder, GLB
packing, base64 data URIs, a buffer declaration per form (.bin, GLB, embedded), and a minimal PNG
encoder for textures."""
import base64
import json
import struct
import zlib


FLOAT, BYTE, UBYTE, SHORT, USHORT, UINT = 5126, 5120, 5121, 5122, 5123, 5125
FMT = {FLOAT: "f", BYTE: "b", UBYTE: "B", SHORT: "h", USHORT: "H", UINT: "I"}
NORM = {BYTE: 127.0, UBYTE: 255.0, SHORT: 32767.0, USHORT: 65535.0}
TYPES = {1: "SCALAR", 2: "VEC2", 3: "VEC3", 4: "VEC4"}


class Builder:
    """Accumulates one binary buffer, its views and accessors."""

    def __init__(self):
        self.bin = bytearray()
        self.views, self.accessors = [], []

    def view(self, data, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            v["byteStride"] = stride
        self.bin += data
        self.views.append(v)
        return len(self.views) - 1

    def accessor(self, values, comps, ctype, normalized=False, view=None, offset=0, count=None):
        """values: flat list of decoded numbers; stored quantized when normalized."""
        if view is None:
            raw = [round(x * NORM[ctype]) if normalized else x for x in values]
            view = self.view(struct.pack("<%d%s" % (len(raw), FMT[ctype]), *raw))
        a = {"bufferView": view, "byteOffset": offset, "componentType": ctype,
             "count": count if count is not None else len(values) // comps, "type": TYPES[comps]}
        if normalized:
            a["normalized"] = True
        if comps == 3 and ctype == FLOAT and view is not None and values:
            a["min"] = [min(values[i::3]) for i in range(3)]
            a["max"] = [max(values[i::3]) for i in range(3)]
        self.accessors.append(a)
        return len(self.accessors) - 1


def decoded(values, ctype, normalized):
    """What a reader gets back from values stored as ctype (the specification's decoding)."""
    if not normalized:
        return list(values)
    n = NORM[ctype]
    return [max(round(x * n) / n, -1.0) for x in values]


def glb(doc, binary):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def data_uri(binary):
    return "data:application/octet-stream;base64," + base64.b64encode(binary).decode()


def with_buffer(doc, uri, size):
    d = json.loads(json.dumps(doc))
    d["buffers"] = [{"byteLength": size} if uri is None else {"uri": uri, "byteLength": size}]
    return d


def write(path, data):
    with open(path, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)


def png(width, height, rgba):
    """A PNG (8-bit RGBA) of the given pixels, with zlib and struct."""
    raw = b"".join(b"\0" + bytes(rgba[4 * width * y:4 * width * (y + 1)]) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))
