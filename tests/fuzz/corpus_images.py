# SPDX-License-Identifier: MIT
"""Images for the texture cases, written here so the corpus needs no committed binaries.
"""
import struct
import zlib


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
