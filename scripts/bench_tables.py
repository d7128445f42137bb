#!/usr/bin/env python3
"""The early-out table and the cost-per-feature table of scripts/bench_cortex_m.sh.

Reads the output of lr_bench under scripts/icount.sh (stdin): "icount: marker ..." lines, two per
case (before and after its measured frame), and one "lr_bench: case NAME checksum X key value ..."
line per case after its markers. Each case's instruction count is the difference of its two
markers. Prints two Markdown tables computed from those counts and the frame statistics the
firmware prints with them (nothing is asserted; a missing case is reported and its row left out).
`scripts/bench_cortex_m.sh --write-docs` puts them in docs/measurements/bench_cortex_m.md.

Early outs (firmware/bench/cases.hpp says which cases go together): each row divides the
difference of two frames by what the early out dropped.
  back-face   knot_gouraud (no culling) - knot_gouraud_cullback, per back face culled
  no pixel    knot_far (24 units) and knot_mid (12 units), each less its *_vertices twin (the
  centre      same draw without triangles: vertex stage, begin_frame, empty strips), solved for
              d (per triangle dropped before setup) and b (per triangle drawn): two equations
              Y = d D + b B, D = triangles dropped (culled_off + culled_zero), B = binned
  off-screen  knot_offscreen less knot_offscreen_vertices, per triangle (all are off-screen)
  depth       quads_near_then_far (the far square drawn last: every pixel of it fails the depth
  before      test) and quads_far_then_near (drawn first: every pixel of it written), each less
  texture     quad_near, per pixel of the far square
  empty strip the frame with no draws, per strip (and per pixel of a 320 x 8 strip)

Cost per feature: for each feature, a pair of cases that differ in it alone, on the knot (about
4,000 small triangles) and on the cube (6 large ones). The two differences give two equations
  delta = p * P + t * T   (P = pixels written, or for the depth test and the base row pixels
                           inside spans; T = triangles binned)
solved for p (instructions per pixel) and t (instructions per triangle; the vertex-stage work of
the feature lands here: the knot has 0.55 vertices per triangle, the cube 2, so a feature that
moves work from triangles to vertices, as Gouraud does against flat shading, can come out
negative per triangle).
"""
import re
import sys


def commas(v):
    return f"{v:,.0f}"


def fmt(v, digits=1):
    if v is None:
        return "-"
    if abs(v) >= 100:
        return f"{v:,.0f}"
    return f"{v:.{digits}f}"


def parse(text):
    counts = []
    cases = []
    for line in text.splitlines():
        if line.startswith("icount: marker "):
            counts.append(int(line.split()[-1]))
        elif line.startswith("lr_bench: case "):
            f = line.split()
            c = {"name": f[2]}
            for k, v in zip(f[3::2], f[4::2]):
                c[k] = int(v, 16) if v.startswith("0x") else int(v)
            cases.append(c)
    if len(counts) != 2 * len(cases):
        sys.exit(f"bench_tables: {len(counts)} markers for {len(cases)} cases")
    by_name = {}
    for i, c in enumerate(cases):
        c["ins"] = counts[2 * i + 1] - counts[2 * i]
        by_name[c["name"]] = c
    return by_name


