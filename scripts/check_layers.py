#!/usr/bin/env python3
"""Checks that the include graph of core/ and hal/ follows the pipeline.

Rules (each violation is printed as file:line, and the exit status is 1):
  1. core/ is one folder per pipeline stage, in the order of STAGES below: a file may include
     its own folder and earlier folders only, so every arrow points down the pipeline (or to
     shared math and records). Every file of core/ is in a folder of STAGES.
  2. Nothing in core/ includes hal/, host_sim/, firmware/ or tests/: the renderer's output port
     is core's own (core/output/strip_sink.hpp); hal implements it.
  3. hal/ outside its host-only folders (HOST_HAL) includes only core/ and hal/ (the MCU side
     builds for bare metal next to the core), never a host-only folder.
Includes of the library are written with the project prefix ("lineraster/core/math/fixed.hpp":
the include view of cmake/include_view.cmake maps lineraster/<part> to the repository's <part>);
others from the repository root; a quoted include that is neither is resolved against the
including file's folder, and reported when it resolves nowhere.

  python3 scripts/check_layers.py            check (CTest: Layers.IncludesPointDownThePipeline)
  python3 scripts/check_layers.py --matrix   also print the folder-by-folder include counts as a
                                             markdown table (rows include columns)
"""

import argparse
import os
import re
import sys

# The pipeline order of core/'s folders, first to last. Move a name to change the order.
STAGES = [
    "math",
    "output",
    "texture",
    "scene",
    "lighting",
    "vertex",
    "binning",
    "setup",
    "span",
    "raster",
]

# The core's umbrella header (<lineraster/lineraster.hpp>): the one file of core/ outside a stage.
UMBRELLA = "core/lineraster.hpp"

# Folders core/ must never include.
OUTSIDE_CORE = ("hal", "host_sim", "firmware", "tests")

# hal/'s host-only backends (heap, threads, exceptions, OS libraries): rule 3 does not apply
# to them, and the MCU side of hal/ must not include them.
HOST_HAL = ("hal/host", "hal/linux", "hal/usb")

# The prefix of the library's public include paths (<lineraster/core/...>).
PREFIX = "lineraster/"

SOURCE_SUFFIXES = (".h", ".hpp", ".c", ".cc", ".cpp", ".inc", ".ipp")
INCLUDE_RE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def sources(root, top):
    """Repository-relative paths of the C/C++ files under root/top, sorted."""
    found = []
    for dirpath, dirnames, filenames in os.walk(os.path.join(root, top)):
        dirnames.sort()
        for name in filenames:
            if name.endswith(SOURCE_SUFFIXES):
                found.append(os.path.relpath(os.path.join(dirpath, name), root))
    return sorted(found)


def includes(root, path):
    """(line number, repository-relative target or None, as written) of each quoted include."""
    out = []
    with open(os.path.join(root, path), encoding="utf-8", errors="replace") as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE_RE.match(line)
            if not m:
                continue
            written = m.group(1)
            if written.startswith(PREFIX):
                written = written[len(PREFIX):]
            if os.path.exists(os.path.join(root, written)):
                out.append((number, os.path.normpath(written), written))
                continue
            local = os.path.normpath(os.path.join(os.path.dirname(path), written))
            out.append((number, local if os.path.exists(os.path.join(root, local)) else None,
                        written))
    return out


def is_host_hal(path):
    return any(path == h or path.startswith(h + "/") for h in HOST_HAL)


def folder(path):
    """The matrix's name for a file's folder: core/<stage>, hal, hal (host), or the top folder."""
    parts = path.split("/")
    if parts[0] == "core":
        return "core/" + parts[1] if len(parts) > 2 else "core"
    if parts[0] == "hal":
        return "hal (host)" if is_host_hal(path) else "hal"
    return parts[0]


