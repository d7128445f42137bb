#!/usr/bin/env python3
"""Puts 8-bit RGB PNGs of equal height side by side (4 white columns between): README images.
Usage: side_by_side.py OUT.png IN1.png IN2.png [...]. Only the standard library (zlib)."""
import struct
import sys
import zlib


def read_png(path):
    data = open(path, "rb").read()
    pos, idat = 8, b""
    while pos < len(data):
        length = struct.unpack(">I", data[pos:pos + 4])[0]
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            if depth != 8 or colour != 2:
                sys.exit(f"{path}: only 8-bit RGB PNGs")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, stride, rows, prev, p = zlib.decompress(idat), width * 3, [], bytearray(width * 3), 0
    for _ in range(height):
        filt, line = raw[p], bytearray(raw[p + 1:p + 1 + stride])
        p += 1 + stride
        for x in range(stride):
            a = line[x - 3] if x >= 3 else 0
            b, c = prev[x], prev[x - 3] if x >= 3 else 0
            if filt == 1:
                line[x] = (line[x] + a) & 255
            elif filt == 2:
                line[x] = (line[x] + b) & 255
            elif filt == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif filt == 4:
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, rows


def write_png(path, width, height, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\x00" + r for r in rows)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


images = [read_png(p) for p in sys.argv[2:]]
height = images[0][1]
if any(h != height for _, h, _ in images):
    sys.exit("side_by_side: images differ in height")
gap = bytes([255, 255, 255]) * 4
rows = [gap.join(img[2][y] for img in images) for y in range(height)]
write_png(sys.argv[1], sum(w for w, _, _ in images) + 4 * (len(images) - 1), height, rows)
