#!/usr/bin/env python3
"""Quality benchmark report: reads build/release/quality_bench.csv (written by
scripts/quality_bench.sh), writes the Markdown table (same path, .md) and JSON (.json), plots
instructions per frame (x, log) against mean absolute error (y, symlog) with one marker per
(scene, setting) and the Pareto front of each scene marked, and prints the fronts.

Pareto front of a scene: the settings that no other setting of the same scene beats on both
instructions per frame and mean error (lower is better for both; equal on both: the first in
table order stays). Strip height changes RAM and time, not the image: its rows share their
error, so the front keeps the cheapest strip height; RAM is in the table.

With BEFORE.csv (an earlier run's table), each scene's earlier Pareto front is drawn dashed in
grey beside the current one, and the table lists it.

Usage: scripts/plot_quality.py QUALITY_BENCH.csv OUT.png [BEFORE.csv]
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENES = {
    "knot": ("torus knot, gold, 1 light", "#b8860b", "o"),
    "sphere": ("sphere, 4 lights", "#1f77b4", "s"),
    "clipped": ("ground plane through the near plane, unlit", "#2ca02c", "^"),
    "cube": ("textured lit cube", "#d62728", "D"),
    "ground": ("textured ground plane to the horizon", "#9467bd", "v"),
}
INT = ["strip", "pixels", "triangles_binned", "instructions_per_frame", "ram_bytes",
       "texture_bytes", "max_err", "coverage_mismatch", "depth_order_errors"]
FLOAT = ["host_ns_per_frame", "mean_err", "psnr_db", "pct_off_gt1", "pct_off_gt4",
         "pct_off_gt16"]


def load(path):
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            for k in INT:
                r[k] = int(r[k])
            for k in FLOAT:
                r[k] = float(r[k])
            rows.append(r)
    return rows


def setting(r):
    if r["filter"] == "-":
        return f"{r['shading']} {r['perspective']} strip{r['strip']}"
    return f"{r['filter']} {r['perspective']} mip-{r['mip']} {r['format']}"


def pareto(rows):
    best = None
    front = []
    for r in sorted(rows, key=lambda r: (r["instructions_per_frame"], r["mean_err"])):
        if best is None or r["mean_err"] < best:
            front.append(r)
            best = r["mean_err"]
    return front


def sep(n):
    return f"{n:,}"


def markdown(rows, fronts):
    out = [
        "| scene | shading | perspective | strip | filter | mip | format | pixels | instr./frame "
        "| instr./pixel | host µs | RAM B | texture B | max err | mean err | PSNR dB | >1 % | >4 % "
        "| >16 % | coverage | depth order | front |",
        "|---|---|---|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:"
        "|---:|---:|:-:|",
    ]
    for r in rows:
        on = any(r is f for f in fronts[r["scene"]])
        out.append(
            f"| {r['scene']} | {r['shading']} | {r['perspective']} | {r['strip']} | {r['filter']} "
            f"| {r['mip']} | {r['format']} | {sep(r['pixels'])} | {sep(r['instructions_per_frame'])} "
            f"| {r['instructions_per_frame'] / max(r['pixels'], 1):.1f} "
            f"| {r['host_ns_per_frame'] / 1000:.1f} | {sep(r['ram_bytes'])} "
            f"| {sep(r['texture_bytes'])} | {r['max_err']} | {r['mean_err']:.4f} "
            f"| {r['psnr_db']:.2f} | {r['pct_off_gt1']:.3f} | {r['pct_off_gt4']:.3f} "
            f"| {r['pct_off_gt16']:.3f} | {r['coverage_mismatch']} | {r['depth_order_errors']} "
            f"| {'*' if on else ''} |")
    out += [
        "",
        "320x240. Instructions: exact Cortex-M4F instructions of the frame (begin_frame + draws + "
        "render into RGB565 strips and a sink that does no per-pixel work), lr_quality under "
        "QEMU mps2-an386 with the counting plugin; its frames equal the host's. Host time: median of 21 frames. RAM: "
        "vertices, binned and peak active triangles, two colour strips, one depth strip, buckets "
        "and draw records (texture B: the texels the setting reads). Errors per channel (0..255) "
        "against the double reference over the pixels both cover (the reference samples the 8-bit "
        "texture and its 8-bit mip chain); >N %: pixels whose worst channel is off by more than N; "
        "coverage: pixels covered by one renderer only; depth order: pixels where the core's "
        "16-bit depth is outside the reference's depth range over the 3x3 pixels around (+-16). "
        "front: on the scene's Pareto front (instructions vs mean error).",
    ]
    return "\n".join(out) + "\n"


def plot(rows, fronts, png, before=None):
    fig, axes = plt.subplots(2, 3, figsize=(16, 10), dpi=100)
    for ax, (scene, (label, color, marker)) in zip(axes.flat, SCENES.items()):
        pts = [r for r in rows if r["scene"] == scene]
        if not pts:
            continue
        ax.scatter([r["instructions_per_frame"] for r in pts], [r["mean_err"] for r in pts],
                   s=22, marker=marker, facecolors="none", edgecolors=color, alpha=0.5,
                   linewidths=0.8, label="dominated")
        f = fronts[scene]
        xs = [r["instructions_per_frame"] for r in f]
        ys = [r["mean_err"] for r in f]
        ax.step(xs, ys, where="post", color=color, linewidth=1.2, alpha=0.8)
        if before and before.get(scene):
            bx = [r["instructions_per_frame"] for r in before[scene]]
            by = [r["mean_err"] for r in before[scene]]
            ax.step(bx, by, where="post", color="0.45", linestyle="--", linewidth=1.0)
            ax.scatter(bx, by, s=22, marker=marker, color="0.6", zorder=2,
                       label="earlier Pareto front")
        ax.scatter(xs, ys, s=60, marker=marker, color=color, edgecolors="black", linewidths=0.6,
                   zorder=3, label="Pareto front")
        for i, r in enumerate(f, 1):
            ax.annotate(str(i), (r["instructions_per_frame"], r["mean_err"]),
                        textcoords="offset points", xytext=(5, 4), fontsize=8, color="black")
        key = "\n".join(f"{i}  {setting(r)}" for i, r in enumerate(f, 1))
        ax.text(0.98, 0.98, key, transform=ax.transAxes, ha="right", va="top", fontsize=7,
                family="monospace", bbox=dict(facecolor="white", alpha=0.85, edgecolor="0.8"))
        ax.set_xscale("log")
        ax.set_yscale("symlog", linthresh=0.01, linscale=0.6)
        top = max(r["mean_err"] for r in pts)
        ax.set_ylim(-0.001, max(top * 4, 0.05))
        ax.set_title(f"{scene}: {label}", fontsize=10)
        ax.set_xlabel("instructions per frame (Cortex-M4F, QEMU, log)", fontsize=8)
        ax.set_ylabel("mean abs. error vs double reference (0..255, symlog)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="both", alpha=0.25)
        ax.legend(fontsize=7, loc="lower left")
    # Sixth panel: what strip height buys (untextured scenes: RAM against instructions).
    ax = axes.flat[5]
    for scene, (label, color, marker) in SCENES.items():
        pts = [r for r in rows if r["scene"] == scene and r["filter"] == "-"
               and r["shading"] == "gouraud" and r["perspective"] == "exact"]
        if not pts:
            continue
        pts.sort(key=lambda r: r["strip"])
        ax.plot([r["instructions_per_frame"] for r in pts], [r["ram_bytes"] for r in pts],
                marker=marker, color=color, label=f"{scene} (gouraud, exact)")
        for r in pts:
            ax.annotate(f"K={r['strip']}", (r["instructions_per_frame"], r["ram_bytes"]),
                        textcoords="offset points", xytext=(5, 3), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title("strip height K: RAM against instructions (same image)", fontsize=10)
    ax.set_xlabel("instructions per frame (Cortex-M4F, QEMU, log)", fontsize=8)
    ax.set_ylabel("RAM (bytes, log)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7, loc="lower right")
    fig.suptitle("lineraster quality settings, 320x240: cost against error "
                 "(filled = Pareto front of the scene, hollow = dominated)", fontsize=12)
    fig.tight_layout()
    os.makedirs(os.path.dirname(png) or ".", exist_ok=True)
    fig.savefig(png)


def pareto_table(fronts, title="Pareto front per scene (instructions per frame vs mean error):"):
    out = [title, "",
           "| scene | setting | instr./frame | instr./pixel | host µs | RAM B | max err "
           "| mean err | PSNR dB | >4 % | coverage | depth order |",
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for s in SCENES:
        for r in fronts[s]:
            out.append(f"| {s} | {setting(r)} | {sep(r['instructions_per_frame'])} "
                       f"| {r['instructions_per_frame'] / max(r['pixels'], 1):.1f} "
                       f"| {r['host_ns_per_frame'] / 1000:.1f} | {sep(r['ram_bytes'])} "
                       f"| {r['max_err']} | {r['mean_err']:.4f} | {r['psnr_db']:.2f} "
                       f"| {r['pct_off_gt4']:.2f} | {r['coverage_mismatch']} "
                       f"| {r['depth_order_errors']} |")
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: plot_quality.py QUALITY_BENCH.csv OUT.png [BEFORE.csv]")
    path, png = sys.argv[1], sys.argv[2]
    rows = load(path)
    fronts = {s: pareto([r for r in rows if r["scene"] == s]) for s in SCENES}
    before = None
    stem = os.path.splitext(path)[0]
    front_table = pareto_table(fronts)
    if len(sys.argv) == 4:
        old = load(sys.argv[3])
        before = {s: pareto([r for r in old if r["scene"] == s]) for s in SCENES}
        front_table += "\n" + pareto_table(
            before, f"Earlier Pareto front per scene ({os.path.basename(sys.argv[3])}):")
    with open(stem + ".md", "w") as f:
        f.write(markdown(rows, fronts) + "\n" + front_table)
    with open(stem + ".json", "w") as f:
        json.dump([dict(r, pareto=any(r is x for x in fronts[r["scene"]])) for r in rows], f,
                  indent=1)
    plot(rows, fronts, png, before)
    print(f"wrote {stem}.md, {stem}.json, {png}")
    print(front_table)


if __name__ == "__main__":
    main()
