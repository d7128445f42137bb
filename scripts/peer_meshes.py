#!/usr/bin/env python3
"""Writes the two peer-scene meshes that are built in code rather than loaded
(tests/data/peer/README.md): tests/data/peer/cube.obj and
tests/data/peer/ground.obj. Their outputs are committed (a few hundred bytes each); run this
again only to change them.

  cube    [-1,1]^3, 24 vertices (4 per face, per-face normals), 12 triangles, counter-clockwise
          seen from outside; the whole texture on each face, upright seen from outside (u to the
          right, v up; for the top and bottom faces "up" is -z and +z).
  ground  the plane y = -1 from z = -1 to z = -256: a trapezoid of two triangles, half width
          0.84875 |z|, texture coordinates s = x / 8 + 32, t = -z / 8; counter-clockwise seen
          from above (+y), normal +y.

usage: scripts/peer_meshes.py [OUT_DIR]   (default tests/data/peer)
"""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))


def num(v):
    """The shortest round-trip form, integers without a decimal point."""
    return str(int(v)) if float(v).is_integer() else repr(float(v))


def obj(comment, positions, uvs, normals, faces):
    lines = [f"# {comment}; written by scripts/peer_meshes.py"]
    lines += ["v " + " ".join(num(c) for c in p) for p in positions]
    lines += ["vt " + " ".join(num(c) for c in t) for t in uvs]
    lines += ["vn " + " ".join(num(c) for c in n) for n in normals]
    lines += ["f " + " ".join(f"{i}/{i}/{i}" for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def cube():
    # Per face: outward normal n, right r and up u with r x u = n.
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    positions, uvs, normals, tris = [], [], [], []
    for n, r, u in faces:
        base = len(positions) + 1
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            positions.append(tuple(n[k] + su * r[k] + sv * u[k] for k in range(3)))
            uvs.append(((su + 1) // 2, (sv + 1) // 2))
            normals.append(n)
        tris += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
    return obj("peer scene S2: cube [-1,1]^3, the whole texture on each face", positions, uvs,
               normals, tris)


def ground():
    near, far, slope = -1.0, -256.0, 0.84875
    corners = [(-slope * -near, near), (slope * -near, near), (slope * -far, far),
               (-slope * -far, far)]
    positions = [(x, -1, z) for x, z in corners]
    uvs = [(x / 8 + 32, -z / 8) for x, z in corners]
    normals = [(0, 1, 0)] * 4
    return obj("peer scene S3: ground plane y = -1, z from -1 to -256, s = x/8 + 32, t = -z/8",
               positions, uvs, normals, [(1, 2, 3), (1, 3, 4)])


def main(argv):
    out = argv[0] if argv else os.path.join(ROOT, "tests", "data", "peer")
    for name, text in (("cube.obj", cube()), ("ground.obj", ground())):
        with open(os.path.join(out, name), "w", encoding="ascii") as f:
            f.write(text)
        print(f"peer_meshes: wrote {os.path.join(out, name)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