def early_outs(k):
    rows = []
    missing = []

    def need(*names):
        absent = [n for n in names if n not in k]
        missing.extend(absent)
        return not absent

    if need("knot_gouraud", "knot_gouraud_cullback", "knot_vertices"):
        none, back, v = k["knot_gouraud"], k["knot_gouraud_cullback"], k["knot_vertices"]
        culled = back["culled_back"]
        saved = none["ins"] - back["ins"]
        drawn = (back["ins"] - v["ins"]) / back["binned"]
        rows.append(("back-face culling", "knot_gouraud - knot_gouraud_cullback",
                     f"{commas(culled)} back faces", fmt(saved / culled), fmt(drawn),
                     f"{commas(saved)} ({100 * saved / none['ins']:.0f} %)"))
    if need("knot_far", "knot_far_vertices", "knot_mid", "knot_mid_vertices"):
        eqs = []
        for n in ("knot_far", "knot_mid"):
            c, cv = k[n], k[n + "_vertices"]
            eqs.append((c["culled_off"] + c["culled_zero"], c["binned"], c["ins"] - cv["ins"]))
        (d1, b1, y1), (d2, b2, y2) = eqs
        det = d1 * b2 - d2 * b1
        d = (y1 * b2 - y2 * b1) / det
        b = (d1 * y2 - d2 * y1) / det
        # What the early out saves: a dropped triangle would cost at least a drawn one.
        rows.append(("covers no pixel centre (or zero area)",
                     "knot_far, knot_mid (each less its *_vertices)",
                     f"{commas(d1)} of 4,000 at 24 units, {commas(d2)} at 12",
                     fmt(d), fmt(b), f"~{commas((b - d) * d1)} at 24 units"))
    if need("knot_offscreen", "knot_offscreen_vertices", "knot_gouraud", "knot_vertices"):
        o, ov = k["knot_offscreen"], k["knot_offscreen_vertices"]
        dropped = o["culled_off"] + o["culled_zero"]
        per = (o["ins"] - ov["ins"]) / dropped
        drawn = (k["knot_gouraud"]["ins"] - k["knot_vertices"]["ins"]) / k["knot_gouraud"]["binned"]
        rows.append(("off-screen", "knot_offscreen - knot_offscreen_vertices",
                     f"{commas(dropped)} of {commas(o['triangles'])}", fmt(per),
                     fmt(drawn) + " (knot_gouraud)", f"~{commas((drawn - per) * dropped)}"))
    if need("quad_near", "quads_near_then_far", "quads_far_then_near"):
        q, nf, fn = k["quad_near"], k["quads_near_then_far"], k["quads_far_then_near"]
        far_px = nf["tested"] - q["tested"]
        hidden = (nf["ins"] - q["ins"]) / far_px
        visible = (fn["ins"] - q["ins"]) / far_px
        rows.append(("depth test before the texture (bilinear)",
                     "quads_near_then_far, quads_far_then_near (each less quad_near)",
                     f"{commas(far_px)} hidden pixels", fmt(hidden) + " per pixel",
                     fmt(visible) + " per pixel (visible)",
                     f"{commas(fn['ins'] - nf['ins'])}"))
    if need("empty"):
        e = k["empty"]
        per_strip = e["ins"] / e["strips"]
        rows.append(("empty strip (background only)", "empty (no draws)",
                     f"{e['empty_strips']} empty strips",
                     f"{fmt(per_strip)} per strip ({per_strip / 2560:.2f} per pixel)",
                     "-", "-"))
    out = ["| early out | cases | dropped | instructions per dropped item | per drawn item |"
           " frame saving |", "|---|---|---|---:|---:|---:|"]
    for r in rows:
        out.append("| " + " | ".join(r) + " |")
    if missing:
        out.append(f"\n(missing cases: {', '.join(sorted(set(missing)))})")
    return "\n".join(out)


# (feature, knot pair, cube pair, pixel count): the depth test works on every pixel inside a span
# ("tested"), shading only on those that pass it ("pixels": written).
FEATURES = [
    ("base: flat-lit triangles, depth test, vertex stage (over an empty frame)",
     ("empty", "knot_flat"), ("empty", "cube_flat"), "tested"),
    ("depth test (16-bit, LESS, with write)", ("knot_gouraud_nodepth", "knot_gouraud"),
     ("cube_gouraud_nodepth", "cube_gouraud"), "tested"),
    ("Gouraud (over flat, lit)", ("knot_flat", "knot_gouraud"), ("cube_flat", "cube_gouraud")),
    ("texture nearest, exact perspective, modulated (over Gouraud)",
     ("knot_gouraud", "knot_nearest"), ("cube_gouraud", "cube_nearest")),
    ("bilinear (over nearest)", ("knot_nearest", "knot_bilinear"),
     ("cube_nearest", "cube_bilinear")),
    ("perspective exact (over affine; nearest)", ("knot_nearest_affine", "knot_nearest"),
     ("cube_nearest_affine", "cube_nearest")),
    ("perspective span 16 (over affine; nearest)",
     ("knot_nearest_affine", "knot_nearest_span16"),
     ("cube_nearest_affine", "cube_nearest_span16")),
    ("mipmaps: trilinear (over bilinear, one level)", ("knot_bilinear", "knot_trilinear"),
     ("cube_bilinear", "cube_trilinear")),
    ("Phong exact (over Gouraud)", ("knot_gouraud", "knot_phong"), ("cube_gouraud", "cube_phong")),
    ("Phong, 32-cell lighting table (over Gouraud)", ("knot_gouraud", "knot_phong_table32"),
     ("cube_gouraud", "cube_phong_table32")),
]


def features(k):
    out = ["| feature | knot: base -> with | cube: base -> with | knot delta | cube delta |"
           " per pixel | per triangle |", "|---|---|---|---:|---:|---:|---:|"]
    missing = []
    for what, (kb, kw), (cb, cw), *px in FEATURES:
        PX = px[0] if px else "pixels"
        absent = [n for n in (kb, kw, cb, cw) if n not in k]
        if absent:
            missing.extend(absent)
            continue
        # P and T of the frame with the feature (the pair shares its geometry).
        pk, tk, dk = k[kw][PX], k[kw]["binned"], k[kw]["ins"] - k[kb]["ins"]
        pc, tc, dc = k[cw][PX], k[cw]["binned"], k[cw]["ins"] - k[cb]["ins"]
        det = pk * tc - pc * tk
        p = (dk * tc - dc * tk) / det
        t = (pk * dc - pc * dk) / det
        t = 0.0 if round(t) == 0 else t
        out.append(f"| {what} | {kb} -> {kw} | {cb} -> {cw} | {commas(dk)} | {commas(dc)} |"
                   f" {p:.1f} | {t:,.0f} |")
    if missing:
        out.append(f"\n(missing cases: {', '.join(sorted(set(missing)))})")
    return "\n".join(out)


