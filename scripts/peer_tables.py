#!/usr/bin/env python3
"""The peer-scene tables of scripts/peer_bench.sh (which runs the programs; this only reads their
output): one Markdown table per core from
  RUN      scripts/icount.sh's output for lr_peer (marker lines, "lr_bench: case NAME ..." lines)
  PROFILE  scripts/icount_profile.py --by folder output for the same image (one table per case)
  PSNR     lr_peer_psnr's output (host), or "-" for none

usage: scripts/peer_tables.py CORE RUN PROFILE PSNR

CORE cortex-m4f gets the TGX figures (tests/data/peer/README.md, Cortex-M4F) and the M4F
budgets of the issue "Fast on the chip" beside the counts; other cores get the counts alone.
The stage mapping and the budgets are documented in scripts/peer_bench.sh's header.
"""
import re
import sys

PIXELS = 320 * 240
# TGX's Cortex-M4F instructions per frame (the peer README's first column).
TGX = {"S1": 3.25e6, "S1x": 32.8e6, "S2n": 1.72e6, "S2b": 6.72e6, "S3n": 1.61e6, "S3b": 6.38e6}
# The M4F budgets: per frame, and per stage unit.
BUDGET = {"S1": 1.6e6, "S1x": 16e6, "S2n": 0.86e6, "S2b": 3.3e6, "S3n": 0.70e6, "S3b": 3.1e6}
BUDGET_VERTEX, BUDGET_BIN, BUDGET_CLEARS = 120, 60, 1
BUDGET_SETUP_GOURAUD, BUDGET_SETUP_TEXTURED = 250, 350
STAGES = ["vertex", "bin", "setup", "spans", "strips"]


def stage_of(row):
    """The stage of a --by folder row (scripts/peer_bench.sh's header has the same mapping)."""
    if row in ("core/vertex", "core/lighting"):
        return "vertex"
    if row == "core/binning":
        return "bin"
    if row == "core/setup":
        return "setup"
    if row in ("core/span", "core/texture"):
        return "spans"
    if row in ("core/raster", "core/output", "firmware/common") or re.match(
            r"libc: (memset|memcpy|memmove)$", row):
        return "strips"
    return "other"


def read_run(path):
    """[(name, instructions, {stat: value})] in the order the image ran them."""
    text = open(path, encoding="utf-8").read()
    marks = [int(m) for m in re.findall(r"^icount: marker \S+ lr_bench_marker at (\d+)$", text,
                                        re.M)]
    cases = []
    for j, line in enumerate(re.findall(r"^lr_bench: case (.*)$", text, re.M)):
        words = line.split()
        stats = {words[k]: words[k + 1] for k in range(1, len(words) - 1, 2)}
        cases.append((words[0], marks[2 * j + 1] - marks[2 * j], stats))
    if len(marks) != 2 * len(cases):
        sys.exit(f"peer_tables: {len(marks)} marker lines for {len(cases)} cases in {path}")
    return cases


def read_profile(path):
    """{case: {stage: instructions}, ...} and {case: {folder row: instructions}}."""
    stages, rows, case = {}, {}, None
    for line in open(path, encoding="utf-8"):
        m = re.match(r"^(\S+) \(= its marker difference\): ([\d,]+) instructions", line)
        if m:
            case = m.group(1)
            stages[case] = dict.fromkeys(STAGES + ["other"], 0)
            rows[case] = {}
            continue
        m = re.match(r"^\s+([\d,]+)\s+[\d.]+\s+(.+)$", line)
        if m and case and not line.lstrip().startswith("instructions"):
            n, row = int(m.group(1).replace(",", "")), m.group(2).strip()
            stages[case][stage_of(row)] += n
            rows[case][row] = n
    return stages, rows


def read_psnr(path):
    if path == "-":
        return {}
    out = {}
    for line in open(path, encoding="utf-8"):
        m = re.match(r"^lr_peer_psnr: case (\S+) (.*)$", line)
        if m:
            w = m.group(2).split()
            out[m.group(1)] = {w[k]: w[k + 1] for k in range(0, len(w) - 1, 2)}
    return out


def commas(v):
    return f"{int(round(v)):,}"


def mega(v):
    """Millions from 100,000 on, else the number itself."""
    return f"{v / 1e6:.2f} M" if v >= 1e5 else commas(v)


FOLDERS = ["core/vertex", "core/lighting", "core/binning", "core/setup", "core/span",
           "core/texture", "core/raster", "core/output", "firmware/common", "core/math",
           "core/scene"]


