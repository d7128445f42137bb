#!/usr/bin/env python3
"""Checks the frame of tests/consumers/asset/textured.cpp against the model's two textures.

The frame: 240x240, the clear colour (16, 24, 48) around a square that covers the pixels whose
centres lie within 120 +- 120 / (2 tan 30 deg) = [16.08, 223.92] on both axes (the square
[-1, 1]^2 seen head-on from z = 2 with a 60 degree field of view). Its left half shows the left
half of LEFT.png, its right half the right half of RIGHT.png (two_textures.obj's uvs: u = 0..1
across the square, v = 0 at its bottom), each texel as it is (nearest, GL_REPLACE).

Every pixel outside the square must be the clear colour, every pixel inside must not; every pixel
whose centre lies at least 0.5 pixel from a texel edge must equal its texel exactly.

  python3 tests/consumers/check_textured.py FRAME.ppm LEFT.png RIGHT.png
"""
import math
import os
import struct
import sys
import zlib

SIZE = 240
CLEAR = (16, 24, 48)
EDGE0 = 120 - 120 / (2 * math.tan(math.radians(30)))
EDGE1 = 240 - EDGE0
MARGIN = 0.5  # pixels from a texel edge, where nearest sampling is unambiguous


def read_png(path):
    """8-bit RGB, non-interlaced PNG (the textures of tests/host/data): rows, top first."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG file")
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        kind, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        pos += 12 + n
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if (depth, colour, interlace) != (8, 2, 0):
                raise ValueError(f"{path}: only 8-bit RGB, non-interlaced PNGs are read here")
        elif kind == b"IDAT":
            idat += body
    raw, stride = zlib.decompress(idat), 3 * width
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - 3] if x >= 3 else 0
            b = prev[x]
            c = prev[x - 3] if x >= 3 else 0
            if kind == 1:
                line[x] = (line[x] + a) & 255
            elif kind == 2:
                line[x] = (line[x] + b) & 255
            elif kind == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[3 * x:3 * x + 3]) for x in range(width)])
        prev = line
    return rows


def main():
    frame_path, left_path, right_path = sys.argv[1:4]
    data = open(frame_path, "rb").read()
    head = data.split(maxsplit=4)
    if head[:4] != [b"P6", str(SIZE).encode(), str(SIZE).encode(), b"255"] or \
            len(head[4]) != SIZE * SIZE * 3:
        print(f"{frame_path}: not a {SIZE}x{SIZE} P6 image", file=sys.stderr)
        return 1
    px = head[4]
    textures = {"left": read_png(left_path), "right": read_png(right_path)}
    problems, checked, seen = [], {"left": 0, "right": 0}, {"left": set(), "right": set()}
    span = EDGE1 - EDGE0
    for y in range(SIZE):
        for x in range(SIZE):
            got = tuple(px[3 * (y * SIZE + x):3 * (y * SIZE + x) + 3])
            cx, cy = x + 0.5, y + 0.5
            if not (EDGE0 < cx < EDGE1 and EDGE0 < cy < EDGE1):
                if got != CLEAR:
                    problems.append(f"({x}, {y}) is {got}, outside the square: not the clear colour")
                continue
            if got == CLEAR:
                problems.append(f"({x}, {y}) is the clear colour, inside the square")
                continue
            s, t = (cx - EDGE0) / span, (cy - EDGE0) / span  # t = 0 at the top
            half = "left" if s < 0.5 else "right"
            rows = textures[half]
            n_s, n_t = len(rows[0]), len(rows)
            us, ut = s * n_s, t * n_t  # in texels
            if min(abs(us - round(us)) * span / n_s, abs(ut - round(ut)) * span / n_t) < MARGIN:
                continue
            want = rows[int(ut)][int(us)]
            checked[half] += 1
            seen[half].add(want)
            if got != want:
                problems.append(f"({x}, {y}) is {got}, not the {half} texture's texel "
                                f"({int(us)}, {int(ut)}) {want}")
    # Both halves drawn, each with its own texture's colours (2 in checker.png, 4 in tiles64.png).
    for half, rows in textures.items():
        colours = {c for row in rows for c in row}
        if checked[half] < 5000 or seen[half] != colours:
            problems.append(f"{half} half: {checked[half]} texels checked, colours {sorted(seen[half])} "
                            f"of {sorted(colours)}")
    for p in problems[:10]:
        print(f"{frame_path}: {p}", file=sys.stderr)
    if len(problems) > 10:
        print(f"{frame_path}: ... {len(problems) - 10} more", file=sys.stderr)
    if not problems:
        print(f"{frame_path}: square at pixels {math.ceil(EDGE0 - 0.5)}..{math.floor(EDGE1 - 0.5)}, "
              f"{checked['left']} pixels equal to their {os.path.basename(left_path)} texel, "
              f"{checked['right']} to their {os.path.basename(right_path)} texel")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
