#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets into tests/fuzz/corpus/<target>/ (run by hand;
the output is committed). OBJ seeds: the project's OBJ + MTL test data (mtllib renamed to the
fuzz target's m.mtl, the MTL appended after a "#mtl" line) and small statements of every kind.
PNG seeds: the project's PNGs and tiny images in every colour type, bit depth, interlace and
ancillary-chunk form libpng reads, and PPM / PGM. Pipeline seeds: headers covering each strip
height, format, shading, texturing and camera mode (layout in pipeline_target.cpp)."""
import os
import random
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "host", "data")


def out(target, name, data):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def read(name):
    with open(os.path.join(DATA, name), "rb") as f:
        return f.read()


# ---------------------------------------------------------------------------------------------
# OBJ
for obj, mtl in (("cube.obj", "cube.mtl"), ("ground.obj", "ground.mtl")):
    text = read(obj).replace(b"mtllib " + mtl.encode(), b"mtllib m.mtl")
    out("obj", obj, text + b"\n#mtl\n" + read(mtl))
out("obj", "color_sphere.obj", read("color_sphere.obj"))
out("obj", "forms.obj", b"""\xef\xbb\xbf# corner forms, negative indices, polygons\r
v 0 0 0\r
v 1 0 0 1\r
v 1 1 0\r
v 0 1 0\r
vt 0 0\r
vt 1 0 0\r
vt 1 1\r
vn 0 0 1\r
vn 0 0 -1\r
g a\r
s 1\r
f 1 2 3\r
f 1/1 2/2 3/3 4/1\r
f -4//-2 -3//-2 -2//-1\r
fo 1/1/1 2/2/2 \\\r
 3/3/1\r