# Frames drawn in bands (docs/bands.md) against the same frame in one pass: every band and
# every retried band runs the vertex stage and binning of the whole frame again.
BANDS = [("knot_gouraud_cullback", ("knot_bands_1024", "knot_bands_512", "knot_bands_256")),
         ("knot64k_gouraud", ("knot64k_bands_4096", "knot64k_small_stores"))]


def bands(k):
    out = ["| case | triangle store | bands | retried | strips drawn in passes | instructions |"
           " over one pass | per extra band or retry |", "|---|---:|---:|---:|---:|---:|---:|---:|"]
    missing = []
    for base, banded in BANDS:
        if base not in k:
            missing.append(base)
            continue
        b = k[base]
        out.append(f"| {base} | whole frame | {b['bands']} | {b['band_retries']} |"
                   f" {b['strip_passes']} | {commas(b['ins'])} | - | - |")
        for name in banded:
            if name not in k:
                missing.append(name)
                continue
            c = k[name]
            store = name.rsplit("_", 1)[1] if name[-1].isdigit() else "3072 (vertices 3072, active 64)"
            extra = c["ins"] - b["ins"]
            passes = c["bands"] + c["band_retries"] - 1
            per = commas(extra / passes) if passes > 0 else "-"
            out.append(f"| {name} | {store} | {c['bands']} | {c['band_retries']} |"
                       f" {c['strip_passes']} | {commas(c['ins'])} | {commas(extra)} | {per} |")
    if missing:
        out.append(f"\n(missing cases: {', '.join(sorted(set(missing)))})")
    return "\n".join(out)


# Sharing decisions: the case drawn with shared code against the same case with specialised code
# (firmware/bench/cases.hpp), and what the sharing saves in flash (scripts/footprint.sh's
# tex_nearest_shared image against tex_nearest).
SHARING = [
    ("texel fetch through the fetcher, shared span body (over inlined per filter and wrap; RGB565,"
     " exact perspective, no mipmaps, replaced or constant colours)",
     [("cube_nearest", "cube_nearest_shared"), ("cube_bilinear", "cube_bilinear_shared"),
      ("ground_nearest", "ground_nearest_shared"), ("ground_bilinear", "ground_bilinear_shared")]),
]


def sharing(k):
    out = ["| shared code | specialised -> shared | pixels | instructions more | per pixel |"
           " same frame |", "|---|---|---:|---:|---:|---|"]
    missing = []
    for what, pairs in SHARING:
        for base, shared in pairs:
            if base not in k or shared not in k:
                missing.extend(n for n in (base, shared) if n not in k)
                continue
            b, c = k[base], k[shared]
            extra = c["ins"] - b["ins"]
            same = "yes" if b["checksum"] == c["checksum"] else "no (bilinear weights within one step)"
            out.append(f"| {what} | {base} -> {shared} | {commas(b['pixels'])} | {commas(extra)} |"
                       f" {fmt(extra / b['pixels'])} | {same} |")
    if missing:
        out.append(f"\n(missing cases: {', '.join(sorted(set(missing)))})")
    return "\n".join(out)


def main():
    k = parse(sys.stdin.read())
    print("Early outs: instructions of what an early out drops, against what the same item costs"
          " when it is drawn (differences of whole frames; firmware/bench/cases.hpp and"
          " scripts/bench_tables.py say which).")
    print()
    print(early_outs(k))
    print()
    kn = k.get("knot_gouraud")
    cu = k.get("cube_gouraud")
    scenes = ""
    if kn and cu:
        scenes = (f" (knot: {commas(kn['pixels'])} pixels written of {commas(kn['tested'])} in"
                  f" spans, {commas(kn['binned'])} triangles; cube: {commas(cu['pixels'])} pixels,"
                  f" {commas(cu['binned'])} triangles)")
    print("Cost per feature: each feature's extra instructions per pixel and per triangle, from"
          " the frame differences of one pair on the knot and one on the cube" + scenes + ".")
    print()
    print(features(k))
    print()
    print("Bands: the same frames with a triangle store too small for them, drawn band by band"
          " (identical frames; the checksums above agree).")
    print()
    print(bands(k))
    print()
    print("Sharing: what a piece of shared code costs per pixel against its specialised copy"
          " (the flash it saves: docs/measurements/footprint.md, tex_nearest_shared).")
    print()
    print(sharing(k))


if __name__ == "__main__":
    main()
