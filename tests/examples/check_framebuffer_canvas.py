#!/usr/bin/env python3
"""Checks what examples/host/framebuffer_canvas.cpp wrote: a 200x150 binary PPM of its RGB565
canvas and the lines it printed.

  python3 tests/examples/check_framebuffer_canvas.py CANVAS.ppm OUTPUT.txt

The canvas outside the 160x120 viewport at (20, 15) is still the GUI's grey (200, 200, 200) as
RGB565 holds it, (198, 199, 198); the viewport's corners are the clear colour (16, 24, 48) as
RGB565 holds it, (16, 24, 49); its centre is the lit teal cube (blue and green above red), whose
three visible faces are lit differently, and it covers 8-60 % of the viewport. The first frame
copied all 15 strips (160 x 120 x 2 bytes), the second kept them all.
"""
import sys

W, H = 200, 150
X0, Y0, VW, VH = 20, 15, 160, 120
GUI = (198, 199, 198)
CLEAR = (16, 24, 49)
OUTPUT = ["frame 0: 15 strips drawn, 0 kept, 38400 bytes copied",
          "frame 1: 0 strips drawn, 15 kept, 0 bytes copied"]


def main():
    path, log = sys.argv[1], sys.argv[2]
    data = open(path, "rb").read()
    head = data.split(maxsplit=4)
    if head[:4] != [b"P6", str(W).encode(), str(H).encode(), b"255"] or len(head[4]) != W * H * 3:
        print(f"{path}: not a {W}x{H} P6 image", file=sys.stderr)
        return 1
    px = head[4]

    def at(x, y):
        i = 3 * (y * W + x)
        return tuple(px[i:i + 3])

    problems = []
    inside = lambda x, y: X0 <= x < X0 + VW and Y0 <= y < Y0 + VH
    outside_wrong = sum(1 for y in range(H) for x in range(W) if not inside(x, y) and at(x, y) != GUI)
    if outside_wrong:
        problems.append(f"{outside_wrong} pixels outside the viewport are not the GUI's {GUI}")
    for x, y in ((X0, Y0), (X0 + VW - 1, Y0), (X0, Y0 + VH - 1), (X0 + VW - 1, Y0 + VH - 1)):
        if at(x, y) != CLEAR:
            problems.append(f"viewport corner ({x}, {y}) is {at(x, y)}, not the clear colour {CLEAR}")
    r, g, b = at(X0 + VW // 2, Y0 + VH // 2)
    if not (g > r and b > r and g + b > 120):
        problems.append(f"viewport centre is {(r, g, b)}, not lit teal")
    obj = [at(x, y) for y in range(Y0, Y0 + VH) for x in range(X0, X0 + VW) if at(x, y) != CLEAR]
    covered = len(obj) / (VW * VH)
    if not 0.08 <= covered <= 0.60:
        problems.append(f"{covered:.1%} of the viewport is the cube's (expected 8-60 %)")
    # Three faces, each one flat colour apart from its highlight: three colours cover most of it.
    counts = sorted((obj.count(c) for c in set(obj)), reverse=True)
    if len(counts) < 3 or sum(counts[:3]) < len(obj) // 2 or counts[2] < len(obj) // 20:
        problems.append(f"not three differently lit faces (largest colour counts {counts[:4]})")
    lines = [line.strip() for line in open(log) if line.strip()]
    if lines != OUTPUT:
        problems.append(f"{log}: printed {lines}, expected {OUTPUT}")
    for p in problems:
        print(f"{path}: {p}", file=sys.stderr)
    if not problems:
        print(f"{path}: GUI untouched, corners clear, centre {(r, g, b)}, cube {covered:.1%}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