f 1 1 2\r
l 1 2\r
vp 0.5\r
""")
out("obj", "colors.obj", b"""v 0 0 0 1 0 0
v 1 0 0 0 1 0
v 0 1 0 0 0 1.5
v +1e-400 2e5 -3.25e-3 0.5 0.5 0.5
f 1 2 3
f 2 3 4
""")
out("obj", "materials.obj", b"""mtllib m.mtl
usemtl first
v 0 0 0
v 1 0 0
v 0 1 0
f 1 2 3
usemtl second
f 3 2 1
#mtl
newmtl first
Ka 0.1
Kd 0.2 0.3 0.4
Ks spectral a.rfl
Ke xyz 1 1 1
Ns 500
d -halo 0.5
map_Kd -blendu on -s 1 1 1 -clamp on tex.png
newmtl second
KD 1 1 1
Tr 0.25
illum 2
newmtl first
Kd 0 0 0
""")

# ---------------------------------------------------------------------------------------------
# PNG / PPM


def chunk(kind, body):
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def png(width, height, depth, ctype, rows, interlace=0, extra=b"", plte=None):
    sig = b"\x89PNG\r\n\x1a\n"
    ihdr = struct.pack(">IIBBBBB", width, height, depth, ctype, 0, 0, interlace)
    body = chunk(b"IHDR", ihdr)
    if plte is not None:
        body += chunk(b"PLTE", plte)
    body += extra
    body += chunk(b"IDAT", zlib.compress(rows))
    return sig + body + chunk(b"IEND", b"")


def raw_rows(width, height, bits_per_pixel, filt=0, seed=1):
    rnd = random.Random(seed)
    stride = (width * bits_per_pixel + 7) // 8
    return b"".join(bytes([filt]) + bytes(rnd.randrange(256) for _ in range(stride))
                    for _ in range(height))


out("png", "checker.png", read("checker.png"))
out("png", "tiles64.png", read("tiles64.png"))
channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}
for ctype, depths in ((0, (1, 2, 4, 8, 16)), (2, (8, 16)), (3, (1, 2, 4, 8)), (4, (8, 16)),
                      (6, (8, 16))):
    for depth in depths:
        bpp = channels[ctype] * depth
        plte = bytes(range(48)) if ctype == 3 else None
        w, h = 5, 3
        out("png", f"c{ctype}_d{depth}.png",
            png(w, h, depth, ctype, raw_rows(w, h, bpp, filt=(depth % 5)), plte=plte))
# Interlaced (Adam7: pass rows of their own widths; a 1x1 image has one pass of one row).
out("png", "interlaced_1x1.png", png(1, 1, 8, 2, b"\x00\x10\x20\x30", interlace=1))
out("png", "trns_grey.png", png(2, 2, 8, 0, raw_rows(2, 2, 8), extra=chunk(b"tRNS", b"\x00\x10")))
out("png", "trns_palette.png", png(2, 2, 8, 3, bytes([0, 0, 1, 0, 2, 3]),
                                   plte=bytes(range(12)), extra=chunk(b"tRNS", b"\x00\x80")))
out("png", "gamma_text.png", png(2, 1, 8, 2, raw_rows(2, 1, 24),
                                 extra=chunk(b"gAMA", struct.pack(">I", 45455)) +
                                 chunk(b"tEXt", b"Comment\x00seed")))
out("png", "p6.ppm", b"P6\n# comment\n2 2\n255\n" + bytes(range(12)))
out("png", "p3.ppm", b"P3\n2 1\n65535\n0 1 2 65535 300 7\n")
out("png", "p5.pgm", b"P5 3 1 1000 " + struct.pack(">HHH", 0, 500, 1000))
out("png", "p2.pgm", b"P2\n1 2\n15\n3\n15\n")

# ---------------------------------------------------------------------------------------------
# Pipeline (header layout in pipeline_target.cpp)


def pipeline(seed, b2, b3, b4, b5, b6, b7, nv, nt, nsv, nst, b12=0, small=(0, 0, 0)):
    rnd = random.Random(seed)
    header = bytes([rnd.randrange(128), rnd.randrange(128), b2, b3, b4, b5, b6, b7, nv, nt, nsv,
                    nst, b12, *small])
    body = bytearray()
    if b4 & 1:
        tw, th = 1 + (b5 >> 2 & 7), 1 + (b5 >> 5)
        body += bytes(rnd.randrange(256) for _ in range(3 * tw * th))
    body += bytes(rnd.randrange(256) for _ in range(17))  # material, global ambient
    for _ in range((b6 & 7) % 5):
        body += struct.pack("<hhh", *(rnd.randrange(-300, 300) for _ in range(3)))
        body += bytes(rnd.randrange(256) for _ in range(9))
    cam = (b6 >> 4) & 3
    if cam == 1:
        body += bytes([60]) + struct.pack("<HH", 6554, 20000)
        body += struct.pack("<hhh", 0, 0, 5 * 256) + struct.pack("<hhh", 0, 0, 0)
        body += b"".join(struct.pack("<i", (1 << 16) if i % 5 == 0 else 0) for i in range(16))
    elif cam >= 2:
        for m in range(3):
            body += b"".join(struct.pack("<i", rnd.randrange(-1 << 17, 1 << 17)) for _ in range(16))
        body += struct.pack("<iii", 0, 0, 5 << 16)
    for _ in range(nv):
        body += struct.pack("<iii", *(rnd.randrange(-1 << 31, 1 << 31) for _ in range(3)))
        body += struct.pack("<hhh", *(rnd.randrange(-16384, 16385) for _ in range(3)))
        body += bytes(rnd.randrange(256) for _ in range(3))
        body += struct.pack("<ii", rnd.randrange(-1 << 21, 1 << 21), rnd.randrange(-1 << 21, 1 << 21))
    body += bytes(rnd.randrange(nv + 2) for _ in range(3 * nt))
    for _ in range(nsv):
        body += struct.pack("<ii", rnd.randrange(-20, 150) << 16, rnd.randrange(-20, 150) << 16)
        body += struct.pack("<II", rnd.randrange(0, 65535 << 16), rnd.randrange(0, 1 << 18))
        body += struct.pack("<ii", rnd.randrange(-1 << 21, 1 << 21), rnd.randrange(-1 << 21, 1 << 21))
        body += bytes(rnd.randrange(256) for _ in range(6))
    body += bytes(rnd.randrange(nsv + 2) for _ in range(3 * nst))
    return header + bytes(body)


seeds = [
    # name, b2 (K, format, depth sink, small), b3 (state), b4 (texture), b5, b6, b7 (uvs, shift)
    ("flat_unlit_k8", 1, 0b00000100, 0, 0, 0b00000000, 15 << 1, 12, 16, 0, 0),
    ("gouraud_lit_k1_rgb888", 0 | 4 | 8, 0b00000111, 0, 0, 0b01010010, 16 << 1, 16, 24, 0, 0),
    ("textured_exact_k32", 2, 0b00001101, 0b00100011, 0b11111100, 0b01010001, 1 | 14 << 1, 12, 12, 0, 0),
    ("textured_span_mip", 1 | 4, 0b00100101, 0b10010111, 0b01101101, 0b11010011, 1 | 16 << 1, 10, 12, 0, 0),
    ("textured_affine_palette", 2, 0b10000100, 0b01001001, 0b00100111, 0b00100001, 1 | 17 << 1, 9, 9, 0, 0),
    ("screen_only", 1, 0b00000101, 0, 0, 0, 0, 0, 0, 12, 10),
    ("screen_textured", 0, 0b01000101, 0b00101001, 0b10010010, 0, 0, 0, 0, 10, 8),
    ("raw_matrices", 1 | 8, 0b00010011, 0, 0, 0b11100011, 18 << 1, 16, 20, 6, 4),
]
for i, (name, b2, b3, b4, b5, b6, b7, nv, nt, nsv, nst) in enumerate(seeds):
    out("pipeline", name, pipeline(i + 1, b2, b3, b4, b5, b6, b7, nv, nt, nsv, nst, b12=8))
out("pipeline", "small_stores", pipeline(99, 1 | 16, 0b00000101, 0, 0, 0, 15 << 1, 20, 30, 6, 6,
                                         b12=16 | 8, small=(9, 0x85, 2)))