def check(root):
    """Returns (violations, matrix counts {(from, to): n})."""
    problems = []
    counts = {}
    for path in sources(root, "core"):
        parts = path.split("/")
        stage = parts[1] if len(parts) > 2 else None
        if path == UMBRELLA:
            stage = STAGES[-1]  # it includes every stage, as the last one may
        elif stage not in STAGES:
            problems.append(f"{path}: not in a stage folder of core/ (scripts/check_layers.py "
                            f"STAGES: {', '.join(STAGES)})")
            stage = None
        for number, target, written in includes(root, path):
            where = f"{path}:{number}"
            if target is None:
                problems.append(f'{where}: #include "{written}" resolves to no file (write '
                                f"includes from the repository root)")
                continue
            counts[(folder(path), folder(target))] = counts.get((folder(path), folder(target)),
                                                                0) + 1
            top = target.split("/")[0]
            if top in OUTSIDE_CORE:
                problems.append(f"{where}: includes {target}: core/ must not include {top}/")
                continue
            if top != "core" or stage is None:
                continue
            tparts = target.split("/")
            tstage = tparts[1] if len(tparts) > 2 else None
            if tstage not in STAGES:
                problems.append(f"{where}: includes {target}, which is in no stage folder")
            elif STAGES.index(tstage) > STAGES.index(stage):
                allowed = ", ".join(STAGES[: STAGES.index(stage) + 1])
                problems.append(f"{where}: includes {target}: {stage} comes before {tstage} in "
                                f"the pipeline (core/{stage} may include: {allowed})")
    for path in sources(root, "hal"):
        host = is_host_hal(path)
        for number, target, written in includes(root, path):
            where = f"{path}:{number}"
            if target is None:
                if not host:
                    problems.append(f'{where}: #include "{written}" resolves to no file (write '
                                    f"includes from the repository root)")
                continue
            counts[(folder(path), folder(target))] = counts.get((folder(path), folder(target)),
                                                                0) + 1
            if host:
                continue
            top = target.split("/")[0]
            if top not in ("core", "hal"):
                problems.append(f"{where}: includes {target}: hal/ (MCU side) includes only "
                                f"core/ and hal/")
            elif is_host_hal(target):
                problems.append(f"{where}: includes {target}: the MCU side of hal/ must not "
                                f"include a host-only backend")
    return problems, counts


def matrix(counts):
    """Markdown table: one row per including folder, one column per included folder."""
    order = ["core/" + s for s in STAGES] + ["core", "hal", "hal (host)"]
    names = sorted({a for a, _ in counts} | {b for _, b in counts},
                   key=lambda n: (order.index(n) if n in order else len(order), n))
    rows = [a for a in names if any(k[0] == a for k in counts)]

    def cell(a, b):
        n = counts.get((a, b), 0)
        if not n:
            return "."
        backwards = (a.startswith("core/") and b.startswith("core/") and a[5:] in STAGES
                     and b[5:] in STAGES and STAGES.index(b[5:]) > STAGES.index(a[5:]))
        wrong = a.startswith("core") and not b.startswith("core")
        return f"**{n}**" if backwards or wrong else str(n)

    short = [n.replace("core/", "") for n in names]
    lines = ["| includes → | " + " | ".join(short) + " |",
             "|---|" + "---:|" * len(names)]
    for a in rows:
        lines.append(f"| {a} | " + " | ".join(cell(a, b) for b in names) + " |")
    lines.append("")
    lines.append("Counts of #include lines from the row's folder to the column's; bold: against "
                 "the rules (an arrow back up the pipeline, or out of core/).")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--matrix", action="store_true",
                        help="print the folder-by-folder include counts as a markdown table")
    parser.add_argument("--root", default=os.path.join(os.path.dirname(__file__), ".."),
                        help="repository root (default: this script's parent folder)")
    args = parser.parse_args()
    root = os.path.abspath(args.root)
    problems, counts = check(root)
    if args.matrix:
        print(matrix(counts))
        print()
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check_layers: FAIL: {len(problems)} include(s) against the pipeline order "
              f"({' < '.join(STAGES)})", file=sys.stderr)
        return 1
    print(f"check_layers: PASS: the includes of core/ and hal/ point down the pipeline "
          f"({' < '.join(STAGES)})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