def folder_table(cases, rows):
    """The folder rows the stages are made of: what "other" and the strip column hold."""
    print("| scene | " + " | ".join(FOLDERS) + " | libgcc | rest |")
    print("|---|" + "---:|" * (len(FOLDERS) + 2))
    for name, _, _ in cases:
        r = rows.get(name)
        if r is None:
            continue
        libgcc = sum(n for k, n in r.items() if k.startswith("libgcc: "))
        rest = sum(r.values()) - libgcc - sum(r.get(f, 0) for f in FOLDERS)
        print(f"| {name} | " + " | ".join(mega(r.get(f, 0)) for f in FOLDERS) +
              f" | {mega(libgcc)} | {mega(rest)} |")


def main(argv):
    if len(argv) != 4:
        sys.exit(__doc__.strip().splitlines()[6])
    core, run_path, profile_path, psnr_path = argv
    m4f = core == "cortex-m4f"
    cases = read_run(run_path)
    stages, rows = read_profile(profile_path)
    psnr = read_psnr(psnr_path)
    head = ["scene", "instructions per frame", "est. cycles",
            "vertex (per vertex)", "cull + bin (per input triangle)",
            "setup (per drawn triangle)", "spans (per pixel written)",
            "strip loop + clears (per pixel of the frame)", "other",
            "per pixel written", "per input triangle"]
    if m4f:
        head += ["TGX (M4F)", "ratio to TGX"]
    head += ["PSNR (within 1 level)", "vs Mesa: PSNR, coverage mismatch"]
    print("| " + " | ".join(head) + " |")
    print("|---|" + "---:|" * (len(head) - 3) + "---|---|")
    no_lines = []
    for name, ins, st in cases:
        written, tris = int(st["pixels_written"]), int(st["triangles_in"])
        verts, drawn = int(st["vertices"]), int(st["set_up"])
        textured = name.startswith(("S2", "S3"))

        def cell(value, per, unit, budget=None):
            s = f"{mega(value)} ({commas(value / per) if per else '-'}{unit}"
            if m4f and budget is not None:
                s += f"; budget {budget:,}"
            return s + ")"

        cells = [name, commas(ins) + (f" (budget {mega(BUDGET[name])})" if m4f and name in BUDGET
                                      else ""), "n/a"]
        sg = stages.get(name)
        if sg is None:
            cells += ["-"] * 6
        elif sum(n for k, n in rows[name].items() if k.startswith("other: ")) * 2 > ins:
            no_lines.append(name)
            cells += ["n/a (no line tables)"] * 5 + [commas(sg["other"])]
        else:
            setup_budget = BUDGET_SETUP_TEXTURED if textured else BUDGET_SETUP_GOURAUD
            cells += [cell(sg["vertex"], verts, "/vertex", BUDGET_VERTEX),
                      cell(sg["bin"], tris, "/triangle", BUDGET_BIN),
                      cell(sg["setup"], drawn, "/triangle", setup_budget),
                      cell(sg["spans"], written, "/pixel"),
                      f"{mega(sg['strips'])} ({sg['strips'] / PIXELS:.2f}/pixel"
                      + (f"; budget {BUDGET_CLEARS}" if m4f else "") + ")",
                      mega(sg["other"])]
        cells += [commas(ins / written) if written else "-", commas(ins / tris) if tris else "-"]
        if m4f:
            cells += [mega(TGX[name]), f"{ins / TGX[name]:.2f}"] if name in TGX else ["-", "-"]
        p = psnr.get(name)
        if p:
            same = "" if not textured else (f"; {p['psnr_same_texels']} dB with the RGB565 texels")
            cells.append(f"{p['psnr']} dB ({p['within1']} %){same}")
        else:
            cells.append("-")
        if p and "mesa_psnr565" in p:
            cells.append(f"{p['mesa_psnr565']} dB, {p['mesa_coverage_diff']} px")
        else:
            cells.append("-")
        print("| " + " | ".join(cells) + " |")
    print()
    print("| scene | covered pixels (Mesa: S1 21,756, S2 39,889, S3 38,080) | pixels written | "
          "vertices | triangles in | back faces culled | other culled | drawn (set up) | "
          "binned, no pixel centre (edges only) | spans | checksum |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for name, _, st in cases:
        other_culled = sum(int(st[k]) for k in ("culled_zero", "culled_off", "clipped_away"))
        print(f"| {name} | {commas(int(st['covered']))} | {commas(int(st['pixels_written']))} | "
              f"{commas(int(st['vertices']))} | {commas(int(st['triangles_in']))} | "
              f"{commas(int(st['culled_back']))} | {commas(other_culled)} | "
              f"{commas(int(st['set_up']))} | {commas(int(st['no_pixels']))} | "
              f"{commas(int(st['spans']))} | {st['checksum']} |")
    if rows and not no_lines:
        print()
        folder_table(cases, rows)
    if no_lines:
        sys.stderr.write(f"peer_tables: {core}: no source lines for {', '.join(no_lines)}: "
                         "configure the tree with CXXFLAGS=-g for the stages\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
