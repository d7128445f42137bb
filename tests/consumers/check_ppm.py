#!/usr/bin/env python3
"""Checks the frame of examples/host/minimal.cpp: a 160x120 binary PPM whose corners are the
clear colour (16, 24, 48) and whose centre is lit gold (red above green above blue, brighter than
the background), and which holds between 8 % and 60 % of object pixels.

  python3 tests/consumers/check_ppm.py FRAME.ppm
"""
import sys

CLEAR = (16, 24, 48)


def main():
    path = sys.argv[1]
    data = open(path, "rb").read()
    head = data.split(maxsplit=4)
    if head[:4] != [b"P6", b"160", b"120", b"255"] or len(head[4]) != 160 * 120 * 3:
        print(f"{path}: not a 160x120 P6 image", file=sys.stderr)
        return 1
    px = head[4]

    def at(x, y):
        i = 3 * (y * 160 + x)
        return tuple(px[i:i + 3])

    problems = []
    for x, y in ((0, 0), (159, 0), (0, 119), (159, 119)):
        if at(x, y) != CLEAR:
            problems.append(f"corner ({x}, {y}) is {at(x, y)}, not the clear colour {CLEAR}")
    r, g, b = at(80, 60)
    if not (r > g > b and r > 64):
        problems.append(f"centre (80, 60) is {(r, g, b)}, not lit gold")
    covered = sum(1 for i in range(0, len(px), 3) if tuple(px[i:i + 3]) != CLEAR) / (160 * 120)
    if not 0.08 <= covered <= 0.60:
        problems.append(f"{covered:.1%} of the pixels are the object's (expected 8-60 %)")
    for p in problems:
        print(f"{path}: {p}", file=sys.stderr)
    if not problems:
        print(f"{path}: corners clear, centre {(r, g, b)}, object {covered:.1%} of the frame")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
